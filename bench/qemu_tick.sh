#!/usr/bin/env bash
# Exact instruction counts of the shipped Cortex-M image's 1 kHz tick under qemu.
#   bench/qemu_tick.sh TARGET [--build-dir DIR] [--exec-s S] [--fw-bytes N] [--skill FILE]
#                      [--path-scale S] [--profile] [--focus REGEX]
# TARGET: cortex-m4f (mps2-an386, hardware float) or cortex-m3 (mps2-an385: the DMP and the
# control law in fixed point, the rest of the application in software float).
# 1. builds the images (toolchain cmake/arm-none-eabi.cmake, Release; size, heap and stack report);
#    on the M3, tools/check_float_free.py: no software float reachable from exec_tick_q_fx;
# 2. checks that a program calling malloc cannot link with the images' flags;
# 3. checks the counter on cm_count_check (must count exactly 103 per marked region), and compares
#    the two counters (below: the plugin and the one-instruction trace) on it and on the first
#    1,000,000 instructions of fs_pil (its boot and IDLE ticks without a host: the same under
#    -icount each run): the same instructions, the same lines;
# 4. runs the product image fs_pil (`hil_sim pil`, the application's app_tick on the port of
#    hal.h, with the plant linked in) under qemu with the counter, while
#    bench/qemu/pil_session.py drives it over python-can's slcan interface: IDLE, a skill
#    download, TEACH, an execution of
#    tests/vectors/engrave_n50_ridge_release.skill with a read-back (UDS upload) during it, a
#    second one ended by host silence (FAULT), a firmware download through its transfer exit.
#    The counter: bench/qemu/tick_plugin.c, a qemu TCG plugin built here with the host's cc (qemu
#    with normal chaining, the plugin called before every executed instruction, running the
#    accounting of COUNT_AWK below itself, profiles included: 12-17 s a target), or, with
#    QEMU_TICK_COUNTER=trace or a qemu that cannot load the plugin (one line to stderr), the
#    one-instruction trace: one instruction per translation block and the exec log streamed
#    through a fifo into awk (never stored; 3-4.5 min a target);
# 5. counts, per app_tick (between cm_port_mark_begin and cm_port_mark_end), all its
#    instructions (with the interrupts taken meanwhile) and those of the DMP and control-law part
#    (without them) (dmp_step and pfc_step with their
#    callees; on the M3 their fixed-point builds dmpfx_step and pfcfx_step, and dmpfx_prepare: the
#    next step's blend, computed after the actuator's write), and the kind of the
#    tick (cm_port_mark_idle/execute/upload after it); prints
#      tick_instructions target=T kernels=N min= median= max=          (DMP + control law, EXECUTE)
#      commit_tick_instructions target=T min= median= max= ticks=  (a download's commit)
#      app_tick_instructions target=T state=IDLE|TEACH|EXECUTE|UPLOAD|FWUPDATE|FAULT min= median= max=
#      actuator_latency_instructions target=T state=S min= median= max=   (the tick's start to its
#        actuator write, hal_actuator_force)
#      softfloat_in_app_tick target=T state=S helpers=N calls= instructions=[: names]  (libgcc's
#        __aeabi_d*/__aeabi_f*, __addsf3 & co. executed inside app_tick: none expected on the M4F)
#      uds_answer_ms target=T request=NAME n= median= max=   (bench/qemu/pil_session.py: each UDS
#        request that starts long work, sent to final response, ms of device time: security_key,
#        skill_transfer_exit (the commit), read_back_block, firmware_request_download (the erase),
#        firmware_block, firmware_transfer_exit (the verification), routine_start_RRRR)
#      qemu_tick_duration target=T seconds=S
#    --profile: then, per state, the top functions of its worst and of its smallest tick
#    (bench/qemu/tick_profile.py over the QEMU_TICK_PROFILE files, below); --focus REGEX (implies
#    --profile): also, per state, the tick where the functions matching REGEX ran the most
#    instructions and those functions (e.g. the skill store and storage: '^(slots_|nvm_|skill_)').
# Exit status 1 if a check fails or the DMP + control-law part exceeds its budget (M4F 850,
# M3 1,250).
set -euo pipefail

