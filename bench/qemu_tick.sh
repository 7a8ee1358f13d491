#!/usr/bin/env bash
# Exact instruction count of the full control tick on Cortex-M under qemu.
#   bench/qemu_tick.sh TARGET [--build-dir DIR] [--host-ref-float EXE] [--host-ref-fixed EXE]
# TARGET: cortex-m4f (float32, mps2-an386) or cortex-m3 (fixed point, mps2-an385).
# 1. builds the images (toolchain cmake/arm-none-eabi.cmake, Release) and the host references;
# 2. checks the counter on cm_count_check (must count exactly 103 per marked region);
# 3. runs cm_bench under qemu with one instruction per translation block and the exec trace
#    streamed through a fifo into awk (the trace is never stored): instructions strictly
#    between the end of cm_bench_mark_begin and the start of cm_bench_mark_end, per tick;
# 4. prints `tick_instructions target=TARGET kernels=N min=A median=B max=C`;
# 5. compares the printed f_hat rollout with the host build (bench/qemu/compare.py);
# 6. runs the 1 kHz SysTick loop image and requires no overrun.
# Exit status 1 if the budget (M4F 1,500, M3 3,000), the comparison or a check fails.
set -euo pipefail

usage() { echo "usage: $0 cortex-m4f|cortex-m3 [--build-dir DIR] [--host-ref-float EXE] [--host-ref-fixed EXE]" >&2; exit 2; }
[ $# -ge 1 ] || usage
TARGET=$1; shift
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=$ROOT/build/$TARGET
HOST_BUILD=$ROOT/build/qemu-host
REF_FLOAT=""
REF_FIXED=""
while [ $# -gt 0 ]; do
  case $1 in
    --build-dir) BUILD=$2; shift 2 ;;
    --host-ref-float) REF_FLOAT=$2; shift 2 ;;
    --host-ref-fixed) REF_FIXED=$2; shift 2 ;;
    *) usage ;;
  esac
done

case $TARGET in
  cortex-m4f) MACHINE=mps2-an386; CPU=cortex-m4; NUMERIC=float; BUDGET=1500 ;;
  cortex-m3)  MACHINE=mps2-an385; CPU=cortex-m3; NUMERIC=fixed; BUDGET=3000 ;;
  *) usage ;;
esac

# One instruction per translation block: -singlestep up to qemu 8.0, then
# -accel tcg,one-insn-per-tb=on (8.1 renamed it; -singlestep was removed in 9.x).
QV=$(qemu-system-arm --version | sed -n 's/.*version \([0-9]*\)\.\([0-9]*\).*/\1 \2/p')
read -r QMAJ QMIN <<< "$QV"
if [ "$QMAJ" -gt 8 ] || { [ "$QMAJ" -eq 8 ] && [ "$QMIN" -ge 1 ]; }; then
  ONE_INSN=(-accel tcg,one-insn-per-tb=on)
else
  ONE_INSN=(-singlestep)
fi

echo "== building $TARGET images in $BUILD"
cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$ROOT/cmake/arm-none-eabi.cmake" \
      -DFS_CORTEX_TARGET=$TARGET -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD" --target cm_bench cm_loop cm_count_check -j 2 | grep -E '^(size|heap|stack)' || true
IMG=$BUILD/firmware/ports/cortex-m
SKILL=$(sed -n 's/^FS_BENCH_SKILL:FILEPATH=//p' "$BUILD/CMakeCache.txt")
GOAL=$(sed -n 's/^FS_BENCH_GOAL_SCALE:STRING=//p' "$BUILD/CMakeCache.txt")
TIME=$(sed -n 's/^FS_BENCH_TIME_SCALE:STRING=//p' "$BUILD/CMakeCache.txt")
KERNELS=$(od -An -tu2 -j12 -N2 "$SKILL" | tr -d ' ')

if [ "$NUMERIC" = float ]; then REF=$REF_FLOAT; REF_T=qemu_host_ref_float; else REF=$REF_FIXED; REF_T=qemu_host_ref_fixed; fi
if [ -z "$REF" ]; then
  echo "== building host reference in $HOST_BUILD"
  cmake -S "$ROOT" -B "$HOST_BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$HOST_BUILD" --target $REF_T -j 2 >/dev/null
  REF=$HOST_BUILD/bench/qemu/$REF_T
fi

