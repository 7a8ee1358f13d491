"""Benchmark: the host heartbeat's worst gap over a run, as the device sees it.

The device supervises the host in TEACH/EXECUTE: a valid host frame at least every 100 ms
(docs/protocol.md). This runs `hil_sim serve` (real time), puts the device in TEACH with 1 kHz
telemetry (the load of `forceskill record`) and keeps the heartbeat going for --duration seconds
with the product's Device (python-can cyclic task, `--impl cyclic`) or with the former plain
Python thread (`--impl thread`). A second client records the heartbeat frames' bus timestamps
(the simulator's bus time: what the device sees); the host's own send times are kept too.
Printed: worst and 99.9th-percentile gap on the bus and at the host, gaps over 50/100 ms, the
simulator's clock slips, and whether the device stayed in TEACH (it runs with --host-timeout, by
default 500 ms, so that a long gap is measured rather than ending the run).

Usage: heartbeat_gap.py [--hil-sim PATH] [--duration S] [--impl cyclic|thread] [--host-timeout MS]"""

from __future__ import annotations

import argparse
import itertools
import logging
import re
import subprocess
import sys
import threading
import time
from pathlib import Path

import can

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "host"))

from forceskill.link import uds as U  # noqa: E402
from forceskill.link.device import HEARTBEAT_PERIOD_S, Device  # noqa: E402
from forceskill.wire.dbc import load_db  # noqa: E402

logging.getLogger("can.interfaces.socketcand.socketcand").setLevel(logging.ERROR)


class Spy(can.Listener):
    def __init__(self, frame_id: int) -> None:
        self.frame_id = frame_id
        self.t: list[float] = []
        self.states: list[int] = []

    def on_message_received(self, msg: can.Message) -> None:
        if msg.arbitration_id == self.frame_id:
            self.t.append(msg.timestamp)


def gaps_ms(t: list[float]) -> list[float]:
    return [(b - a) * 1e3 for a, b in itertools.pairwise(t)]


def pct(v: list[float], q: float) -> float:
    s = sorted(v)
    return s[min(len(s) - 1, int(q * len(s)))] if s else float("nan")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--hil-sim", default=str(REPO / "build" / "hil_sim" / "hil_sim"))
    ap.add_argument("--duration", type=float, default=60.0)
    ap.add_argument("--impl", choices=("cyclic", "thread"), default="cyclic")
    ap.add_argument("--host-timeout", type=int, default=500)
    args = ap.parse_args()
    srv = subprocess.Popen(
        [
            args.hil_sim,
            "serve",
            "--port",
            "0",
            "--host-timeout",
            str(args.host_timeout),
            "--scenario",
            str(REPO / "hil_sim" / "scenarios" / "pressing_task1_demo.toml"),
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        port = int(srv.stdout.readline().split("127.0.0.1:")[1].split()[0])
        hb_id = {m.name: m.frame_id for m in load_db(0).messages}["HostHeartbeat"]
        spy_bus = can.Bus(interface="socketcand", host="127.0.0.1", port=port, channel="can0")
        spy = Spy(hb_id)
        spy_n = can.Notifier(spy_bus, [spy], timeout=0.05)
        bus = can.Bus(interface="socketcand", host="127.0.0.1", port=port, channel="can0")
        left_teach = None
        with Device(bus, node=0, channel="can0", timeout_s=3.0) as dev:
            dev.wait_present()
            with U.uds_client(dev) as client:
                U.motion_session(client, dev)  # authenticated heartbeats and commands
            dev.telemetry_period_ms = 1
            stop = threading.Event()
            th = None
            if args.impl == "cyclic":
                dev.start_heartbeat(telemetry_period_ms=1)
            else:

                def run() -> None:  # the former implementation (a plain Python thread)
                    nxt = time.monotonic()
                    while not stop.is_set():
                        dev.heartbeat()
                        dev.heartbeat_sent.append(time.monotonic())
                        nxt += HEARTBEAT_PERIOD_S
                        stop.wait(max(0.0, nxt - time.monotonic()))

                th = threading.Thread(target=run, daemon=True)
                th.start()
            dev.command_until("teach", {"TEACH"}, 6.0)
            t0 = time.monotonic()
            while time.monotonic() - t0 < args.duration:
                time.sleep(0.05)
                st = dev.status
                if st is not None and st.state != "TEACH" and left_teach is None:
                    left_teach = f"{st.state} fault {st.fault_code} after {time.monotonic() - t0:.1f} s"
            dev.command_until("idle", {"IDLE"}, 6.0)
            stop.set()
            dev.stop_heartbeat()
            if th is not None:
                th.join()
        spy_n.stop()
        spy_bus.shutdown()
        bus.shutdown()
    finally:
        srv.terminate()
        _, err = srv.communicate(timeout=10)
    slips = re.search(r"(\d+) clock slips", err)
    g_bus, g_host = gaps_ms(spy.t), gaps_ms(dev.heartbeat_sent)
    print(
        f"heartbeat_gap impl={args.impl} duration_s={args.duration:g} period_ms={HEARTBEAT_PERIOD_S * 1e3:g} "
        f"frames_on_bus={len(spy.t)} bus_gap_max_ms={max(g_bus):.1f} bus_gap_p999_ms={pct(g_bus, 0.999):.1f} "
        f"bus_gaps_over_50ms={sum(g > 50 for g in g_bus)} bus_gaps_over_100ms={sum(g > 100 for g in g_bus)} "
        f"host_gap_max_ms={max(g_host):.1f} host_gap_p999_ms={pct(g_host, 0.999):.1f} "
        f"sim_clock_slips={slips.group(1) if slips else '?'} "
        f"teach={'kept' if left_teach is None else 'left: ' + left_teach}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