usage() { echo "usage: $0 cortex-m4f|cortex-m3 [--build-dir DIR] [--exec-s S] [--fw-bytes N] [--skill FILE] [--path-scale S] [--profile] [--focus REGEX]" >&2; exit 2; }
[ $# -ge 1 ] || usage
TARGET=$1; shift
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=$ROOT/build/$TARGET
EXEC_S=1.0
FW_BYTES=16384
PATH_SCALE=1
PROFILE=0
T_START=$SECONDS
while [ $# -gt 0 ]; do
  case $1 in
    --build-dir) BUILD=$2; shift 2 ;;
    --exec-s) EXEC_S=$2; shift 2 ;;
    --fw-bytes) FW_BYTES=$2; shift 2 ;;   # the firmware download's payload (FWUPDATE)
    --skill) SKILL_ARG=$2; shift 2 ;;
    --path-scale) PATH_SCALE=$2; shift 2 ;;   # the run's: a y path the axis can follow (the cost is the same)
    --profile) PROFILE=1; shift ;;   # per state, the top functions of its worst tick (tick_profile.py)
    --focus) PROFILE=1; QEMU_TICK_FOCUS=$2; shift 2 ;;   # also the tick where REGEX's functions ran most
    --host-ref-float|--host-ref-fixed) shift 2 ;;   # accepted for older callers; unused
    *) usage ;;
  esac
done

case $TARGET in
  cortex-m4f) MACHINE=mps2-an386; CPU=cortex-m4; BUDGET=850
              DMP_RE='^dmp_((periodic_)?step(_xy)?|prepare)_f32$'; LAW=pfc_step_f32 ;;
  cortex-m3)  MACHINE=mps2-an385; CPU=cortex-m3; BUDGET=1250
              DMP_RE='^dmpfx_((periodic_)?step(_xy)?|prepare)$'; LAW=pfcfx_step ;;
  *) usage ;;
esac
PY=${PYTHON:-$ROOT/.venv/bin/python}
HIL_SIM=${FORCESKILL_HIL_SIM:-$ROOT/build/hil_sim/hil_sim}
[ -x "$HIL_SIM" ] || { echo "hil_sim not built at $HIL_SIM (./scripts/setup.sh)"; exit 1; }
SKILL=${SKILL_ARG:-$ROOT/tests/vectors/engrave_n50_ridge_release.skill}
KERNELS=$(od -An -tu2 -j12 -N2 "$SKILL" | tr -d ' ')

source "$ROOT/bench/qemu/one_insn.sh"   # ONE_INSN, TRACE_FILTER, plugin_build: the two counters

echo "== building $TARGET images in $BUILD"
cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$ROOT/cmake/arm-none-eabi.cmake" \
      -DFS_CORTEX_TARGET=$TARGET -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE="$PY" >/dev/null
cmake --build "$BUILD" --target fs_pil cm_count_check -j 2 | grep -E '^(size|heap|stack)' || true
IMG=$BUILD/firmware/ports/mps2
if [ "$TARGET" = cortex-m3 ]; then
  # the executor's tick on the M3 must reach no software float (objdump call graph)
  echo "== float-free check of exec_tick_q_fx"
  if ! ff=$("$PY" "$ROOT/tools/check_float_free.py" --build-dir "$BUILD" --no-build); then
    echo "$ff"; exit 1
  fi
  echo "$ff" | grep -E '^(control|float-free check)'
fi

WORK=$(mktemp -d "${TMPDIR:-/tmp}/qemu_tick.XXXXXX")
PIL_PID=""
cleanup() { [ -n "$PIL_PID" ] && kill "$PIL_PID" 2>/dev/null || true; rm -rf "$WORK"; }
trap cleanup EXIT

echo "== heap poison check"
# The images link with malloc & co. wrapped to undefined symbols (ports/mps2/CMakeLists.txt):
# a program that calls malloc must fail to link with exactly those flags.
WRAP=$(grep -o -- '-Wl,--wrap=[A-Za-z_]*' "$BUILD/build.ninja" | sed 's/.*=//' | sort -u | tr '\n' ' ')
printf '#include <stdlib.h>\nint main(void);\nint main(void) { return malloc(4) != 0; }\nvoid Reset_Handler(void) { (void)main(); }\n' > "$WORK/heap.c"
WRAP_FLAGS=()
for s in $WRAP; do WRAP_FLAGS+=("-Wl,--wrap=$s"); done
if arm-none-eabi-gcc -mcpu=$CPU -mthumb -nostartfiles --specs=nano.specs "${WRAP_FLAGS[@]}" \
     -L"$ROOT/firmware/ports/mps2" -T"$ROOT/firmware/ports/mps2/$MACHINE.ld" \
     "$WORK/heap.c" -o "$WORK/heap.elf" 2> "$WORK/heap.err"; then
  echo "heap poison check FAILED: a malloc call linked"; exit 1
