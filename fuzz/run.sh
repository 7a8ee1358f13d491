#!/usr/bin/env bash
# Build the libFuzzer harnesses with clang (-fsanitize=fuzzer,address,undefined) and run each for
# RUNS executions from its seed corpus (fuzz/corpus/<harness>/, read-only; new inputs go to the
# build directory). Prints one line per harness:
#   fuzz HARNESS runs=N time_s=T exec_per_s=R crashes=C corpus=K
# and exits non-zero if any harness crashed (artifacts in $OUT/artifacts).
# usage: fuzz/run.sh [RUNS=100000] [HARNESS ...]   (default: every harness whose sources exist)
#        FS_FUZZ_SECONDS=S bounds each harness's run time as well (libFuzzer -max_total_time);
#        FS_FUZZ_APP_RUNS overrides RUNS for the whole-application harness (slower per input).
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
        uds)         echo "-I$FW/base -I$FW/proto -I$FW/proto/generated $FW/proto/uds.c $FW/proto/generated/fs_wire.c" ;;
        frames)      echo "-I$FW/base -I$FW/proto -I$FW/proto/generated $FW/proto/generated/fs_dbc.c $FW/proto/e2e.c" ;;
        app)         local d
                     for d in base app control proto proto/generated safety storage security boot core hal ports/host; do
                         printf -- '-I%s ' "$FW/$d"
                     done
                     echo "-DFS_FUZZ_GOLDEN=\"$ROOT/tests/vectors/press_n10_ridge_release.skill\"" \
                          "-DFS_FUZZ_GOLDEN_FW=\"$ROOT/tests/firmware/boot/vectors/golden_host_1.2.3.fwimg\"" \
                          "$FW/app/app.c $FW/app/app_run.c $FW/app/app_sm.c $FW/app/app_uds.c $FW/app/app_state.c $FW/app/app_sec.c $FW/app/app_fw.c $FW/app/slots.c $FW/control/fs_exec.c" \
                          "$FW/proto/generated/fs_dbc.c $FW/proto/generated/fs_wire.c $FW/proto/e2e.c $FW/proto/isotp.c $FW/proto/uds.c" \
                          "$FW/safety/flt.c $FW/safety/lim.c $FW/safety/saf.c $FW/safety/sen.c $FW/safety/wdg.c" \
                          "$FW/storage/nvm.c $FW/storage/fls_ram.c" \
                          "$FW/security/sec_access.c $FW/security/sec_sha256.c $FW/security/sec_aes.c $FW/security/secoc.c" \
                          "$FW/boot/boot.c $FW/boot/boot_image.c $FW/boot/boot_verify.c $FW/boot/boot_fls_window.c $FW/boot/fwu.c $FW/boot/fwu_uds.c" \
                          "$FW/core/dmp.c $FW/core/pfc.c $FW/core/skill.c $FW/core/skill_check.c" \
                          "$FW/ports/host/hal_host.c $FW/ports/host/hal_can_sim.c" ;;
    esac
}
needs_for() {
    case "$1" in
        skill_parse) echo "$FW/core/skill.c" ;;
        nvm_record)  echo "$FW/storage/nvm.c" ;;
        isotp)       echo "$FW/proto/isotp.c" ;;
        uds)         echo "$FW/proto/uds.c" ;;
        frames)      echo "$FW/proto/generated/fs_dbc.c" ;;
        app)         echo "$FW/app/app.c" ;;
    esac
}

HARNESSES=("$@")
if [ ${#HARNESSES[@]} -eq 0 ]; then
    HARNESSES=(skill_parse nvm_record isotp uds frames app)
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
    runs="$RUNS"
    if [ "$h" = app ] && [ -n "${FS_FUZZ_APP_RUNS:-}" ]; then runs="$FS_FUZZ_APP_RUNS"; fi
    limit=()
    if [ -n "${FS_FUZZ_SECONDS:-}" ]; then limit=(-max_total_time="$FS_FUZZ_SECONDS"); fi
    "$OUT/fuzz_$h" -runs="$runs" "${limit[@]}" -seed=1 -max_len=8192 -print_final_stats=1 \
        -artifact_prefix="$OUT/artifacts/$h-" "$work" "$ROOT/fuzz/corpus/$h" >"$log" 2>&1
    rc=$?
    set -e
    end=$(date +%s.%N)
    execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
    # a slow-unit artifact is an input that took over 10 s on a loaded machine: listed, not a
    # crash (a hang is a timeout-* artifact, libFuzzer's -timeout)
    crashes=$(find "$OUT/artifacts" -name "$h-*" ! -name "$h-slow-unit-*" -newermt "@${start%.*}" \
              2>/dev/null | wc -l)
    slow=$(find "$OUT/artifacts" -name "$h-slow-unit-*" -newermt "@${start%.*}" 2>/dev/null | wc -l)
    if [ "$rc" -ne 0 ] && [ "$crashes" -eq 0 ]; then crashes=1; fi
    t=$(echo "$end - $start" | bc)
    rate=$(echo "scale=0; ${execs:-0} / ($t + 0.001)" | bc)
    ncorp=$(find "$work" -type f | wc -l)
    echo "fuzz $h runs=${execs:-0} time_s=$(printf '%.1f' "$t") exec_per_s=$rate crashes=$crashes corpus=$ncorp"
    if [ "$slow" -ne 0 ]; then
        echo "fuzz $h: $slow input(s) over 10 s (slow-unit artifacts in $OUT/artifacts; not crashes)"
    fi
    if [ "$crashes" -ne 0 ]; then
        status=1
        grep -m1 -A12 'ERROR\|runtime error\|deadly signal' "$log" || tail -20 "$log"
    fi
done
exit $status
