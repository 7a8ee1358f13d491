#!/usr/bin/env bash
# Exact instruction counts of the authenticated frames' operations on the Cortex-M images under
# qemu (the counters of bench/qemu_tick.sh, bench/qemu/one_insn.sh: the plugin, or the
# one-instruction trace when qemu cannot load it, with one line to stderr):
#   bench/qemu_mac_cost.sh [cortex-m4f] [cortex-m3]     (default: both; images in build/TARGET)
# builds cm_mac_cost (firmware/ports/mps2/mac_cost.c) and prints one line per operation:
#   mac_cost target=T op=verify_ok|verify_bad|protect|set_key|hmac_oneshot instructions=N
#   mac_cost target=T op=hmac_slice_max instructions=N slices=K   (8 SHA-256 rounds a call)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
PY=${PYTHON:-$ROOT/.venv/bin/python}
TARGETS=("$@")
[ ${#TARGETS[@]} -gt 0 ] || TARGETS=(cortex-m4f cortex-m3)
OPS=(verify_ok verify_bad protect set_key hmac_oneshot)
source "$ROOT/bench/qemu/one_insn.sh"   # ONE_INSN, TRACE_FILTER, REGION_AWK, plugin_build
WORK=$(mktemp -d "${TMPDIR:-/tmp}/qemu_mac.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
PLUGIN=$WORK/tick_plugin.so
USE_PLUGIN=1   # QEMU_TICK_COUNTER=trace: the trace
[ "${QEMU_TICK_COUNTER:-plugin}" = plugin ] || USE_PLUGIN=0
[ $USE_PLUGIN = 0 ] || plugin_build "$PLUGIN" 2> "$WORK/plugin.err" ||
  { echo "qemu_mac_cost: cannot build the plugin: counting with the one-instruction trace" >&2; USE_PLUGIN=0; }
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
  QEMU=(qemu-system-arm -M $MACHINE -cpu $CPU -nographic -monitor none -serial null
        -semihosting-config enable=on,target=native -kernel "$BUILD/firmware/ports/mps2/cm_mac_cost.elf")
  if [ $USE_PLUGIN = 1 ] && ! "${QEMU[@]}" -plugin "$PLUGIN,mode=count,out=$WORK/counts" > "$WORK/out" 2>&1 &&
     grep -qi "plugin" "$WORK/out"; then
    echo "qemu_mac_cost: qemu cannot load the plugin: counting with the one-instruction trace" >&2
    USE_PLUGIN=0
  fi
  if [ $USE_PLUGIN = 0 ]; then
    rm -f "$WORK/fifo"; mkfifo "$WORK/fifo"
    awk "$TRACE_FILTER" < "$WORK/fifo" | awk "$REGION_AWK" > "$WORK/counts" &
    AWK_PID=$!
    "${QEMU[@]}" "${ONE_INSN[@]}" -d exec,nochain -D "$WORK/fifo" > "$WORK/out" 2>&1
    wait $AWK_PID
  fi
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