fi
if grep -q "undefined reference to \`__wrap_malloc'" "$WORK/heap.err"; then
  echo "heap poison check ok: malloc -> undefined __wrap_malloc (wrapped: $WRAP)"
else
  echo "heap poison check FAILED: link failed for another reason:"; cat "$WORK/heap.err"; exit 1
fi

# The counters (both exact, same lines; bench/qemu/one_insn.sh):
# - the plugin (default): bench/qemu/tick_plugin.c (qemu with normal chaining, the plugin called
#   before each executed instruction; it runs COUNT_AWK's accounting below itself, writes ticks.txt);
# - the one-instruction trace (QEMU_TICK_COUNTER=trace, or a qemu that cannot load the plugin):
#   qemu's exec log through TRACE_FILTER then COUNT_AWK.
COUNTER=${QEMU_TICK_COUNTER:-plugin}
PLUGIN=$WORK/tick_plugin.so
QEMU_CC=(qemu-system-arm -M $MACHINE -cpu $CPU -nographic -monitor none -serial null
         -semihosting-config enable=on,target=native -kernel "$IMG/cm_count_check.elf")
cc_trace() { # FILE: the counter check's counts with the one-instruction trace
  rm -f "$WORK/cc.fifo"; mkfifo "$WORK/cc.fifo"
  awk "$TRACE_FILTER" < "$WORK/cc.fifo" | awk "$REGION_AWK" > "$1" &
  local pid=$!
  "${QEMU_CC[@]}" "${ONE_INSN[@]}" -d exec,nochain -D "$WORK/cc.fifo" > "$WORK/cc.out" 2>&1
  wait $pid
}
if [ "$COUNTER" = plugin ]; then
  if ! plugin_build "$PLUGIN" 2> "$WORK/plugin.err"; then
    echo "qemu_tick: cannot build bench/qemu/tick_plugin.c ($(head -1 "$WORK/plugin.err")): counting with the one-instruction trace" >&2
    COUNTER=trace
  elif ! "${QEMU_CC[@]}" -plugin "$PLUGIN,mode=count,out=$WORK/cc.counts" > "$WORK/cc.out" 2>&1; then
    echo "qemu_tick: $(qemu-system-arm --version | head -1) cannot load the plugin ($(grep -m1 -i plugin "$WORK/cc.out")): counting with the one-instruction trace" >&2
    COUNTER=trace
  fi
fi
echo "== counter check ($MACHINE, counter: $COUNTER)"
[ "$COUNTER" = plugin ] || cc_trace "$WORK/cc.counts"
CC=$(tr '\n' ' ' < "$WORK/cc.counts")
if [ "$CC" != "103 103 103 " ]; then
  echo "counter check FAILED: expected '103 103 103', got '$CC'"; exit 1
fi
echo "counter check ok: 100 nops + call/return/call counted as $CC"
if [ "$COUNTER" = plugin ]; then
  cc_trace "$WORK/cc.trace"
  CT=$(tr '\n' ' ' < "$WORK/cc.trace")
  [ "$CT" = "$CC" ] || { echo "counter comparison FAILED: the trace (${ONE_INSN[*]}) counted '$CT'"; exit 1; }
  echo "counter comparison ok: the one-instruction trace (${ONE_INSN[*]}) counts the same $CT"
fi

