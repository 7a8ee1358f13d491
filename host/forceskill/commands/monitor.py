"""forceskill monitor: live state and telemetry of a node (text, or --plot for a live plot)."""

from __future__ import annotations

import argparse
import time

from ..wire import TICK_S
from ._common import add_common, connect


def _cmd(args: argparse.Namespace) -> int:
    with connect(args) as dev:
        tel = dev.start_telemetry()
        if args.rate:  # the rate travels in the heartbeat: authenticated, as every host frame
            from ..link import uds as U

            with U.uds_client(dev, request_timeout_s=2.0) as client:
                U.motion_session(client, dev)
            dev.start_heartbeat(telemetry_period_ms=args.rate)
        t_end = time.monotonic() + args.duration if args.duration else None
        if args.plot:
            import matplotlib.pyplot as plt

            plt.ion()
            _, ax = plt.subplots(figsize=(8, 4))
            lines = {k: ax.plot([], [], label=k)[0] for k in ("f_contact", "f_cmd", "f_ref")}
            ax.set_xlabel("device time [s]")
            ax.set_ylabel("force [N]")
            ax.legend(loc="upper left")
        try:
            while t_end is None or time.monotonic() < t_end:
                time.sleep(0.1)
                st = dev.status
                s = tel.samples[-1] if tel.samples else None
                if args.plot and tel.samples:
                    win = tel.samples[-5000:]
                    t = [x.tick * TICK_S for x in win]
                    lines["f_contact"].set_data(t, [x.f_contact_N for x in win])
                    lines["f_cmd"].set_data(t, [x.f_cmd_N for x in win])
                    lines["f_ref"].set_data(t, [x.f_ref_N for x in win])
                    ax.relim()
                    ax.autoscale_view()
                    plt.pause(0.001)
                elif s is not None and st is not None:
                    print(
                        f"{st.state:8s} fault {st.fault_code:3d}  x {s.x_m * 1e3:8.3f} mm  "
                        f"f_contact {s.f_contact_N:7.2f} N  f_operator {s.f_operator_N:7.2f} N  "
                        f"f_cmd {s.f_cmd_N:7.2f} N  f_ref {s.f_ref_N:7.2f} N",
                        flush=True,
                    )
        except KeyboardInterrupt:
            pass
        finally:
            dev.stop_heartbeat()
    return 0


def register(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = sub.add_parser(
        "monitor",
        help="live values of a device (--plot for a live plot)",
        description="Print the state and the latest telemetry ten times a second "
        "(or plot force over time with --plot) until Ctrl-C or --duration.",
    )
    p.add_argument("--plot", action="store_true", help="live matplotlib plot")
    p.add_argument("--duration", type=float, default=0.0, metavar="S", help="stop after S seconds")
    p.add_argument(
        "--rate",
        type=int,
        default=0,
        metavar="MS",
        help="request telemetry every MS ms via the heartbeat (only in TEACH/EXECUTE; "
        "sending a heartbeat makes this tool a host the device supervises)",
    )
    add_common(p)
    p.set_defaults(func=_cmd)
