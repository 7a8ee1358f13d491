"""forceskill journey: the user's day over CAN against the simulator, end to end.

Starts `hil_sim serve` (pressing task 1 of the paper), then through python-can's socketcand
interface only: record a demonstration in TEACH (.blf), fit it, upload it (UDS, read-back
verified), execute it at goal 1x and 1.5x, and write DIR/can_report.md, DIR/can_summary.json and
DIR/can_tracking.png. Exactly the commands a user types (docs/protocol.md, "The journey over CAN").
Then the demonstrated band (--target host): a skill fitted from six simulator demonstrations of the
task (`hil_sim run --seed 1..6`), run with `--band-action stop` on the object whose inner layer
gives way mid-stroke (pressing_layer_gives.toml): the device stops it with fault 515.
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
#: the band's step: demonstrations (simulator seeds) of the task, the object that gives way, and
#: the time outside the band in one piece that stops the run
BAND_SEEDS = range(1, 7)
BAND_DEMO_SCENARIO = "pressing_task1_demo.toml"
BAND_GIVES_SCENARIO = "pressing_layer_gives.toml"
BAND_MS = 30
FLT_BAND = 515


def _load_csv(path: Path) -> dict[str, np.ndarray]:
    a = np.genfromtxt(path, delimiter=",", names=True)
    return {str(n): np.asarray(a[n]) for n in (a.dtype.names or ())}


def _step(*argv: str, ok: tuple[int, ...] = (0,)) -> int:
    """One command a user types, in its own process (python -m forceskill); its exit code, one
    of ``ok`` or FsError."""
    print("$ forceskill " + " ".join(argv), flush=True)
    rc = subprocess.run([sys.executable, "-m", "forceskill", *argv]).returncode
    if rc not in ok:
        raise FsError(ERR_IO, f"step failed: forceskill {' '.join(argv)}")
    return rc


def _serve(args: argparse.Namespace, hil: Path, scenario: Path) -> tuple[subprocess.Popen[str], list[str]]:
    """Start the device (hil_sim serve, or hil_sim pil for a Cortex-M target) on the scenario;
    the process and the bus options that reach it."""
    if args.target == "host":
        what, cmd = "hil_sim serve", [str(hil), "serve", "--port", "0", "--speed", str(args.speed)]
    else:
        what, cmd = "hil_sim pil", [str(hil), "pil", "--target", args.target, "--port", "0"]
    cmd += ["--scenario", str(scenario), "--host-timeout", str(args.host_timeout)]
    srv = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    line = srv.stdout.readline() if srv.stdout else ""
    if "listening on" not in line:
        _stop(srv)
        raise FsError(
            ERR_IO, f"{what} did not start: {line.strip() or (srv.stderr.read() if srv.stderr else '')}"
        )
    port = int(line.split("127.0.0.1:")[1].split()[0])
    print(line.strip(), flush=True)
    if args.target == "host":
        return srv, ["-i", "socketcand", "-c", "can0", "--bus-kwargs", "host=127.0.0.1", f"port={port}"]
    return srv, ["-i", "slcan", "-c", f"socket://127.0.0.1:{port}"]


def _stop(srv: subprocess.Popen[str]) -> None:
    srv.terminate()
    try:
        srv.communicate(timeout=10)
    except subprocess.TimeoutExpired:
        srv.kill()


def _band_step(args: argparse.Namespace, hil: Path, out: Path) -> dict[str, Any]:
    """The demonstrated band: six simulator demonstrations (seeds), fit, upload to the device on
    the object whose inner layer gives way, run with --band-action stop. Returns the times (s,
    from the execution's start) the layer gave way and the run stopped, and the fault."""
    try:
        import tomllib
    except ModuleNotFoundError:  # Python < 3.11
        import tomli as tomllib  # type: ignore[no-redef,unused-ignore]

    from ..sim import scenario_dir

    t0 = time.perf_counter()
    scenarios = scenario_dir(None)
    gives = scenarios / BAND_GIVES_SCENARIO
    gives_at_s = float(tomllib.loads(gives.read_text())["object"]["gives_at_s"])
    band_dir = out / "band"
    band_dir.mkdir(exist_ok=True)
    demos = []
    for seed in BAND_SEEDS:  # the simulated operator's own timing and levels per seed
        demo = band_dir / f"press{seed}.csv"
        cmd = [str(hil), "run", str(scenarios / BAND_DEMO_SCENARIO), "--seed", str(seed), "-o", str(demo)]
        print("$ " + " ".join(cmd), flush=True)
        if subprocess.run(cmd, stdout=subprocess.DEVNULL).returncode != 0:
            raise FsError(ERR_IO, f"step failed: {' '.join(cmd)}")
        demos.append(str(demo))
    skill = band_dir / "press_band.skill"
    _step(
        "fit",
        *demos,
        "--stiffness",
        str(K_NPM),
        "--object-mass",
        str(OBJECT_MASS_KG),
        "--end",
        "release",
        "-o",
        str(skill),
        "--plot",
        str(out / "can_band_fit.png"),
    )
    srv, bus = _serve(args, hil, gives)
    try:
        _step("upload", str(skill), "--slot", "1", *bus)
        csv = out / "run_band_stop.csv"
        argv = ["run", "--slot", "1", "--band-action", "stop", "--band-ms", str(BAND_MS)]
        _step(*argv, "--csv", str(csv), "--plot", str(out / "can_band.png"), *bus, ok=(0, 2))
    finally:
        _stop(srv)
    cols = _load_csv(csv)
    fault = cols["fault"]
    stopped = bool(np.any(fault > 0))
    code = int(fault[np.argmax(fault > 0)]) if stopped else 0
    t_stop = float(cols["t"][np.argmax(fault > 0)]) if stopped else float("nan")
    wall = time.perf_counter() - t0
    return {
        "gives_at_s": gives_at_s,
        "fault": code,
        "stopped_at_s": t_stop,
        "band_ms": BAND_MS,
        "wall_s": wall,
    }


def _cmd(args: argparse.Namespace) -> int:
    from ..sim import find_hil_sim, scenario_dir
    from ._common import tracking

    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    scenario = Path(args.scenario) if args.scenario else scenario_dir(None) / "pressing_task1_demo.toml"
    if not scenario.is_file():
        raise FsError(ERR_IO, f"scenario not found: {str(scenario)!r}")
    hil = find_hil_sim(args.hil_sim, ERR_IO)
    if args.target != "host" and args.speed != 1.0:
        raise FsError(ERR_IO, f"--speed applies to the simulator only, not to --target {args.target}")
    srv, bus = _serve(args, hil, scenario)
    try:
        t0 = time.perf_counter()
        step = _step

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
        _stop(srv)
    # the band's step on the host build only: one more device start, fit and run, which the
    # journey on a Cortex-M image under qemu does not take on
    band = _band_step(args, hil, out) if args.target == "host" else None
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
    band_text = ""
    if band is not None:
        summary["band"] = band
        band_text = _band_text(band)
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
            + (
                "\n## The demonstrated band\n\nA skill fitted from six simulator demonstrations "
                f"(`hil_sim run {BAND_DEMO_SCENARIO} --seed 1..6`), run with `--band-action stop "
                f"--band-ms {BAND_MS}` on `{BAND_GIVES_SCENARIO}`: {band_text}. Figures: "
                "`can_band_fit.png`, `can_band.png`.\n"
                if band is not None
                else ""
            )
        ).encode(),
    )
    print(f"wrote {out / 'can_report.md'}, {out / 'can_summary.json'}, {out / 'can_tracking.png'}")
    for g, f in figs.items():
        print(f"goal x{g}: tracking max {f['tracking_max_pct']:.2f} %, RMS {f['tracking_rms_pct']:.2f} %")
    if band is not None:
        print(f"band: {band_text}")
        if band["fault"] != FLT_BAND:
            raise FsError(ERR_IO, f"the band's run did not stop with fault {FLT_BAND}: {band_text}")
    return 0


def _band_text(band: dict[str, Any]) -> str:
    """The band step's outcome in one line."""
    if not band["fault"]:
        return f"the inner layer gave way at {band['gives_at_s']:.3f} s and the run was not stopped"
    late = 1e3 * (band["stopped_at_s"] - band["gives_at_s"])
    return (
        f"the inner layer gave way at {band['gives_at_s']:.3f} s; the run stopped with fault "
        f"{band['fault']} at {band['stopped_at_s']:.3f} s, within {late:.0f} ms (this step {band['wall_s']:.1f} s)"
    )


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