echo "== the product image: $(basename "$SKILL") (N = $KERNELS), IDLE / download / EXECUTE / EXECUTE + read-back"
# Per counted tick: kind, all instructions of app_tick, those inside dmp_step(_xy)/pfc_step (entered
# from their caller, left when the caller's code runs again; an interrupt handler taken meanwhile
# is the CAN link's cost: in the tick's total, not in the part. The plugin follows each interrupt
# from its *_Handler entry to its exception return, the return with none of the handler's calls
# open; COUNT_AWK, with symbols only, until the interrupted function runs again: the same but
# when the interrupt comes right after a call or a return, rare with one instruction per block), 1 if the DMP stepped (not after the
# skill's end, when the end policy runs the law alone), those inside dmp_step(_xy) alone, 1 if the
# tick worked on a download's commit (the application's download_end, which runs the parse, the
# checks and the slot's write in slices, or skill_parse_run / skchk_* inlined into it).
# Also: each boot (from the first instruction of Reset_Handler to the first counted tick: all its
# instructions and those inside app_init), and the skill check of each download (the instructions
# inside skchk_params/skchk_begin/skchk_run, entered from the UDS transfer's code, over the ticks
# it is spread across).
COUNT_AWK='/ cm_port_mark_begin$/ { if (inboot) { print "boot", bc, ba; inboot = 0 }
                                    inb = 1; c = 0; part = 0; inpart = 0; dmp = 0; dpart = 0; indmp = 0; inisr = 0
                                    cmt = 0; act = 0; next }
  / cm_port_mark_end$/ { if (inb) { done = 1; lc = c; lp = part; ld = dmp; ldp = dpart; lcm = cmt; la = act }
                         if (chk_tick > 0) { chk_ticks++; if (chk_tick > chk_max) chk_max = chk_tick }
                         if (chk_tick == 0 && chk_ticks > 0) { print "check", chk_total, chk_ticks, chk_max
                                                               chk_total = 0; chk_ticks = 0; chk_max = 0 }
                         chk_tick = 0; inb = 0; next }
  / cm_port_mark_(idle|teach|execute|upload|fwupdate|fault|other)$/ {
      if (done) { k = $NF; sub(/^cm_port_mark_/, "", k); print k, lc, lp, ld, ldp, lcm, la; done = 0
                  if (prof != "" && k == "execute") { for (f in h) tot[f] += h[f]; nexec++
                                                      for (a in hp) tp[a] += hp[a]
                                                      if (ld && ldp > maxdp) { maxdp = ldp; delete hm
                                                                               for (f in h) hm[f] = h[f] } }
                  if (prof != "" && lc > kmax[k]) { kmax[k] = lc
                                                    for (x in hk) if (index(x, k SUBSEP) == 1) delete hk[x]
                                                    for (f in h) hk[k, f] = h[f] }
                  if (prof != "" && FOCUS != "") { fc = 0; for (f in h) if (f ~ FOCUS) fc += h[f]
                                                   if (fc > fmax[k]) { fmax[k] = fc
                                                     for (x in hf) if (index(x, k SUBSEP) == 1) delete hf[x]
                                                     for (f in h) if (f ~ FOCUS) hf[k, f] = h[f] } }
                  if (prof != "" && (!(k in kmin) || lc < kmin[k])) { kmin[k] = lc
                                                    for (x in hn) if (index(x, k SUBSEP) == 1) delete hn[x]
                                                    for (f in h) hn[k, f] = h[f] }
                  for (f in sfi) { SFI[k, f] += sfi[f]; SFC[k, f] += sfc[f] } }
      delete h; delete hp; delete sfi; delete sfc; next }
  END { if (prof != "") { for (f in tot) printf "%d %s\n", tot[f] / nexec, f > prof
                          for (a in tp) printf "%.2f %s\n", tp[a] / nexec, a > (prof ".pc")
                          for (f in hm) printf "%d %s\n", hm[f], f > (prof ".maxdmp")
                          for (x in hk) { split(x, q, SUBSEP); printf "%d %s\n", hk[x], q[2] > (prof ".max." q[1]) }
                          for (x in hf) { split(x, q, SUBSEP); printf "%d %s\n", hf[x], q[2] > (prof ".focus." q[1]) }
                          for (x in hn) { split(x, q, SUBSEP); printf "%d %s\n", hn[x], q[2] > (prof ".min." q[1]) } }
        for (x in SFI) { split(x, q, SUBSEP); print "softfloat", q[1], q[2], SFC[x], SFI[x] } }
  { s = $NF
    if (!inboot && s == "Reset_Handler") { inboot = 1; bc = 0; ba = 0; ininit = 0 }
    if (inboot) { bc++
                  if (!ininit && s == "app_init") { ininit = 1; initcaller = bprev }
                  else if (ininit && s == initcaller) { ininit = 0 }
                  if (ininit) ba++
                  bprev = s }
    if (inb) { c++; h[s]++
               if (s == "hal_actuator_force" && !act) act = c
               if (s ~ SOFTF) { sfi[s]++; if (s != last) sfc[s]++ }
               last = s
               if (s ~ COMMIT) cmt = 1
               if (prof != "") { split($4, pcs, "/"); hp[pcs[2] " " s]++ }
               # an interrupt taken inside the tick (the UART of the CAN link) counts in the
               # tick, not in a part it interrupts: from its handler back to the interrupted code
               # (an interrupt taken right after a return resumes in the caller, so the function
               # last seen may not run again: inisr is also cleared when a tick starts)
               if (!inisr && s ~ /_Handler$/ && s != "Reset_Handler") { inisr = 1; isrret = prev }
               else if (inisr && s == isrret) { inisr = 0 }
               if (inisr) { prev = s; next }
               if (!inpart && (s ~ DMP || s == LAW)) { inpart = 1; caller = prev
                                                                   if (s ~ DMP) dmp = 1 }
               else if (inpart && s == caller) { inpart = 0 }
               if (inpart) part++
               if (!indmp && s ~ DMP) { indmp = 1; dcaller = prev }
               else if (indmp && s == dcaller) { indmp = 0 }
               if (indmp) dpart++
               if (!inchk && s ~ CHK) { inchk = 1; chkcaller = prev }
               else if (inchk && s == chkcaller) { inchk = 0 }
               if (inchk) { chk_total++; chk_tick++ }
               prev = s } }'
