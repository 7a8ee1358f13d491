#!/usr/bin/env bash
# The Linux CAN part of the suite, in a qemu guest (scripts/vm.sh) whose kernel has SocketCAN:
# vcan0 with the CAN FD MTU and two emulated SJA1000 controllers (qemu's kvaser_pci, can0 and
# can1) on one qemu can-bus. One boot, one pytest (one interpreter) over:
#   tests/can/test_socketcan.py           hil_sim serve --socketcan: refusals, python-can clients
#   tests/can/test_journey_socketcan.py   record -> fit -> upload -> run 1x/1.5x on vcan0
#   tests/can/test_linux_can.py           the SJA1000 pair (bit rate, bus-off, restart-ms), can-utils
#                                         (candump -l read by fit), CAN FD on vcan0
# It ends with pytest's summary line. Exit status: pytest's; 77 with one "skipped:" line where qemu
# or the guest's kernel cannot be had (scripts/vm.sh --setup fetches them).
#
#   scripts/test_linux_can.sh [PYTEST ARGS]...   e.g. -k journey, -x
#
# Under qemu's TCG (no hardware virtualisation here) the guest runs 15-20x slower than the host:
# Python there reads about 150 frames/s (not the device's 2,100 of 1 kHz telemetry), so record and
# run ask for telemetry every FORCESKILL_CAN_TELEMETRY_PERIOD_MS (default here 10 ms:
# --telemetry-period) and the simulator runs at FORCESKILL_CAN_SPEED (default here 0.5: half of
# real time, the device's own timing unchanged): 150 frames/s in wall time (0.25 took 1.6x as long);
# the host tools wait FORCESKILL_CAN_TIMEOUT_S (default here 20 s) for the device's frames and
# FORCESKILL_CAN_REQUEST_TIMEOUT_S (15 s: --request-timeout) for each UDS answer, the
# candump's log of a recording may run FORCESKILL_CAN_RECORD_OVERRUN_S (3 s) past its --duration
# (record stops TEACH when its loop reads the last status; record's own log ends there),
# python-can's import leaves out MF4 (FORCESKILL_TEST_NO_MF4=1: asammdf and pandas are most of its
# import time; nothing here reads .mf4) and the guest's copy of the editable install's .pth is a
# plain path (setuptools' import hook costs seconds under TCG at every interpreter start).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
TESTS=(tests/can/test_socketcan.py tests/can/test_journey_socketcan.py tests/can/test_linux_can.py)
# the refusal without AF_CAN cannot happen on a kernel with SocketCAN: it runs on this machine's
# own pytest (where there is none), deselected here (counted in the summary line)
DESELECT=(--deselect tests/can/test_socketcan.py::test_without_af_can_fails_with_one_line)

if [ "${1:-}" = --guest ]; then # inside the guest (root, the host's files under a tmpfs overlay)
  shift
  for pth in .venv/lib/python3*/site-packages/__editable__.forceskill-*.pth; do
    [ -e "$pth" ] && echo "$ROOT/host" >"$pth" # the overlay's copy; the host's file is untouched
  done
  exec .venv/bin/python -m pytest -q -p no:cacheprovider -o console_output_style=classic \
    "${DESELECT[@]}" "${TESTS[@]}" "$@"
fi

[ -x build/hil_sim/hil_sim ] || { echo "test_linux_can: no build/hil_sim/hil_sim (scripts/setup.sh builds it)" >&2; exit 1; }
[ -x .venv/bin/python ] || { echo "test_linux_can: no .venv (scripts/setup.sh creates it)" >&2; exit 1; }
# a fresh clone: the guest's kernel and initramfs first (77 with one line where apt cannot get them)
if [ ! -s build/vm/kernel/.package ] || ! command -v qemu-system-x86_64 >/dev/null; then
  scripts/vm.sh --setup || exit $?
fi
# byte-compile on the host: the guest's writes vanish, so it would compile at every start
.venv/bin/python -m compileall -q host/forceskill tests >/dev/null
set +e
scripts/vm.sh --vcan --kvaser 2 --timeout "${FORCESKILL_VM_TIMEOUT:-900}" \
  --env FORCESKILL_TEST_NO_MF4=1 --env "FORCESKILL_CAN_SPEED=${FORCESKILL_CAN_SPEED:-0.5}" \
  --env "FORCESKILL_CAN_TIMEOUT_S=${FORCESKILL_CAN_TIMEOUT_S:-20}" \
  --env "FORCESKILL_CAN_REQUEST_TIMEOUT_S=${FORCESKILL_CAN_REQUEST_TIMEOUT_S:-15}" \
  --env "FORCESKILL_CAN_TELEMETRY_PERIOD_MS=${FORCESKILL_CAN_TELEMETRY_PERIOD_MS:-10}" \
  --env "FORCESKILL_CAN_RECORD_OVERRUN_S=${FORCESKILL_CAN_RECORD_OVERRUN_S:-3}" \
  --env "FORCESKILL_HIL_SIM=$ROOT/build/hil_sim/hil_sim" \
  -- scripts/test_linux_can.sh --guest "$@"
rc=$?
set -e
exit "$rc" # 77: scripts/vm.sh printed its one "vm: skipped: ..." line
