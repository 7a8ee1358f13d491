"""forceskill journey: the user's day over CAN against the simulator, end to end.

Starts `hil_sim serve` (pressing task 1 of the paper), then through python-can's socketcand
interface only: record a demonstration in TEACH (.blf), fit it, upload it (UDS, read-back
verified), execute it at goal 1x and 1.5x, and write DIR/can_report.md, DIR/can_summary.json and
DIR/can_tracking.png. Exactly the commands a user types (docs/protocol.md, "The journey over CAN").
With --target cortex-m4f|cortex-m3 the device is the product's Cortex-M image under qemu
(`hil_sim pil`, docs/cortex-m.md), reached through python-can's slcan interface instead."""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ERR_IO, FsError
from ..model.synthetic import SURFACE_M  # the scenarios' object surface
from ..outputs import write_figure, write_file

K_NPM = 100.0
OBJECT_MASS_KG = 10.0  # m_v_kg of the scenario: the default force gains are adapted to it


def _load_csv(path: Path) -> dict[str, np.ndarray]:
    a = np.genfromtxt(path, delimiter=",", names=True)
    return {str(n): np.asarray(a[n]) for n in (a.dtype.names or ())}


def _cmd(args: argparse.Namespace) -> int:
    from ..sim import find_hil_sim, scenario_dir
    from ._common import tracking

    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    scenario = Path(args.scenario) if args.scenario else scenario_dir(None) / "pressing_task1_demo.toml"
    if not scenario.is_file():
        raise FsError(ERR_IO, f"scenario not found: {str(scenario)!r}")
    hil = find_hil_sim(args.hil_sim, ERR_IO)
    if args.target == "host":
        what, cmd = "hil_sim serve", [str(hil), "serve", "--port", "0", "--speed", str(args.speed)]
    else:
        if args.speed != 1.0:
            raise FsError(ERR_IO, f"--speed applies to the simulator only, not to --target {args.target}")
        what, cmd = "hil_sim pil", [str(hil), "pil", "--target", args.target, "--port", "0"]
    cmd += ["--scenario", str(scenario), "--host-timeout", str(args.host_timeout)]
    srv = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        line = srv.stdout.readline() if srv.stdout else ""
        if "listening on" not in line:
            raise FsError(
                ERR_IO,
                f"{what} did not start: {line.strip() or (srv.stderr.read() if srv.stderr else '')}",
            )
        port = int(line.split("127.0.0.1:")[1].split()[0])
        print(line.strip(), flush=True)
        if args.target == "host":
            bus = ["-i", "socketcand", "-c", "can0", "--bus-kwargs", "host=127.0.0.1", f"port={port}"]
        else:
            bus = ["-i", "slcan", "-c", f"socket://127.0.0.1:{port}"]
        t0 = time.perf_counter()

        def step(*argv: str) -> None:
            # each step is the command a user types, in its own process (python -m forceskill)
            print("$ forceskill " + " ".join(argv), flush=True)
            rc = subprocess.run([sys.executable, "-m", "forceskill", *argv]).returncode
            if rc != 0:
                raise FsError(ERR_IO, f"step failed: forceskill {' '.join(argv)}")

        step("record", "-o", str(out / "demo.blf"), "--duration", str(args.duration), *bus)
        step(
            "fit",
            str(out / "demo.blf"),
            "--stiffness",
            str(K_NPM),
            "--surface-m",
            str(SURFACE_M),
            "--object-mass",
            str(OBJECT_MASS_KG),
            "--end",
            "release",
            "-o",
            str(out / "press.skill"),
            "--plot",
            str(out / "can_fit.png"),
        )
        step("upload", str(out / "press.skill"), "--slot", "1", *bus)
        runs: dict[str, Any] = {}
        for g in ("1", "1.5"):
            csv = out / f"run_goal{g}.csv"
            step(
                "run",
                "--slot",
                "1",
                "--goal-scale",
                g,
                "--csv",
                str(csv),
                "-o",
                str(out / f"run_goal{g}.blf"),
                *bus,
            )
            runs[g] = _load_csv(csv)
        wall = time.perf_counter() - t0
    finally:
        srv.terminate()
        try:
            srv.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            srv.kill()
    figs = {g: tracking(c) for g, c in runs.items()}
    ratio = float(np.max(runs["1.5"]["f_contact"]) / np.max(runs["1"]["f_contact"]))
    summary = {
        "scenario": scenario.name,
        "target": args.target,
        "speed": args.speed,
        "wall_s": wall,
        "runs": [{"goal_scale": float(g), **{k: float(v) for k, v in f.items()}} for g, f in figs.items()],
        "force_ratio_1_5_over_1": ratio,
    }
    write_file(out / "can_summary.json", (json.dumps(summary, indent=2) + "\n").encode())
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 4))
    for g, c in runs.items():
        ax.plot(c["t"], c["f_contact"], lw=1.2, label=f"contact force, goal x{g}")
    for g, c in runs.items():
        ax.plot(c["t"], c["f_hat"], "k--", lw=0.9, label=f"reference f_hat, goal x{g}", zorder=5)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("force [N]")
    link = "hil_sim serve, socketcand" if args.target == "host" else f"{args.target} image, slcan"
    ax.set_title(f"execution over CAN ({link})")
    ax.legend(loc="upper left", fontsize=8)
    write_figure(fig, out / "can_tracking.png", dpi=120)
    where = (
        f"`hil_sim serve` (speed {args.speed:g}), driven through python-can's socketcand interface"
        if args.target == "host"
        else f"the {args.target} image under qemu (`hil_sim pil`), driven through python-can's slcan interface"
    )
    rows = "\n".join(
        f"| {g}x | {f['max_ref_N']:.3f} | {f['max_force_N']:.3f} | {f['tracking_max_pct']:.2f} | "
        f"{f['tracking_rms_pct']:.2f} |"
        for g, f in figs.items()
    )
    write_file(
        out / "can_report.md",
        (
            f"# The journey over CAN\n\nScenario `{scenario.name}` on {where}: record (TEACH) -> fit -> upload (UDS, "
            f"read-back verified) -> run at goal 1x and 1.5x. Wall time {wall:.1f} s.\n\n"
            "| goal | max reference [N] | max contact force [N] | tracking max [%] | tracking RMS [%] |\n"
            "|---|---:|---:|---:|---:|\n"
            + rows
            + f"\n\nForce ratio 1.5x / 1x: {ratio:.3f}. Figures: `can_fit.png`, `can_tracking.png`.\n"
        ).encode(),
    )
    print(f"wrote {out / 'can_report.md'}, {out / 'can_summary.json'}, {out / 'can_tracking.png'}")
    for g, f in figs.items():
        print(f"goal x{g}: tracking max {f['tracking_max_pct']:.2f} %, RMS {f['tracking_rms_pct']:.2f} %")
    return 0


