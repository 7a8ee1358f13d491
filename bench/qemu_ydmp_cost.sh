#!/usr/bin/env bash
# The y DMP's added cost per control tick on the product's Cortex-M images: bench/qemu_tick.sh runs
# the image with two N = 50 skills, engrave_n50_ridge_release (force DMP only) and
# wipe_n50_ridge_release (force and path DMPs, one phase and kernel window), and this prints the
# DMP part of each (dmp_step / dmp_step_xy with their callees, per EXECUTE tick) and
#   added = DMP part (wipe) - DMP part (engrave)      ratio = added / DMP part (engrave)
# per statistic (min, median, max).
#   bench/qemu_ydmp_cost.sh [cortex-m4f] [cortex-m3]     (default: both; the images in build/TARGET)
set -uo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
TARGETS=("$@")
[ ${#TARGETS[@]} -gt 0 ] || TARGETS=(cortex-m4f cortex-m3)
for t in "${TARGETS[@]}"; do
  declare -A C=()
  for sk in engrave_n50_ridge_release wipe_n50_ridge_release; do
    out=$("$ROOT/bench/qemu_tick.sh" "$t" --skill "$ROOT/tests/vectors/$sk.skill" 2>&1)
    line=$(echo "$out" | grep '^dmp_instructions')
    [ -n "$line" ] || { echo "qemu_tick.sh gave no DMP count for $t with $sk:"; echo "$out" | tail -5; exit 1; }
    echo "$line"
    C[$sk]=$(echo "$line" | sed 's/.*min=\([0-9]*\) median=\([0-9]*\) max=\([0-9]*\).*/\1 \2 \3/')
  done
  read -r a1 b1 c1 <<< "${C[engrave_n50_ridge_release]}"; read -r a2 b2 c2 <<< "${C[wipe_n50_ridge_release]}"
  awk -v t="$t" -v a1="$a1" -v b1="$b1" -v c1="$c1" -v a2="$a2" -v b2="$b2" -v c2="$c2" 'BEGIN {
    printf "ydmp_cost target=%s dmp_part min=%d median=%d max=%d added min=%d median=%d max=%d ratio_median=%.1f%% ratio_max=%.1f%%\n",
      t, a1, b1, c1, a2 - a1, b2 - b1, c2 - c1, 100 * (b2 - b1) / b1, 100 * (c2 - c1) / c1 }'
done
