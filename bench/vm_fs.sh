#!/usr/bin/env bash
# How fast the guest of scripts/vm.sh reads the host's files over each shared file system:
# `python -c "import forceskill"` (the checkout's .venv, a few hundred files). Per file system, one
# boot that only starts and one that imports N times; the host CPU seconds (user + sys of qemu,
# and of virtiofsd where used) of the difference, per import, is the figure (the guest's wall
# clock follows the machine's load; the CPU it costs much less). The in-guest wall time of the
# imports (median) is printed beside it.
#   bench/vm_fs.sh [N]      (default 4)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
N="${1:-4}"
OUT=$(mktemp)
trap 'rm -f "$OUT" "$OUT.t"' EXIT
cpu() { # host CPU seconds of one scripts/vm.sh run; its output in $OUT
  /usr/bin/time -f "%U %S" -o "$OUT.t" scripts/vm.sh "$@" >"$OUT"
  awk '{print $1 + $2}' "$OUT.t"
}
for fs in 9p virtiofs; do
  base=$(cpu --fs "$fs" -- true)
  work=$(cpu --fs "$fs" -- bash -c "for i in \$(seq $N); do s=\$(date +%s%N); .venv/bin/python -c 'import forceskill'; echo \$(( (\$(date +%s%N) - s) / 1000000 )); done")
  med=$(sort -n "$OUT" | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]/1000}')
  echo "$fs $base $work $med" | awk -v n="$N" \
    '{printf "%-8s boot %5.1f CPU s   import forceskill: %5.2f host CPU s each (guest wall median %.2f s)\n", $1, $2, ($3 - $2) / n, $4}'
done
