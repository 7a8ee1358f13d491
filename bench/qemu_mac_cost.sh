#!/usr/bin/env bash
# Exact instruction counts of the authenticated frames' operations on the Cortex-M images under
# qemu (one instruction per translation block, the counter of bench/qemu_tick.sh):
#   bench/qemu_mac_cost.sh [cortex-m4f] [cortex-m3]     (default: both; images in build/TARGET)
# builds cm_mac_cost (firmware/ports/cortex-m/mac_cost.c) and prints one line per operation:
#   mac_cost target=T op=verify_ok|verify_bad|protect|set_key|hmac_oneshot instructions=N
#   mac_cost target=T op=hmac_slice_max instructions=N slices=K   (8 SHA-256 rounds a call)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
PY=${PYTHON:-$ROOT/.venv/bin/python}
TARGETS=("$@")
[ ${#TARGETS[@]} -gt 0 ] || TARGETS=(cortex-m4f cortex-m3)
OPS=(verify_ok verify_bad protect set_key hmac_oneshot)
source "$ROOT/bench/qemu/one_insn.sh"   # ONE_INSN: qemu-system-arm's one instruction per block
WORK=$(mktemp -d "${TMPDIR:-/tmp}/qemu_mac.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
status=0
for t in "${TARGETS[@]}"; do
  case $t in
    cortex-m4f) MACHINE=mps2-an386; CPU=cortex-m4 ;;
    cortex-m3) MACHINE=mps2-an385; CPU=cortex-m3 ;;
    *) echo "usage: $0 [cortex-m4f] [cortex-m3]" >&2; exit 2 ;;
  esac
  BUILD=$ROOT/build/$t
  cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$ROOT/cmake/arm-none-eabi.cmake" \
        -DFS_CORTEX_TARGET="$t" -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE="$PY" >/dev/null
  cmake --build "$BUILD" --target cm_mac_cost -j 2 >/dev/null
  rm -f "$WORK/fifo"; mkfifo "$WORK/fifo"
  awk '/ cm_port_mark_begin$/ { inb = 1; c = 0; next }
       / cm_port_mark_end$/   { if (inb) print c; inb = 0; next }
       { if (inb) c++ }' < "$WORK/fifo" > "$WORK/counts" &
  AWK_PID=$!
  qemu-system-arm -M $MACHINE -cpu $CPU -nographic -monitor none -serial null \
    -semihosting-config enable=on,target=native -kernel "$BUILD/firmware/ports/cortex-m/cm_mac_cost.elf" \
    "${ONE_INSN[@]}" -d exec,nochain -D "$WORK/fifo" > "$WORK/out" 2>&1
  wait $AWK_PID
  grep -q "mac_cost done" "$WORK/out" || { echo "cm_mac_cost FAILED on $t:"; cat "$WORK/out"; status=1; }
  # the counter counts the call of the end marker too (bench/qemu_tick.sh's calibration: +1)
  i=0
  while read -r n; do
    [ $i -lt ${#OPS[@]} ] || break
    echo "mac_cost target=$t op=${OPS[$i]} instructions=$((n - 1))"
    i=$((i + 1))
  done < "$WORK/counts"
  tail -n +$((${#OPS[@]} + 1)) "$WORK/counts" |
    awk -v t="$t" '{ if ($1 - 1 > m) m = $1 - 1; n++ }
                   END { printf "mac_cost target=%s op=hmac_slice_max instructions=%d slices=%d\n", t, m, n }'

done
exit $status