WORK=$(mktemp -d "${TMPDIR:-/tmp}/qemu_tick.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
# Semihosting output (no chardev given) goes to qemu's stderr.
QEMU=(qemu-system-arm -M $MACHINE -cpu $CPU -nographic -monitor none -serial null
      -semihosting-config enable=on,target=native)

# Count instructions per marked region from a trace streamed on stdin; one count per line.
COUNT_AWK='/ cm_bench_mark_begin$/ { inb = 1; c = 0; next }
           / cm_bench_mark_end$/   { if (inb) print c; inb = 0; next }
           { if (inb) c++ }'

run_counted() { # ELF OUTFILE COUNTFILE
  mkfifo "$WORK/trace.fifo"
  awk "$COUNT_AWK" < "$WORK/trace.fifo" > "$3" &
  local awk_pid=$!
  "${QEMU[@]}" -kernel "$1" "${ONE_INSN[@]}" -d exec,nochain -D "$WORK/trace.fifo" > "$2" 2>&1
  wait $awk_pid
  rm -f "$WORK/trace.fifo"
}

echo "== heap poison check"
# The images link with malloc & co. wrapped to undefined symbols (ports/cortex-m/CMakeLists.txt):
# a program that calls malloc must fail to link with exactly those flags.
WRAP=$(grep -o -- '-Wl,--wrap=[A-Za-z_]*' "$BUILD/build.ninja" | sed 's/.*=//' | sort -u | tr '\n' ' ')
printf '#include <stdlib.h>\nint main(void);\nint main(void) { return malloc(4) != 0; }\nvoid Reset_Handler(void) { (void)main(); }\n' > "$WORK/heap.c"
WRAP_FLAGS=()
for s in $WRAP; do WRAP_FLAGS+=("-Wl,--wrap=$s"); done
if arm-none-eabi-gcc -mcpu=$CPU -mthumb -nostartfiles --specs=nano.specs "${WRAP_FLAGS[@]}" \
     -L"$ROOT/firmware/ports/cortex-m" -T"$ROOT/firmware/ports/cortex-m/$MACHINE.ld" \
     "$WORK/heap.c" -o "$WORK/heap.elf" 2> "$WORK/heap.err"; then
  echo "heap poison check FAILED: a malloc call linked"; exit 1
fi
if grep -q "undefined reference to \`__wrap_malloc'" "$WORK/heap.err"; then
  echo "heap poison check ok: malloc -> undefined __wrap_malloc (wrapped: $WRAP)"
else
  echo "heap poison check FAILED: link failed for another reason:"; cat "$WORK/heap.err"; exit 1
fi

echo "== counter check ($MACHINE, ${ONE_INSN[*]})"
run_counted "$IMG/cm_count_check.elf" "$WORK/cc.out" "$WORK/cc.counts"
CC=$(tr '\n' ' ' < "$WORK/cc.counts")
if [ "$CC" != "103 103 103 " ]; then
  echo "counter check FAILED: expected '103 103 103', got '$CC'"; exit 1
fi
echo "counter check ok: 100 nops + call/return/call counted as $CC"

echo "== benchmark: $(basename "$SKILL") goal=$GOAL time=$TIME"
run_counted "$IMG/cm_bench.elf" "$WORK/bench.out" "$WORK/bench.counts"
grep '^bench' "$WORK/bench.out" || { echo "benchmark image failed:"; tail -5 "$WORK/bench.out"; exit 1; }
ROWS=$(sed -n 's/^bench .*rows=\([0-9]*\).*/\1/p' "$WORK/bench.out")
NCOUNTS=$(wc -l < "$WORK/bench.counts")
if [ "$NCOUNTS" != "$ROWS" ]; then echo "FAILED: $NCOUNTS counted ticks for $ROWS rows"; exit 1; fi
read -r MIN MEDIAN MAX < <(sort -n "$WORK/bench.counts" | awk '{ v[NR] = $1 } END {
  m = (NR % 2) ? v[(NR + 1) / 2] : int((v[NR / 2] + v[NR / 2 + 1]) / 2); print v[1], m, v[NR] }')
echo "tick_instructions target=$TARGET kernels=$KERNELS min=$MIN median=$MEDIAN max=$MAX"

status=0
if [ "$MAX" -gt "$BUDGET" ]; then
  echo "budget FAILED: max $MAX > $BUDGET instructions"; status=1
else
  echo "budget ok: max $MAX <= $BUDGET instructions"
fi

"$REF" "$SKILL" "$GOAL" "$TIME" > "$WORK/host.out"
# the golden float64 rollout of the same skill and scales, if tests/vectors has one
GOLDEN=$(awk -v s="$(basename "$SKILL")" -v g="$GOAL" -v t="$TIME" \
  '$1 == s && $2 + 0 == g + 0 && $3 + 0 == t + 0 { print $4; exit }' "$ROOT/tests/vectors/manifest.txt" 2>/dev/null || true)
if [ -z "$GOLDEN" ]; then  # a skill with a y DMP: its rollout at path scale 1 (t,f_hat,y_hat)
  GOLDEN=$(awk -v s="$(basename "$SKILL")" -v g="$GOAL" -v t="$TIME" \
    '$1 == s && $2 + 0 == g + 0 && $3 + 0 == t + 0 && $4 + 0 == 1 { print $5; exit }' \
    "$ROOT/tests/vectors/manifest_y.txt" 2>/dev/null || true)
fi
python3 "$ROOT/bench/qemu/compare.py" $NUMERIC $TARGET "$WORK/bench.out" "$WORK/host.out" \
  ${GOLDEN:+"$(dirname "$SKILL")/$GOLDEN"} || status=1

echo "== 1 kHz SysTick loop"
# -icount: deterministic virtual time, 2^5 ns per instruction (~31 MIPS), so an overrun is
# the code's, not the loaded host's.
LOOP=$(timeout 120 "${QEMU[@]}" -icount shift=5,sleep=off -kernel "$IMG/cm_loop.elf" 2>&1 | grep '^loop' || true)
echo "$LOOP"
case $LOOP in
  *"overruns=0 faults=0"*) ;;
  *) echo "loop FAILED"; status=1 ;;
esac
exit $status
