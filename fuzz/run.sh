#!/usr/bin/env bash
# Build the libFuzzer harnesses with clang (-fsanitize=fuzzer,address,undefined) and run each for
# RUNS executions from its seed corpus (fuzz/corpus/<harness>/, read-only; new inputs go to the
# build directory). Prints one line per harness:
#   fuzz HARNESS runs=N time_s=T exec_per_s=R crashes=C corpus=K
# and exits non-zero if any harness crashed (artifacts in $OUT/artifacts).
# usage: fuzz/run.sh [RUNS=100000] [HARNESS ...]   (default: every harness whose sources exist)
# env:   FS_FUZZ_BUILD (default build/fuzz), CLANG (default clang), FS_FUZZ_JOBS unused: one core.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
RUNS="${1:-100000}"
shift || true
OUT="${FS_FUZZ_BUILD:-$ROOT/build/fuzz}"
CC="${CLANG:-clang}"
CFLAGS=(-g -O1 -std=c11 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all
        -fno-omit-frame-pointer -Wall -Wextra -Werror)
FW="$ROOT/firmware"

sources_for() {
    case "$1" in
        skill_parse) echo "-I$FW/base -I$FW/core $FW/core/skill.c $FW/core/dmp.c $FW/core/pfc.c" ;;
        nvm_record)  echo "-I$FW/base -I$FW/storage $FW/storage/nvm.c $FW/storage/fls_ram.c" ;;
        isotp)       echo "-I$FW/base -I$FW/proto -I$FW/proto/generated $FW/proto/isotp.c" ;;
        uds)         echo "-I$FW/base -I$FW/proto -I$FW/proto/generated $FW/proto/uds.c" ;;
        frames)      echo "-I$FW/base -I$FW/proto -I$FW/proto/generated $FW/proto/generated/fs_dbc.c $FW/proto/e2e.c" ;;
    esac
}
needs_for() {
    case "$1" in
        skill_parse) echo "$FW/core/skill.c" ;;
        nvm_record)  echo "$FW/storage/nvm.c" ;;
        isotp)       echo "$FW/proto/isotp.c" ;;
        uds)         echo "$FW/proto/uds.c" ;;
        frames)      echo "$FW/proto/generated/fs_dbc.c" ;;
    esac
}

HARNESSES=("$@")
if [ ${#HARNESSES[@]} -eq 0 ]; then
    HARNESSES=(skill_parse nvm_record isotp uds frames)
fi
mkdir -p "$OUT/artifacts"
status=0
for h in "${HARNESSES[@]}"; do
    if [ ! -f "$(needs_for "$h")" ]; then
        echo "fuzz $h skipped: $(needs_for "$h") not present"
        continue
    fi
    # shellcheck disable=SC2046
    "$CC" "${CFLAGS[@]}" -o "$OUT/fuzz_$h" "$ROOT/fuzz/fuzz_$h.c" $(sources_for "$h") -lm
    work="$OUT/corpus/$h"
    mkdir -p "$work"
    log="$OUT/fuzz_$h.log"
    start=$(date +%s.%N)
    set +e
    "$OUT/fuzz_$h" -runs="$RUNS" -seed=1 -max_len=8192 -print_final_stats=1 \
        -artifact_prefix="$OUT/artifacts/$h-" "$work" "$ROOT/fuzz/corpus/$h" >"$log" 2>&1
    rc=$?
    set -e
    end=$(date +%s.%N)
    execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
    crashes=$(find "$OUT/artifacts" -name "$h-*" -newermt "@${start%.*}" 2>/dev/null | wc -l)
    if [ "$rc" -ne 0 ] && [ "$crashes" -eq 0 ]; then crashes=1; fi
    t=$(echo "$end - $start" | bc)
    rate=$(echo "scale=0; ${execs:-0} / ($t + 0.001)" | bc)
    ncorp=$(find "$work" -type f | wc -l)
    echo "fuzz $h runs=${execs:-0} time_s=$(printf '%.1f' "$t") exec_per_s=$rate crashes=$crashes corpus=$ncorp"
    if [ "$crashes" -ne 0 ]; then
        status=1
        grep -m1 -A12 'ERROR\|runtime error\|deadly signal' "$log" || tail -20 "$log"
    fi
done
exit $status