if [ "$PROFILE" = 1 ] && [ -z "${QEMU_TICK_PROFILE:-}" ]; then QEMU_TICK_PROFILE=$WORK/prof; fi
# QEMU_TICK_PROFILE=FILE: also write the mean instructions per function of an EXECUTE tick there,
# per instruction address (hex, with its function) in FILE.pc, per function of the EXECUTE tick
# with the largest DMP part in FILE.maxdmp, per function of the largest tick of each kind K in
# FILE.max.K and of its smallest (a tick without bus traffic: the state's floor) in FILE.min.K,
# the soft-float helpers per kind in FILE.softfloat (--profile: a temporary FILE, printed by
# bench/qemu/tick_profile.py); with QEMU_TICK_FOCUS=REGEX also, per kind K, the functions matching
# REGEX of the tick where they ran the most instructions, in FILE.focus.K
COMMIT_RE='^(download_end|skill_parse_run_f32|skchk_(params|begin|run)_f32)$'
SOFTF_RE='^__aeabi_(d|f|u?i2[df]|u?l2[df])|^__[a-z]+[sd]f[a-z0-9]*$'
CHK_RE='^skchk_(params|begin|run)_f32$'   # COUNT_AWK's skill check functions
popt() { printf '%s' "${1//,/,,}"; }      # a value in qemu's -plugin option (commas doubled)
start_pil() { # COUNTER TICKS [LIMIT STREAM]: hil_sim pil in the background (PIL_PID), its ticks.txt
  # lines into TICKS by COUNTER (plugin|trace; the trace's awk: CNT_PID); LIMIT: only the first
  # LIMIT instructions, their "pc symbol" lines into STREAM; PROF, FOCUS_RE: the profiles
  local limit=${3:-0} stream=${4:-} qa=()
  CNT_PID=""
  if [ "$1" = plugin ]; then
    qa=(--qemu-arg -plugin --qemu-arg "$(popt "$PLUGIN"),out=$(popt "$2"),limit=$limit${stream:+,log=$(popt "$stream")},dmp=$(popt "$DMP_RE"),law=$LAW,commit=$(popt "$COMMIT_RE"),softf=$(popt "$SOFTF_RE"),chk=$(popt "$CHK_RE")${PROF:+,prof=$(popt "$PROF")}${FOCUS_RE:+,focus=$(popt "$FOCUS_RE")}")
  else
    rm -f "$WORK/trace.fifo"; mkfifo "$WORK/trace.fifo"
    awk -v limit="$limit" -v stream="$stream" "$TRACE_FILTER" < "$WORK/trace.fifo" |
      awk -v prof="$PROF" -v FOCUS="$FOCUS_RE" -v DMP="$DMP_RE" -v LAW="$LAW" \
          -v COMMIT="$COMMIT_RE" -v SOFTF="$SOFTF_RE" -v CHK="$CHK_RE" "$COUNT_AWK" > "$2" &
    CNT_PID=$!
    qa=(--qemu-arg "${ONE_INSN[0]}" ${ONE_INSN[1]:+--qemu-arg "${ONE_INSN[1]}"}
        --qemu-arg -d --qemu-arg exec,nochain --qemu-arg -D --qemu-arg "$WORK/trace.fifo")
  fi
  "$HIL_SIM" pil --target "$TARGET" --image "$BUILD/hil_sim/pil/fs_pil.elf" --port 0 --host-timeout 500 "${qa[@]}" \
    > "$WORK/pil.out" 2> "$WORK/pil.err" &
  PIL_PID=$!
}
stop_pil() { kill -TERM "$PIL_PID" 2>/dev/null || true; wait "$PIL_PID" || true; PIL_PID=""; }
status=0
PROF=""; FOCUS_RE=""
if [ "$COUNTER" = plugin ]; then
  # the plugin against the one-instruction trace on the product image: its first EXACT_N
  # instructions (the boot with an empty flash, then IDLE ticks; no host connected, -icount: the
  # same instructions each run) must be the same stream and give the same lines
  EXACT_N=${QEMU_TICK_EXACT_N:-1000000}
  start_pil plugin "$WORK/exact.plugin" "$EXACT_N" "$WORK/exact.plugin.pcs"
  for _ in $(seq 1200); do grep -q '^limit' "$WORK/exact.plugin" 2>/dev/null && break; sleep 0.1; done
  stop_pil
  start_pil trace "$WORK/exact.trace" "$EXACT_N" "$WORK/exact.trace.pcs"
  wait "$CNT_PID"; stop_pil
  if ! grep -q "^limit $EXACT_N$" "$WORK/exact.plugin" || ! grep -q '^boot' "$WORK/exact.plugin" ||
     ! cmp -s "$WORK/exact.plugin.pcs" "$WORK/exact.trace.pcs" ||
     ! diff <(grep -v '^limit' "$WORK/exact.plugin" | sort) <(sort "$WORK/exact.trace") > "$WORK/exact.diff" ||
     ! diff <(grep -v '^limit\|^softfloat' "$WORK/exact.plugin") <(grep -v '^softfloat' "$WORK/exact.trace") >> "$WORK/exact.diff"; then
    echo "counter comparison FAILED on fs_pil's first $EXACT_N instructions:"
    cmp "$WORK/exact.plugin.pcs" "$WORK/exact.trace.pcs" || true; head -20 "$WORK/exact.diff"; exit 1
  fi
  read -r _ BT BA < <(grep -m1 '^boot' "$WORK/exact.plugin")
  echo "counter comparison ok: fs_pil's first $EXACT_N instructions, the same with the plugin and the trace (boot total=$BT app_init=$BA, then $(grep -c '^idle' "$WORK/exact.plugin") IDLE ticks)"
