#!/usr/bin/env bash
# The demonstrated band's check: its cost per control tick on the product's Cortex-M images.
# bench/qemu_tick.sh runs its journey (0.5 s of execution) twice with one skill, band_press_n50_ridge
# (N = 50), once with its band resampled to 64 points (the Cortex-M3 image's most; the check's cost
# does not depend on the count) and once with its band taken out (the same kernels),
# and this prints per statistic (min, median, max) over the EXECUTE ticks that stepped the DMP (those
# the check runs in) of the whole app_tick and of the sensor-to-actuator latency
#   band_cost target=T what=app_tick|actuator_latency with= without= added_median= added_max=
# (added = with the band - without). The two journeys differ a little (the larger image's upload,
# a few ticks more or less of execution), so the median's difference is the check's cost in a
# typical tick; the max's, its share of the worst tick, as far as the two worst ticks compare.
#   bench/qemu_band_cost.sh [cortex-m4f] [cortex-m3]     (default: both; the images in build/TARGET)
set -uo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
PY=${PYTHON:-$ROOT/.venv/bin/python}
TARGETS=("$@")
[ ${#TARGETS[@]} -gt 0 ] || TARGETS=(cortex-m4f cortex-m3)
WORK=$(mktemp -d "${TMPDIR:-/tmp}/qemu_band.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
WITH=$WORK/band_press_n50_ridge_band64.skill
WITHOUT=$WORK/band_press_n50_ridge_noband.skill
PYTHONPATH=$ROOT/host "$PY" - "$ROOT/tests/vectors/band_press_n50_ridge.skill" "$WITH" "$WITHOUT" <<'EOF' ||
import dataclasses, sys
import numpy as np
from forceskill.model.skill import Skill
sk = Skill.read(sys.argv[1])
assert sk.band_lo_N is not None and sk.band_hi_N is not None, "the vector has no band"
x, x64 = np.linspace(0.0, 1.0, sk.band_lo_N.size), np.linspace(0.0, 1.0, 64)
lo, hi = np.interp(x64, x, sk.band_lo_N), np.interp(x64, x, sk.band_hi_N)
dataclasses.replace(sk, band_lo_N=lo, band_hi_N=hi, format_version=0).write(sys.argv[2])
dataclasses.replace(sk, band_lo_N=None, band_hi_N=None, format_version=0).write(sys.argv[3])
EOF
  { echo "qemu_band_cost: cannot write the two skills"; exit 1; }
status=0
declare -A L=()
for t in "${TARGETS[@]}"; do
  for which in with without; do
    sk=$WITH; [ $which = with ] || sk=$WITHOUT
    rm -f "$WORK/ticks_$which.txt"
    out=$(QEMU_TICK_KEEP=$WORK/ticks_$which.txt "$ROOT/bench/qemu_tick.sh" "$t" --skill "$sk" --exec-s 0.5 2>&1)
    [ -s "$WORK/ticks_$which.txt" ] || { echo "qemu_tick.sh failed on $t ($which the band):"; echo "$out" | tail -5
                                         status=1; continue 2; }
    # the EXECUTE ticks that stepped the DMP (the check runs in those; not in the end policy's)
    for what in app_tick actuator_latency; do
      col=2; [ $what = app_tick ] || col=7
      L[$t.$which.$what]=$(awk -v c=$col '$1 == "execute" && $4 == 1 { print $c }' "$WORK/ticks_$which.txt" |
        sort -n | awk '{ v[NR] = $1 } END { if (NR) print v[1], v[int((NR + 1) / 2)], v[NR] }')
      [ -n "${L[$t.$which.$what]}" ] || { echo "no stepped EXECUTE tick on $t ($which the band)"; status=1; }
    done
  done
  for what in app_tick actuator_latency; do
    [ -n "${L[$t.with.$what]:-}" ] && [ -n "${L[$t.without.$what]:-}" ] || continue
    read -r a1 b1 c1 <<< "${L[$t.without.$what]}"; read -r a2 b2 c2 <<< "${L[$t.with.$what]}"
    echo "band_cost target=$t what=$what with=$a2/$b2/$c2 without=$a1/$b1/$c1 added_median=$((b2 - b1)) added_max=$((c2 - c1))"
  done
done
exit $status
