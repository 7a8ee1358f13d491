"""How many CAN frames per second python-can's socketcan interface reads in this machine: a bare
`bus.recv` loop on vcan0 for --seconds while `cangen` offers 2,000 frames/s (-g 0.5), with the
receive lag at the end (kernel timestamp to the loop). Run in the qemu guest, where it sets the
telemetry period and the simulator speed scripts/test_linux_can.sh uses:

    scripts/vm.sh --vcan -- .venv/bin/python bench/vm_can_rate.py [--seconds S]"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import time

sys.modules.setdefault("asammdf", None)  # python-can's MF4 support is not needed (import time)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--iface", default="vcan0")
    ap.add_argument("--seconds", type=float, default=10.0)
    a = ap.parse_args()
    if shutil.which("cangen") is None:
        print("vm_can_rate: no cangen (can-utils)", file=sys.stderr)
        return 77
    t0 = time.time()
    import can

    t_import = time.time() - t0
    bus = can.Bus(interface="socketcan", channel=a.iface)
    gen = subprocess.Popen(["cangen", a.iface, "-g", "0.5", "-I", "7FF", "-L", "8"])
    n, lag = 0, 0.0
    t1 = time.time()
    try:
        while time.time() - t1 < a.seconds:
            m = bus.recv(0.1)
            if m is not None:
                n += 1
                lag = time.time() - m.timestamp
    finally:
        gen.terminate()
        gen.wait()
        bus.shutdown()
    print(
        f"vm_can_rate: import can {t_import:.1f} s; read {n / a.seconds:.0f} frames/s of 2000 offered; "
        f"receive lag at the end {lag:.2f} s"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
