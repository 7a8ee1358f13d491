#!/usr/bin/env bash
# Every test: one tick implementation (scripts/check_one_tick.sh), C unit tests under ASan+UBSan
# (Debug build, preset host-debug), the static checks, the Cortex-M images under qemu
# (bench/qemu_tick.sh: the product image's tick counted per state, no heap/recursion, size and
# stack per entry point), then the Python, HIL and CAN tests against the Release build
# (tests/can/test_pil.py: the journey and the firmware update against the Cortex-M4F image built
# by the step before), and a subset again in .venv-min (every dependency at its lowest allowed
# version, scripts/min_venv.sh). Exit status is non-zero if anything fails.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$ROOT/scripts/setup.sh"
cd "$ROOT"
# each step's header carries the suite's elapsed time, so a slow step shows in the log
step() { printf '== [%dm%02ds] %s\n' $((SECONDS / 60)) $((SECONDS % 60)) "$1"; }

step "generated files agree with their sources (codes.toml -> headers, codes.py, docs/codes.md and"
echo "   the marked tables of docs/protocol.md, safety.md, update.md;"
echo "   public headers -> the _f32 rename headers)"
.venv/bin/python tools/gen_codes.py --check
.venv/bin/python tools/gen_f32_names.py --check
step "comments and docs cite no SPEC or issue numbers"
tools/check_no_tracker_refs.sh
step "one implementation of the control tick (scripts/check_one_tick.sh)"
scripts/check_one_tick.sh
step "layers: no upward or sideways include or host import, no cycle (tools/check_layers.py)"
.venv/bin/python tools/check_layers.py
step "no C function over 80 lines in firmware/ and hil_sim/ without a /* long: reason */ (tools/check_fn_length.py)"
.venv/bin/python tools/check_fn_length.py
step "test modules: every tests/**/test_*.py basename is unique (pytest imports them by basename)"
dup_tests="$(find tests -name 'test_*.py' -printf '%f\n' | sort | uniq -d)"
if [ -n "$dup_tests" ]; then
  echo "error: test module basenames used twice: $dup_tests" >&2
  exit 1
fi
step "Python: ruff (lint, format) on host/forceskill, tests/, tools/ and bench/, mypy (strict) on"
echo "   host/forceskill (configuration: host/pyproject.toml)"
.venv/bin/ruff check --config host/pyproject.toml host/forceskill tests tools bench
.venv/bin/ruff format --config host/pyproject.toml --check host/forceskill tests tools bench
(cd host && ../.venv/bin/mypy)

step "C tests (Debug: ASan + UBSan; preset host-debug, build/host-debug)"
cmake --preset host-debug >/dev/null
cmake --build --preset host-debug -j "$(nproc)"
ctest --preset host-debug -j "$(nproc)"

step "the firmware libraries as a consumer sees them: cmake --install, find_package, add_subdirectory, pkg-config"
tests/consumer/run.sh build/consumer

step "static checks (cppcheck; MISRA addon findings counted, not fatal)"
tools/static_check.sh build/host-debug/static

# The hard real-time budgets of app_tick (instructions, every tick of bench/qemu_tick.sh's journey):
# M4F max 3,000 in every state and EXECUTE median 1,500; M3 max 8,000 and EXECUTE median 3,000.
# A state listed in TICK_OVER (target:STATE, or target:EXECUTE-median) is not yet within its budget:
# reported with its figure, not enforced; every other state over its budget fails the suite.
# Measured with bench/qemu_tick.sh TARGET --fw-bytes 4096 --exec-s 0.5 (the plugin's count), over
# several runs of each image: every state's max is within its budget and both EXECUTE medians too
# (M4F 1,482, M3 2,545); the M4F's UPLOAD max is enforced since a read-back's block is copied
# once and its frames built in place, and each 0x78 job's slice (key checks, the attempt record's
# write, the motion key's set-up) takes a tick of its own (docs/cortex-m.md "Worst tick per state").
TICK_OVER=""
# The whole tick's target, tighter than its budget: M4F 2,000 and M3 5,000 in every state. Listed
# in TICK_TARGET_OVER (target:STATE, or target:STATE@periodic_y for the periodic y journey): not
# yet within, reported with its figure, not enforced. Measured (same command, several runs): M4F
# IDLE 1,405-1,740 since a seed's random bytes come from the port's FIFO, TEACH 1,295-1,724, FAULT
# 1,498-1,885; over: EXECUTE 2,055-2,124 (a MAC check's start or its rounds beside the control
# path and a status frame), UPLOAD 2,132-2,270 (a run routine's request with the run's checks;
# 2,294-2,386 with the executor's reset in that tick too), FWUPDATE 2,027-2,420 (the
# verification's 16 rounds beside a tick's frames; a tick of 9 host frames' arrival); the periodic
# y journey's EXECUTE 2,366-2,377, UPLOAD 2,607-2,684 and FWUPDATE 2,007-2,385 (its heavier
# control path; two rollout steps of a commit's check a tick). M3: every state of both journeys
# within (UPLOAD 4,187-4,647, the periodic y journey's 4,332-4,501, since a periodic kernel's reach
# counts two parse units and a run's start and a commit's check derive the periodic, path and
# state constants each in a call).
TICK_TARGET_OVER="cortex-m4f:EXECUTE cortex-m4f:UPLOAD cortex-m4f:FWUPDATE
  cortex-m4f:EXECUTE@periodic_y cortex-m4f:UPLOAD@periodic_y cortex-m4f:FWUPDATE@periodic_y"