def register(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = sub.add_parser(
        "journey",
        help="record -> fit -> upload -> run 1x/1.5x over CAN on the simulator",
        description=__doc__,
    )
    p.add_argument("-o", "--output", default="can_journey", metavar="DIR")
    p.add_argument(
        "--hil-sim",
        metavar="PATH",
        help="hil_sim binary (default $FORCESKILL_HIL_SIM, else hil_sim on PATH, else this checkout's build)",
    )
    p.add_argument(
        "--scenario",
        metavar="TOML",
        help="simulator scenario (default: the packaged pressing_task1_demo.toml)",
    )
    p.add_argument(
        "--target",
        choices=("host", "cortex-m4f", "cortex-m3"),
        default="host",
        help="the device: host = the firmware in hil_sim serve (socketcand); cortex-m4f / cortex-m3 = "
        "the product's Cortex-M image under qemu (hil_sim pil, slcan)",
    )
    p.add_argument("--speed", type=float, default=1.0, metavar="S", help="simulator speed factor (1)")
    p.add_argument("--duration", type=float, default=6.0, metavar="S", help="demonstration length (6 s)")
    p.add_argument(
        "--host-timeout",
        type=int,
        default=250,
        metavar="MS",
        help="device's host-silence timeout in the simulator (250 ms: host tools and "
        "simulator share one machine; the product default is 100)",
    )
    p.set_defaults(func=_cmd)
