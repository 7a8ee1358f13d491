# Toolchain file for bare-metal Cortex-M with Debian's gcc-arm-none-eabi + libnewlib-arm-none-eabi.
#   cmake -S . -B build-m4f -DCMAKE_TOOLCHAIN_FILE=cmake/arm-none-eabi.cmake -DFS_CORTEX_TARGET=cortex-m4f
# or use the presets (CMakePresets.json: cortex-m4f, cortex-m3).
# FS_CORTEX_TARGET selects the core and the numeric build:
#   cortex-m4f  -mcpu=cortex-m4 -mfpu=fpv4-sp-d16 -mfloat-abi=hard   float32 core (FS_REAL_FLOAT)
#   cortex-m3   -mcpu=cortex-m3 -mfloat-abi=soft                     fixed-point core (firmware/fixed)
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_ASM_COMPILER arm-none-eabi-gcc)
set(CMAKE_OBJCOPY arm-none-eabi-objcopy CACHE FILEPATH "objcopy")
set(CMAKE_SIZE arm-none-eabi-size CACHE FILEPATH "size")
set(CMAKE_NM arm-none-eabi-nm CACHE FILEPATH "nm")
set(CMAKE_OBJDUMP arm-none-eabi-objdump CACHE FILEPATH "objdump")
# try_compile cannot link a bare-metal executable without our startup code and linker script.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)
set(CMAKE_TRY_COMPILE_PLATFORM_VARIABLES FS_CORTEX_TARGET)

if(NOT FS_CORTEX_TARGET)
  set(FS_CORTEX_TARGET cortex-m4f)
endif()
set(FS_CORTEX_TARGET ${FS_CORTEX_TARGET} CACHE STRING "cortex-m4f (float) or cortex-m3 (fixed)")

if(FS_CORTEX_TARGET STREQUAL "cortex-m4f")
  set(FS_CPU_FLAGS "-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard")
elseif(FS_CORTEX_TARGET STREQUAL "cortex-m3")
  set(FS_CPU_FLAGS "-mcpu=cortex-m3 -mthumb -mfloat-abi=soft")
else()
  message(FATAL_ERROR "FS_CORTEX_TARGET must be cortex-m4f or cortex-m3, not '${FS_CORTEX_TARGET}'")
endif()

# The boards' CAN link is SLCAN over the UART, classic CAN only: frames keep 8 data bytes
# (CAN_FRAME_MAX_LEN, can_frame.h), so the frame queues stay as small as before CAN FD.
# Sections per function/object so the linker drops what the image does not use; stack usage
# per function (.su) and the call graph (.ci) for the worst-case stack report.
set(CMAKE_C_FLAGS_INIT "${FS_CPU_FLAGS} -DCAN_FRAME_MAX_LEN=8u -ffunction-sections -fdata-sections -fstack-usage -fcallgraph-info=su")
set(CMAKE_ASM_FLAGS_INIT "${FS_CPU_FLAGS}")
set(CMAKE_C_FLAGS_RELEASE "-O2 -DNDEBUG" CACHE STRING "Release flags (Cortex-M: -O2)")
set(CMAKE_EXE_LINKER_FLAGS_INIT "${FS_CPU_FLAGS} -nostartfiles --specs=nano.specs -Wl,--gc-sections")

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