tick_budgets() { # TARGET LOG [MAX_ONLY [JOURNEY]]: fail on a tick over budget in a state not listed
  # in TICK_OVER, or over target in a state not listed in TICK_TARGET_OVER (MAX_ONLY=1: the maxima
  # only, for a journey whose skill is not the medians' reference, named JOURNEY in the keys)
  local target=$1 log=$2 max_only=${3:-0} journey=${4:-} max_b med_b tgt_b
  case $target in cortex-m4f) max_b=3000; med_b=1500; tgt_b=2000 ;; *) max_b=8000; med_b=3000; tgt_b=5000 ;; esac
  awk -v t="$target" -v mb="$max_b" -v eb="$med_b" -v tb="$tgt_b" -v mo="$max_only" \
      -v j="${journey:+@$journey}" -v over=" $(echo $TICK_OVER) " -v tover=" $(echo $TICK_TARGET_OVER) " '
    function check(what, lst, key, v, b) {
      if (v == "-") { printf "tick %s FAILED: %s not measured\n", what, key; bad = 1; return }
      if (index(lst, " " key " ")) {
        printf "tick %s (not enforced yet): %s %d %s %d\n", what, key, v, (v + 0 > b ? ">" : "<= (within in this run)"), b
      } else if (v + 0 > b) { printf "tick %s FAILED: %s %d > %d\n", what, key, v, b; bad = 1 }
      else printf "tick %s ok: %s %d <= %d\n", what, key, v, b }
    $1 == "app_tick_instructions" && $2 == "target=" t {
      for (i = 3; i <= NF; i++) { split($i, kv, "="); f[kv[1]] = kv[2] }
      n++; check("budget", over, t ":" f["state"] j, f["max"], mb)
      check("target", tover, t ":" f["state"] j, f["max"], tb)
      if (f["state"] == "EXECUTE" && mo != 1) check("budget", over, t ":EXECUTE-median", f["median"], eb) }
    END { if (n < 6) { printf "tick budget FAILED: %d states counted for %s, 6 expected\n", n, t; bad = 1 }
          exit bad }' "$log"
}

# The sensor-to-actuator latency (instructions from the tick's start to its actuator write): M4F
# 1,200 and M3 2,500 in every state. Listed in LATENCY_OVER (target:STATE): not yet within,
# reported with its figure, not enforced. Every state is within on both images since the DMP's
# kernel blend for the next tick is computed after the write (exec_prepare_next; on the M3 also
# the object model's forces): M4F max IDLE 818-839, EXECUTE 889-936, UPLOAD 868-960, FAULT 1,050;
# M3 max EXECUTE 1,916, UPLOAD 2,071, FAULT 2,065 (the UART's receive interrupts taken before the
# write add up to ~115 on the M4F and ~700 on the M3 at their per-tick byte caps). Before, the M4F's EXECUTE ticks reached
# 1,244-1,308, its tick that latches a fault 1,386-1,423; the M3's EXECUTE 2,237-2,793 and FAULT
# 2,496-2,540. The periodic y journey (target:STATE@periodic_y): its DMP's blend is computed before
# the write (a periodic model has no prepared blend: that cost ~26 instructions of its DMP + law
# count, over its 850 budget), so EXECUTE and a read-back during its run (UPLOAD) are over: M4F
# 1,500-1,645, M3 2,892-3,577; its other states are enforced.
LATENCY_OVER="cortex-m4f:EXECUTE@periodic_y cortex-m4f:UPLOAD@periodic_y
  cortex-m3:EXECUTE@periodic_y cortex-m3:UPLOAD@periodic_y"
latency_budgets() { # TARGET LOG [JOURNEY]
  local target=$1 log=$2 journey=${3:-} b
  case $target in cortex-m4f) b=1200 ;; *) b=2500 ;; esac
  awk -v t="$target" -v b="$b" -v j="${journey:+@$journey}" -v over=" $(echo $LATENCY_OVER) " '
    $1 == "actuator_latency_instructions" && $2 == "target=" t {
      for (i = 3; i <= NF; i++) { split($i, kv, "="); f[kv[1]] = kv[2] }
      n++; key = t ":" f["state"] j
      if (f["max"] == "-") { printf "latency budget FAILED: %s not measured\n", key; bad = 1 }
      else if (index(over, " " key " ")) {
        printf "latency budget (not enforced yet): %s %d %s %d\n", key, f["max"], (f["max"] + 0 > b ? ">" : "<= (within in this run)"), b }
      else if (f["max"] + 0 > b) { printf "latency budget FAILED: %s %d > %d\n", key, f["max"], b; bad = 1 }
      else printf "latency budget ok: %s %d <= %d\n", key, f["max"], b }
    END { if (n < 6) { printf "latency budget FAILED: %d states counted for %s, 6 expected\n", n, t; bad = 1 }
          exit bad }' "$log"
}