fi
PROF=${QEMU_TICK_PROFILE:-}; FOCUS_RE=${QEMU_TICK_FOCUS:-}
start_pil "$COUNTER" "$WORK/ticks.txt"
for _ in $(seq 600); do grep -q "listening on" "$WORK/pil.out" && break; sleep 0.1; done
PORT=$(sed -n 's/.*127.0.0.1:\([0-9]*\).*/\1/p' "$WORK/pil.out")
[ -n "$PORT" ] || { echo "hil_sim pil did not start:"; cat "$WORK/pil.err"; exit 1; }
"$PY" "$ROOT/bench/qemu/pil_session.py" "$PORT" "$SKILL" --target "$TARGET" --exec-s "$EXEC_S" \
  --fw-bytes "$FW_BYTES" --path-scale "$PATH_SCALE" || status=1
stop_pil
[ -z "$CNT_PID" ] || wait "$CNT_PID"
grep '^fs_pil' "$WORK/pil.err" || true
if grep -q '^isr_lost' "$WORK/ticks.txt"; then   # the plugin's interrupt tracking lost one
  echo "counter FAILED: $(grep '^isr_lost' "$WORK/ticks.txt") (an interrupt's entry or return missed)"; status=1
fi
# QEMU_TICK_KEEP=FILE: also keep the per-tick counts there (kind, app_tick, DMP + law, stepped,
# DMP alone, commit, instructions to the actuator write; one line per tick in order)
[ -z "${QEMU_TICK_KEEP:-}" ] || cp "$WORK/ticks.txt" "$QEMU_TICK_KEEP"

