#!/usr/bin/env bash
# The y DMP's added cost per control tick on the Cortex-M images, against the force DMP's part of
# today's tick: bench/qemu_tick.sh on three builds of each target that differ only in
# FS_CM_TICK_DMP (firmware/ports/cortex-m/cm_tick.h: 2 both DMPs, 1 the force DMP alone, 0 no
# DMP), all with the skill tests/vectors/wipe_n50_ridge_release.skill (N = 50, force and path).
#   DMP part   = tick(1) - tick(0)      added = tick(2) - tick(1)      ratio = added / DMP part
# per statistic (min, median, max over the 2000 ticks). The build with no DMP fails
# qemu_tick.sh's f_hat comparison by design (f_hat = f0); only its count is used.
#   bench/qemu_ydmp_cost.sh [cortex-m4f] [cortex-m3]     (default: both; ~2 min per build)
set -uo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
SKILL=$ROOT/tests/vectors/wipe_n50_ridge_release.skill
TARGETS=("$@")
[ ${#TARGETS[@]} -gt 0 ] || TARGETS=(cortex-m4f cortex-m3)
for t in "${TARGETS[@]}"; do
  declare -A C=()
  for m in 2 1 0; do
    B=$ROOT/build/cm-$t-dmp$m
    cmake -S "$ROOT" -B "$B" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$ROOT/cmake/arm-none-eabi.cmake" \
          -DFS_CORTEX_TARGET=$t -DCMAKE_BUILD_TYPE=Release -DFS_BENCH_SKILL="$SKILL" \
          -DFS_CM_TICK_DMP=$m >/dev/null || exit 1
    out=$("$ROOT/bench/qemu_tick.sh" $t --build-dir "$B" 2>&1)
    line=$(echo "$out" | grep '^tick_instructions')
    [ -n "$line" ] || { echo "qemu_tick.sh gave no count for $t FS_CM_TICK_DMP=$m"; exit 1; }
    echo "$line (FS_CM_TICK_DMP=$m)"
    # the product build: both halves against the host build and the golden float64 rollout
    [ $m != 2 ] || echo "$out" | grep -E '^qemu_vs'
    C[$m]=$(echo "$line" | sed 's/.*min=\([0-9]*\) median=\([0-9]*\) max=\([0-9]*\).*/\1 \2 \3/')
  done
  read -r a0 b0 c0 <<< "${C[0]}"; read -r a1 b1 c1 <<< "${C[1]}"; read -r a2 b2 c2 <<< "${C[2]}"
  awk -v t=$t -v a0=$a0 -v b0=$b0 -v c0=$c0 -v a1=$a1 -v b1=$b1 -v c1=$c1 -v a2=$a2 -v b2=$b2 -v c2=$c2 'BEGIN {
    printf "ydmp_cost target=%s dmp_part min=%d median=%d max=%d added min=%d median=%d max=%d ratio_median=%.1f%% ratio_max=%.1f%%\n",
      t, a1 - a0, b1 - b0, c1 - c0, a2 - a1, b2 - b1, c2 - c1, 100 * (b2 - b1) / (b1 - b0), 100 * (c2 - c1) / (c1 - c0) }'
done