step "Cortex-M images under qemu (M4F, M3): the product image's app_tick counted per state,"
echo "   DMP + control law within budget, no heap, no recursion, size, worst stack per entry point"
# a 4 KiB firmware download: its verification runs in the same slices as the bench's 16 KiB one
# (the same worst tick), in a quarter of the ticks under the trace; 0.5 s of each execution (the
# EXECUTE ticks alike but for the bus: min 1,813, median 1,888 over 1 s and its read-back), TEACH
# and FAULT 150 ticks each (bench/qemu/pil_session.py's defaults)
for target in cortex-m4f cortex-m3; do
  log="build/qemu_tick_$target.log"
  if ! bench/qemu_tick.sh "$target" --fw-bytes 4096 --exec-s 0.5 >"$log" 2>&1; then
    cat "$log"; echo "qemu benchmark failed for $target (log: $log)" >&2; exit 1
  fi
  grep -E '^(size|heap|stack|tick_instructions|app_tick_instructions|actuator_latency_instructions|softfloat_in_app_tick|budget|counter (check|comparison)|qemu_tick_duration)' "$log" || true
  tick_budgets "$target" "$log"
  latency_budgets "$target" "$log"
  # the same journey with a periodic skill with the y path: its commit derives a periodic model
  # (trigonometry a kernel: software float on the M3), its run the heavier periodic DMP and path;
  # at path scale 0.05 (at 1 its 64 mm stroke asks 418 N of the y axis and latches
  # FLT_SLEW_LIMIT); every state's max enforced
  log="build/qemu_tick_${target}_periodic_y.log"
  if ! bench/qemu_tick.sh "$target" --fw-bytes 4096 --exec-s 0.5 \
      --skill tests/vectors/periodic_y_n20_ridge.skill --path-scale 0.05 >"$log" 2>&1; then
    cat "$log"; echo "qemu benchmark (periodic y skill) failed for $target (log: $log)" >&2; exit 1
  fi
  grep -E '^(tick_instructions|commit_tick_instructions|app_tick_instructions|actuator_latency_instructions|budget)' "$log" | sed 's/^/periodic_y_n20: /' || true
  tick_budgets "$target" "$log" 1 periodic_y
  latency_budgets "$target" "$log" periodic_y
done
# the images' objects: no firmware object uses a symbol only the simulator defines
.venv/bin/python tools/check_layers.py --objects build/cortex-m4f --objects build/cortex-m3

# One worker more than the cores (pytest-xdist, one test file each at a time): most of the time of
# the CAN and HIL tests is the simulators' real time, not CPU (on 2 cores: 2 workers kept 1.1 cores
# busy for 8m54s, 3 workers 1.5 cores for 6m15s); FORCESKILL_TEST_WORKERS=N sets it, 1 runs them
# one by one.
WORKERS=${FORCESKILL_TEST_WORKERS:-$(($(nproc) + 1))}
step "Python, HIL and CAN tests ($WORKERS workers)"
export FORCESKILL_HIL_SIM="$ROOT/build/hil_sim/hil_sim"
if [ "$WORKERS" -gt 1 ]; then
  .venv/bin/python -m pytest -q -n "$WORKERS" --dist loadfile tests
else
  .venv/bin/python -m pytest -q tests
fi

step "Linux CAN in a qemu guest (scripts/test_linux_can.sh: the SocketCAN journey on vcan0, the"
echo "   emulated SJA1000 pair, can-utils, CAN FD; one boot under TCG, within 5 min here: docs/hil.md)"
# qemu-system-x86 and the guest's kernel installed first where missing (scripts/vm.sh --setup), so a
# fresh machine runs this part too; FORCESKILL_LINUX_CAN=0 leaves it out
linux_can="${FORCESKILL_LINUX_CAN:-1}"
if [ "$linux_can" = 0 ]; then
  echo "   (not run: FORCESKILL_LINUX_CAN=0)"
else
  if ! command -v qemu-system-x86_64 >/dev/null; then
    scripts/vm.sh --setup
  fi
  rc=0
  scripts/test_linux_can.sh || rc=$?
  if [ "$rc" -ne 0 ]; then # 77: scripts/vm.sh printed its one "vm: skipped:" line: not tested
    echo "Linux CAN tests in the VM failed or could not run (exit $rc)" >&2
    exit "$rc"
  fi
fi

step "clang-format: firmware/ and hil_sim/ match .clang-format (generated code excluded)"
tools/check_format.sh
step "the host package at the lowest dependency versions pyproject.toml allows (.venv-min):"
echo "   host CLI tests and the CAN journey"
scripts/min_venv.sh
printf "suite: every step passed in %dm%02ds\n" $((SECONDS / 60)) $((SECONDS % 60))