stats() { # lines of numbers on stdin -> "min median max count"
  sort -n | awk '{ v[NR] = $1 } END { if (NR == 0) { print "- - - 0"; exit }
    m = (NR % 2) ? v[(NR + 1) / 2] : int((v[NR / 2] + v[NR / 2 + 1]) / 2); print v[1], m, v[NR], NR }'
}
# the DMP + control-law part of every EXECUTE tick that stepped the DMP (with or without a
# transfer; the skill check of a download steps the DMP too, in IDLE ticks: counted apart)
read -r MIN MED MAX N < <(awk '$4 == 1 && $6 == 0 && ($1 == "execute" || $1 == "upload") { print $3 }' "$WORK/ticks.txt" | stats)
echo "tick_instructions target=$TARGET kernels=$KERNELS min=$MIN median=$MED max=$MAX"
# the DMP part alone (dmp_step or dmp_step_xy with its callees) of the same ticks
read -r DMIN DMED DMAX _ < <(awk '$4 == 1 && $6 == 0 && ($1 == "execute" || $1 == "upload") { print $5 }' "$WORK/ticks.txt" | stats)
echo "dmp_instructions target=$TARGET kernels=$KERNELS skill=$(basename "$SKILL") min=$DMIN median=$DMED max=$DMAX"
[ "$N" -ge 100 ] || { echo "FAILED: only $N ticks ran the DMP"; status=1; }
# boots: the first with an empty flash, the second (the session's ECUReset) with the skill stored
awk '$1 == "boot" { n++; printf "boot_instructions target=%s boot=%d skills=%d total=%d app_init=%d\n", t, n, n - 1, $2, $3 }' \
  t="$TARGET" "$WORK/ticks.txt"
awk '$1 == "check" { printf "skill_check_instructions target=%s total=%d ticks=%d max_per_tick=%d\n", t, $2, $3, $4 }' \
  t="$TARGET" "$WORK/ticks.txt"
# the ticks of a download's commit (RequestTransferExit to its answer: the parse, the parameter
# check, the rollout, the flash write), whatever the state
read -r A B C N < <(awk '$6 == 1 && $1 != "fwupdate" { print $2 }' "$WORK/ticks.txt" | stats)
echo "commit_tick_instructions target=$TARGET min=$A median=$B max=$C ticks=$N"
for st in idle teach execute upload fwupdate fault; do
  read -r A B C N < <(awk -v k=$st '$1 == k { print $2 }' "$WORK/ticks.txt" | stats)
  echo "app_tick_instructions target=$TARGET state=$(echo $st | tr a-z A-Z) min=$A median=$B max=$C ticks=$N"
  [ "$N" -gt 0 ] || { echo "FAILED: no $st tick counted"; status=1; }
done
# the sensor-to-actuator latency: the instructions from the tick's start (the sensors are read
# first) to its actuator write, per state (ticks that wrote the actuator)
for st in idle teach execute upload fwupdate fault; do
  read -r A B C N < <(awk -v k=$st '$1 == k && $7 > 0 { print $7 }' "$WORK/ticks.txt" | stats)
  echo "actuator_latency_instructions target=$TARGET state=$(echo $st | tr a-z A-Z) min=$A median=$B max=$C ticks=$N"
done
# the software-float helpers (libgcc) executed inside app_tick, per state: calls and instructions
for st in idle teach execute upload fwupdate fault; do
  awk -v k=$st -v t="$TARGET" '$1 == "softfloat" && $2 == k { n++; c += $4; i += $5; names = names " " $3 }
    END { printf "softfloat_in_app_tick target=%s state=%s helpers=%d calls=%d instructions=%d%s\n",
                 t, toupper(k), n, c, i, (n ? ":" names : "") }' "$WORK/ticks.txt"
done
if [ -n "${QEMU_TICK_PROFILE:-}" ]; then
  awk '$1 == "softfloat" { print $2, $3, $4, $5 }' "$WORK/ticks.txt" > "$QEMU_TICK_PROFILE.softfloat"
fi
if [ "$PROFILE" = 1 ]; then
  "$PY" "$ROOT/bench/qemu/tick_profile.py" "$QEMU_TICK_PROFILE" --target "$TARGET" || status=1
fi
if [ "$MAX" = "-" ] || [ "$MAX" -gt "$BUDGET" ]; then
  echo "budget FAILED: DMP + control law max $MAX > $BUDGET instructions"; status=1
else
  echo "budget ok: DMP + control law max $MAX <= $BUDGET instructions"
fi
echo "qemu_tick_duration target=$TARGET seconds=$((SECONDS - T_START))"
exit $status
