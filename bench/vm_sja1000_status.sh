#!/usr/bin/env bash
# UDS over the qemu guest's emulated SJA1000 pair (scripts/vm.sh --kvaser 2): `hil_sim serve
# --socketcan can0` and N `forceskill status` on can1 (each reads five identifiers, three of them
# multi-frame answers), then how many completed and what the controllers counted (`ip -s link`:
# a receive error is a frame qemu's 64-byte receive FIFO could not take).
#   bench/vm_sja1000_status.sh [N]     (default 6; boots the guest itself)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
if [ "${1:-}" != --guest ]; then
  .venv/bin/python -m compileall -q host/forceskill >/dev/null
  exec scripts/vm.sh --kvaser 2 --timeout 900 --env "N=${1:-6}" -- "$0" --guest
fi
for pth in .venv/lib/python3*/site-packages/__editable__.forceskill-*.pth; do
  [ -e "$pth" ] && echo "$ROOT/host" >"$pth" # the guest's copy (scripts/test_linux_can.sh)
done
ip link set can1 type can bitrate 500000 restart-ms 100
ip link set can1 up
build/hil_sim/hil_sim serve --socketcan can0 --bitrate 500000 --speed 0.25 \
  --scenario hil_sim/scenarios/pressing_task1_demo.toml --host-timeout 500 >/dev/null 2>/tmp/sim.err &
sim=$!
sleep 1
FORCESKILL_TEST_NO_MF4=1 .venv/bin/python - <<'PY'
import contextlib
import io
import os
import sys
import time

sys.modules.setdefault("asammdf", None)  # python-can without MF4 (tests/conftest.py)
from forceskill import cli

n, ok = int(os.environ["N"]), 0
for i in range(n):
    t = time.monotonic()
    with contextlib.redirect_stdout(io.StringIO()):  # the status itself is not the figure
        rc = cli.main(["status", "-i", "socketcan", "-c", "can1", "--timeout", "20", "--request-timeout", "15"])
    ok += rc == 0
    print(f"status {i + 1}: exit {rc}, {time.monotonic() - t:.2f} s", file=sys.stderr)
print(f"status on can1: {ok} of {n} completed")
PY
kill "$sim"
wait "$sim" || true
tail -n 1 /tmp/sim.err
for i in can0 can1; do
  ip -s link show "$i" | awk -v i="$i" '/RX:/ {getline; print i ": received " $2 " frames, " $3 " receive errors"}'
done
