#!/usr/bin/env bash
# Static checks: cppcheck over the firmware, and cppcheck's MISRA C:2012 addon over
# firmware/core (plus the safety/storage/security layers for information). Findings are counted
# and printed per folder and per MISRA rule. Exit status: non-zero only if plain cppcheck reports
# an `error`-severity finding (MISRA findings are counted, not fatal).
# usage: tools/static_check.sh [OUTDIR=build-static]
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
OUT="${1:-$ROOT/build-static}"
mkdir -p "$OUT"
cd "$ROOT"
TEMPLATE='{file}:{line}:{severity}:{id}:{message}'
INC=(-I firmware/base -I firmware/core -I firmware/safety -I firmware/storage -I firmware/security
     -I firmware/proto -I firmware/proto/generated
     -UFS_NUM_LAYER)  # the real numeric layer; fs_fixed plugs its header in at build time
fatal=0

echo "== cppcheck $(cppcheck --version | awk '{print $2}') (warning, style, performance, portability)"
for d in core safety storage security proto app boot; do
    [ -d "firmware/$d" ] || continue
    ls firmware/$d/*.c >/dev/null 2>&1 || continue
    log="$OUT/cppcheck_$d.txt"
    cppcheck --std=c11 --enable=warning,style,performance,portability --inline-suppr \
        --suppress=missingIncludeSystem --suppress=unusedFunction --suppress=checkersReport \
        "${INC[@]}" --template="$TEMPLATE" -q firmware/$d/*.c 2>"$log" || true
    n=$(grep -c ':' "$log" || true)
    e=$(grep -c ':error:' "$log" || true)
    printf '  firmware/%-9s findings=%-4s errors=%s\n' "$d" "$n" "$e"
    [ "$e" -eq 0 ] || fatal=1
done

misra() {
    local d="$1" log="$OUT/misra_$1.txt"
    cppcheck --std=c11 --addon=misra --inline-suppr --suppress=missingIncludeSystem \
        --suppress=checkersReport "${INC[@]}" --template="$TEMPLATE" -q firmware/$d/*.c \
        2>"$log" || true
    local n
    n=$(grep -c 'misra-c2012' "$log" || true)
    echo "  firmware/$d: $n MISRA findings"
    grep -o 'misra-c2012-[0-9.]*' "$log" | sort | uniq -c | sort -rn | \
        awk '{printf "      rule %-8s %s\n", substr($2, 13), $1}'
}
echo "== cppcheck --addon=misra (MISRA C:2012; rule texts are not shipped, ids only)"
for d in core safety storage security; do
    [ -d "firmware/$d" ] && misra "$d"
done
echo "logs in $OUT"
exit $fatal
