# Generate a C array from a skill image: cmake -DIN=skill -DOUT=file.c -P gen_skill.cmake
file(READ ${IN} hex HEX)
string(LENGTH "${hex}" nhex)
math(EXPR nbytes "${nhex} / 2")
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1u," body "${hex}")
string(REGEX REPLACE "((0x..u,){16})" "\\1\n    " body "${body}")
get_filename_component(name ${IN} NAME)
file(WRITE ${OUT} "/* Generated from ${name} by gen_skill.cmake: do not edit. */\n#include \"cm_bench.h\"\n\nconst uint8_t cm_bench_skill[${nbytes}] = {\n    ${body}\n};\nconst uint32_t cm_bench_skill_len = ${nbytes}u;\n")
