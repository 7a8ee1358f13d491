"""``forceskill report -o DIR``: every experiment of the paper, end to end, on the HIL simulator.

For each learning task (pressing 1/2, engraving 1/2): the demonstration runs in TEACH on the
simulator (``hil_sim run hil_sim/scenarios/<task>_demo.toml``), is fitted with the default fit
(ridge, N = 50) and with the paper's LWR (N = 50, then the smallest N in 50..100 that meets the
paper's bound), and the default skill is executed on the same object. The engraving operators
move along y while varying the force (paper Fig. 6) on a surface with Coulomb friction: their
skills also learn the y path (``fit --y-column y``), and the report gives the path tracking of
the execution (measured y against the learned path, mm) and draws both halves. Reuse: the two engraving
skills in series (8 s then 9 s) on 200 N/m at goal 1x, on 300 N/m at 1.5x, and on 300 N/m at 1x
(no scaling) for comparison. Writes DIR/report.md, DIR/summary.json, DIR/fig_*.png, and keeps
the logs (DIR/logs) and skills (DIR/skills).

The simulator binary: ``--hil-sim PATH``, else ``$FORCESKILL_HIL_SIM``, else ``hil_sim`` on PATH,
else the checkout's own ``build/hil_sim/hil_sim``.
Scenarios: ``--scenarios DIR``, else the paper scenarios packaged with forceskill.
"""

from __future__ import annotations

import argparse
import json
import subprocess
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ERR_REPORT, FsError
from ..model.synthetic import INNER_LAYER_M as LAYER_X_M
from ..model.synthetic import SURFACE_M
from ..outputs import write_figure, write_file

#: Paper bounds on the LWR approximation error (% of max force): pressing <= 4, engraving <= 6.
LWR_BOUND_PCT = {"pressing": 4.0, "engraving": 6.0}
LWR_KERNELS = (50, 60, 70, 80, 90, 100)
#: mass of every object of the HIL scenarios (m_v_kg in hil_sim/scenarios/*.toml): the force gains
#: are adapted to it (k_f*m_v/m_d <= 0.75)
OBJECT_MASS_KG = 10.0


@dataclass(frozen=True)
class Task:
    """One learning experiment of the paper."""

    name: str
    kind: str  # pressing | engraving
    stiffness_Npm: float
    end_policy: str
    figure: str  # the paper's figure


TASKS = (
    Task("pressing_task1", "pressing", 100.0, "release", "Fig. 5"),
    Task("pressing_task2", "pressing", 500.0, "release", "Fig. 5"),
    Task("engraving_task1", "engraving", 100.0, "hold", "Fig. 6"),
    Task("engraving_task2", "engraving", 280.0, "hold", "Fig. 6"),
)
#: Reuse runs: (name, scenario, goal scale); deformation is compared over the two steps (17 s).
REUSE = (
    ("reuse_200_1x", "reuse_200_1x", 1.0),
    ("reuse_300_1_5x", "reuse_300_1_5x", 1.5),
    ("reuse_300_1x_unscaled", "reuse_300_1_5x", 1.0),
)
REUSE_WINDOW_S = 17.0
#: Execution on stiff objects: (kind, stiffness). The skill is fitted at that stiffness from a
#: synthetic profile shaped like the paper's (8 s); the scenario stiff_<kind>_<k>_exec.toml runs it
#: with the surface known to 0.5 mm only.
STIFF = (("pressing", "1e4"), ("pressing", "1e5"), ("engraving", "1e4"), ("engraving", "1e5"))
STIFF_SEED = 7


def run_sim(hil_sim: Path, scenario: Path, log: Path, *extra: str) -> dict[str, Any]:
    """Run one scenario; returns its summary (raises FsError with hil_sim's message on failure)."""
    cmd = [str(hil_sim), "run", str(scenario), "-o", str(log), *extra]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        msg = (r.stderr.strip().splitlines() or ["no message"])[0]
        raise FsError(ERR_REPORT, f"hil_sim failed on {scenario.name} (exit {r.returncode}): {msg}")
    summary: dict[str, Any] = json.loads(log.with_suffix(".summary.json").read_text())
    return summary


def read_log(path: Path) -> dict[str, np.ndarray]:
    """A hil_sim CSV log as columns."""
    data = np.genfromtxt(path, delimiter=",", names=True)
    return {k: np.asarray(data[k], dtype=float) for k in data.dtype.names or ()}


def deformation(log: dict[str, np.ndarray], surface_m: float = SURFACE_M) -> np.ndarray:
    """Object deformation p = x - surface (>= 0) from a log."""
    return np.maximum(log["x"] - surface_m, 0.0)


def deformation_diff_pct(
    p_ref: np.ndarray, p_other: np.ndarray, t: np.ndarray, window_s: float = REUSE_WINDOW_S
) -> float:
    """max |p_other - p_ref| / max p_ref over t <= window_s, in %."""
    n = min(p_ref.size, p_other.size)
    m = t[:n] <= window_s + 1e-9
    return float(100.0 * np.max(np.abs(p_other[:n][m] - p_ref[:n][m])) / np.max(p_ref[:n][m]))


def path_tracking_mm(skill: Any, ex: dict[str, np.ndarray], time_scale: float = 1.0) -> dict[str, float]:
    """Executed y (the execution log: row n is the device's n-th tick of the skill) against the
    learned path from where execution started, y(0) + p_n (dmp.rollout_path), over the skill's
    rows: max and RMS in mm."""
    from ..model.dmp import rollout_path

    _, y_hat = rollout_path(skill, time_scale=time_scale)
    p = y_hat - skill.y_start_m
    m = min(p.size, ex["y"].size)
    e = ex["y"][:m] - (ex["y"][0] + p[:m])
    return {
        "path_max_mm": 1e3 * float(np.max(np.abs(e))),
        "path_rms_mm": 1e3 * float(np.sqrt(np.mean(e * e))),
        "path_extent_mm": 1e3 * float(np.max(p) - np.min(p)),
    }


def _pct(x: float | None) -> str:
    return "-" if x is None else f"{x:.2f}"


def _learn(
    task: Task, hil_sim: Path, scen: Path, out: Path, seed: int, n_kernels: int, plots: bool
) -> dict[str, Any]:
    from ..model.demo import load_demo
    from ..model.fit import fit
    from ..model.params import gains_for_object

    demo_log = out / "logs" / f"{task.name}_demo.csv"
    demo_sum = run_sim(hil_sim, scen / f"{task.name}_demo.toml", demo_log, "--seed", str(seed))
    with_path = task.kind == "engraving"
    demo = load_demo(demo_log, y_column="y" if with_path else None)
    gains = gains_for_object(task.stiffness_Npm, OBJECT_MASS_KG)

    def fit_n(n: int, method: str) -> Any:
        return fit(
            demo,
            task.stiffness_Npm,
            n_kernels=n,
            method=method,
            surface_m=SURFACE_M,
            end_policy=task.end_policy,
            gains=gains,
        )

    res = fit_n(n_kernels, "ridge")
    lwr50 = fit_n(50, "lwr")
    bound = LWR_BOUND_PCT[task.kind]
    lwr_n, lwr_at_n = None, None
    for n in LWR_KERNELS:
        r = lwr50 if n == 50 else fit_n(n, "lwr")
        if r.err_max_pct <= bound:
            lwr_n, lwr_at_n = n, r
            break
    skill_path = out / "skills" / f"{task.name}.skill"
    res.skill.write(skill_path)
    exec_log = out / "logs" / f"{task.name}_exec.csv"
    ex = run_sim(
        hil_sim, scen / f"{task.name}_exec.toml", exec_log, "--seed", str(seed), "--skill", str(skill_path)
    )
    entry: dict[str, Any] = {
        "name": task.name,
        "kind": task.kind,
        "figure": task.figure,
        "stiffness_Npm": task.stiffness_Npm,
        "max_force_N": float(np.max(demo.force_N)),
        "approx_max_pct": res.err_max_pct,
        "approx_rms_pct": res.err_rms_pct,
        "n_kernels": n_kernels,
        "approx_max_pct_lwr": lwr50.err_max_pct,
        "approx_rms_pct_lwr": lwr50.err_rms_pct,
        "lwr_bound_pct": bound,
        "lwr_kernels_needed": lwr_n,
        "approx_max_pct_lwr_needed": None if lwr_at_n is None else lwr_at_n.err_max_pct,
        "tracking_max_pct": ex["tracking_max_pct"],
        "tracking_rms_pct": ex["tracking_rms_pct"],
        "exec_max_force_N": ex["max_force_N"],
        "max_cmd_abs_N": ex["max_cmd_abs_N"],
        "force_limit_N": ex["force_limit_N"],
        "limit_violations": ex["limit_violations"],
        "deformation_max_m": demo_sum["deformation_max_m"],
        "layer_reached_s": demo_sum["layer_reached_s"],
        "skill": str(skill_path),
        "demo_log": str(demo_log),
        "exec_log": str(exec_log),
    }
    if with_path:
        entry.update(path_tracking_mm(res.skill, read_log(exec_log)))
        entry["path_fit_max_mm"] = res.y_err_max_mm
        entry["path_fit_rms_mm"] = res.y_err_rms_mm
    if plots:
        _learn_figure(task, res, lwr50, read_log(demo_log), read_log(exec_log), out / f"fig_{task.name}.png")
    return entry


#: Figures of an execution's summary (run_sim) that every report row carries, in this order.
TRACKING_FIELDS = (
    "tracking_max_pct",
    "tracking_rms_pct",
    "max_cmd_abs_N",
    "force_limit_N",
    "limit_violations",
)


def _tracking(summary: dict[str, Any], *extra: str) -> dict[str, Any]:
    """The TRACKING_FIELDS of an execution summary, then the extra ones named."""
    return {k: summary[k] for k in TRACKING_FIELDS + extra}


def _reuse(hil_sim: Path, scen: Path, out: Path, seed: int, plots: bool) -> list[dict[str, Any]]:
    skills = [str(out / "skills" / "engraving_task1.skill"), str(out / "skills" / "engraving_task2.skill")]
    logs: dict[str, dict[str, np.ndarray]] = {}
    sums: dict[str, dict[str, Any]] = {}
    for name, scenario, goal in REUSE:
        log = out / "logs" / f"{name}.csv"
        sums[name] = run_sim(
            hil_sim,
            scen / f"{scenario}.toml",
            log,
            "--seed",
            str(seed),
            "--skill",
            *skills,
            "--goal-scale",
            repr(goal),
        )
        logs[name] = read_log(log)
    t = logs["reuse_200_1x"]["t"]
    p200 = deformation(logs["reuse_200_1x"])
    d_scaled = deformation_diff_pct(p200, deformation(logs["reuse_300_1_5x"]), t)
    d_unscaled = deformation_diff_pct(p200, deformation(logs["reuse_300_1x_unscaled"]), t)
    entries = []
    for name, _, goal in REUSE:
        s = sums[name]
        entries.append(
            {
                "name": name,
                "kind": "reuse",
                "figure": "Fig. 7",
                "goal_scale": goal,
                "stiffness_Npm": 200.0 if "200" in name else 300.0,
                "max_force_N": s["max_force_N"],
                "approx_max_pct": None,
                "approx_rms_pct": None,
                "approx_max_pct_lwr": None,
                "approx_rms_pct_lwr": None,
                **_tracking(s, "deformation_max_m"),
                "deformation_diff_pct": None
                if name == "reuse_200_1x"
                else (d_scaled if name == "reuse_300_1_5x" else d_unscaled),
                "deformation_diff_unscaled_pct": d_unscaled if name == "reuse_300_1_5x" else None,
                "exec_log": str(out / "logs" / f"{name}.csv"),
            }
        )
    if plots:
        _reuse_figure(logs, d_scaled, d_unscaled, out / "fig_reuse.png")
    return entries


def _stiff(hil_sim: Path, scen: Path, out: Path, seed: int, n_kernels: int) -> list[dict[str, Any]]:
    from ..model import synthetic
    from ..model.fit import fit

    entries = []
    for kind, k_txt in STIFF:
        k = float(k_txt)
        demo = (
            synthetic.pressing(STIFF_SEED, 8.0)
            if kind == "pressing"
            else synthetic.engraving(STIFF_SEED, 8.0)
        )
        res = fit(demo, k, n_kernels=n_kernels, surface_m=SURFACE_M)
        name = f"stiff_{kind}_{k_txt}"
        skill_path = out / "skills" / f"{name}.skill"
        res.skill.write(skill_path)
        log = out / "logs" / f"{name}_exec.csv"
        s = run_sim(hil_sim, scen / f"{name}_exec.toml", log, "--seed", str(seed), "--skill", str(skill_path))
        entries.append(
            {
                "name": name,
                "kind": "stiff",
                "figure": "-",
                "stiffness_Npm": k,
                "max_force_N": s["max_force_N"],
                "approx_max_pct": res.err_max_pct,
                "approx_rms_pct": res.err_rms_pct,
                "approx_max_pct_lwr": None,
                "approx_rms_pct_lwr": None,
                **_tracking(s, "saturated_ticks", "nonfinite_ticks", "deformation_max_m"),
                "skill": str(skill_path),
                "exec_log": str(log),
            }
        )
    return entries


# ---- figures -----------------------------------------------------------------------------------


def _plt() -> Any:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _learn_figure(
    task: Task, res: Any, lwr: Any, demo: dict[str, np.ndarray], ex: dict[str, np.ndarray], path: Path
) -> None:
    plt = _plt()
    t = res.t_s
    f_max = float(np.max(np.abs(res.target_N)))
    rows = 4
    fig, ax = plt.subplots(rows, 1, figsize=(7.5, 2.2 * rows + 0.6))
    ax[0].plot(t, res.target_N, "k--", lw=1.2, label="demonstrated (contact)")
    ax[0].plot(t, res.f_hat_N, "g-", lw=1.0, label=f"learned, ridge N={res.skill.n_kernels}")
    ax[0].plot(t, lwr.f_hat_N, color="tab:orange", lw=0.8, alpha=0.8, label="learned, LWR N=50")
    ax[0].set_ylabel("force [N]")
    ax[0].legend(fontsize=7, loc="best")
    ax[0].set_title(f"{task.name} ({task.figure}): k = {task.stiffness_Npm:g} N/m", fontsize=10)
    ax[1].plot(
        t,
        100.0 * (res.target_N - res.f_hat_N) / f_max,
        "g-",
        lw=0.8,
        label=f"ridge: max {res.err_max_pct:.2f} %",
    )
    ax[1].plot(
        t,
        100.0 * (lwr.target_N - lwr.f_hat_N) / f_max,
        color="tab:orange",
        lw=0.6,
        label=f"LWR N=50: max {lwr.err_max_pct:.2f} %",
    )
    ax[1].set_ylabel("error [% max]")
    ax[1].legend(fontsize=7, loc="best")
    r = 2
    if task.kind == "pressing":
        x = demo["x"]
        ax[2].plot(demo["t"], 1e3 * x, "b-", lw=1.0, label="demonstrated position")
        ax[2].axhline(1e3 * LAYER_X_M, color="0.5", ls=":", lw=0.8, label="inner layer (0.020 m)")
        hit = np.nonzero(x >= LAYER_X_M)[0]
        if hit.size:
            ax[2].plot(demo["t"][hit[0]], 1e3 * x[hit[0]], "ro", ms=6, label="inner layer reached")
        ax[2].set_ylabel("x [mm]")
        ax[2].legend(fontsize=7, loc="best")
    else:
        y0 = float(demo["y"][0])
        ax[2].plot(demo["t"], 1e3 * (demo["y"] - y0), "k--", lw=1.2, label="demonstrated y path")
        if res.y_hat_m.size:
            ax[2].plot(t, 1e3 * (res.y_hat_m - y0), "g-", lw=0.8, label="learned")
        ax[2].plot(ex["t"], 1e3 * (ex["y"] - float(ex["y"][0])), "b-", lw=0.7, label="executed")
        ax[2].set_ylabel("y from start [mm]")
        ax[2].legend(fontsize=7, loc="best")
    r = 3
    ax[r].plot(ex["t"], ex["f_hat"], "g--", lw=1.2, label="learned f_hat")
    ax[r].plot(ex["t"], ex["f_contact"], "b-", lw=0.7, label="measured (execution)")
    ax[r].set_ylabel("force [N]")
    ax[r].set_xlabel("t [s]")
    ax[r].legend(fontsize=7, loc="best")
    for a in ax:
        a.grid(True, lw=0.3)
    write_figure(fig, path)


def _reuse_figure(
    logs: dict[str, dict[str, np.ndarray]], d_scaled: float, d_unscaled: float, path: Path
) -> None:
    plt = _plt()
    a, b, c = logs["reuse_200_1x"], logs["reuse_300_1_5x"], logs["reuse_300_1x_unscaled"]
    fig, ax = plt.subplots(3, 1, figsize=(8.0, 8.5))
    ax[0].plot(a["t"], a["f_hat"], "g--", lw=1.2, label="learned (1x)")
    ax[0].plot(b["t"], b["f_hat"], "r-", lw=1.0, label="scaled (1.5x)")
    ax[0].axvline(8.0, color="0.6", ls=":", lw=0.8)
    ax[0].set_ylabel("force [N]")
    ax[0].set_title("reuse (Fig. 7): engraving skills 1 then 2 (8 s + 9 s)", fontsize=10)
    ax[0].legend(fontsize=7)
    ax[1].plot(b["t"], b["f_hat"], "r-", lw=1.2, label="scaled f_hat, 300 N/m")
    ax[1].plot(b["t"], b["f_contact"], "k--", lw=0.7, label="measured")
    ax[1].plot(a["t"], a["f_contact"], color="tab:blue", lw=0.7, label="measured, 200 N/m at 1x")
    ax[1].set_ylabel("force [N]")
    ax[1].legend(fontsize=7)
    ax[2].plot(a["t"], 1e3 * deformation(a), "b-", lw=1.2, label="200 N/m, goal 1x")
    ax[2].plot(
        b["t"], 1e3 * deformation(b), "r--", lw=1.2, label=f"300 N/m, goal 1.5x (max diff {d_scaled:.1f} %)"
    )
    ax[2].plot(
        c["t"],
        1e3 * deformation(c),
        color="0.5",
        ls=":",
        lw=1.2,
        label=f"300 N/m, goal 1x (max diff {d_unscaled:.1f} %)",
    )
    ax[2].set_ylabel("deformation [mm]")
    ax[2].set_xlabel("t [s]")
    ax[2].legend(fontsize=7)
    for x in ax:
        x.grid(True, lw=0.3)
    write_figure(fig, path)


# ---- report ------------------------------------------------------------------------------------


def write_markdown(summary: dict[str, Any], path: Path) -> None:
    """DIR/report.md: one table row per experiment."""
    lines = [
        "# forceskill: the paper's experiments on the HIL simulator",
        "",
        f"hil_sim `{summary['hil_sim']}`, seed {summary['seed']}, default fit ridge N = {summary['n_kernels']}, "
        "ideal plant. Errors in % of the maximum force; approximation error against the recorded "
        "(noisy) contact force; tracking = measured contact force vs f_hat during execution.",
        "",
        "| experiment | max force [N] | approx. max/RMS LWR N=50 [%] | LWR N for the paper's bound | "
        "approx. max/RMS default [%] | tracking max/RMS [%] | path tracking max/RMS [mm] | "
        "deformation diff [%] | limit violations |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for e in summary["experiments"]:
        lwr = (
            "-"
            if e["approx_max_pct_lwr"] is None
            else f"{e['approx_max_pct_lwr']:.2f} / {e['approx_rms_pct_lwr']:.2f}"
        )
        if e["kind"] in ("reuse", "stiff"):
            need = "-"
        elif e["lwr_kernels_needed"] is None:
            need = f"> 100 (bound {e['lwr_bound_pct']:g} %)"
        else:
            need = f"{e['lwr_kernels_needed']} ({e['approx_max_pct_lwr_needed']:.2f} % <= {e['lwr_bound_pct']:g} %)"
        dflt = (
            "-" if e["approx_max_pct"] is None else f"{e['approx_max_pct']:.2f} / {e['approx_rms_pct']:.2f}"
        )
        trk = f"{e['tracking_max_pct']:.2f} / {e['tracking_rms_pct']:.2f}"
        ptrk = f"{e['path_max_mm']:.2f} / {e['path_rms_mm']:.2f}" if "path_rms_mm" in e else "-"
        dd = e.get("deformation_diff_pct")
        ddu = e.get("deformation_diff_unscaled_pct")
        dtxt = "-" if dd is None else (f"{dd:.2f} (unscaled {ddu:.2f})" if ddu is not None else f"{dd:.2f}")
        lines.append(
            f"| {e['name']} | {e['max_force_N']:.2f} | {lwr} | {need} | {dflt} | {trk} | {ptrk} | {dtxt} | "
            f"{e['limit_violations']} |"
        )
    lines += [
        "",
        "Path tracking (engraving: the operator moves along y on a surface with Coulomb friction "
        "0.3 x the contact force): measured y against the learned path from where execution "
        "started, over the skill's duration.",
        "",
        "Deformation difference: max over t <= 17 s of |p(t) - p_200@1x(t)| / max p_200@1x, with "
        "p = x - 0.001 m. stiff_*: a synthetic profile fitted at 1e4 / 1e5 N/m, executed on that "
        "object with the surface known to 0.5 mm (the firmware takes it from the first contact "
        "measurement).",
        "",
    ]
    figs = sorted(p.name for p in path.parent.glob("fig_*.png"))
    for f in figs:
        lines.append(f"![{f}]({f})")
    write_file(path, ("\n".join(lines) + "\n").encode())


def run_report(
    out: Path,
    hil_sim: Path,
    scenarios: Path,
    seed: int = 1,
    n_kernels: int = 50,
    plots: bool = True,
    progress: bool = True,
) -> dict[str, Any]:
    """Run every experiment; write report.md, summary.json and the figures into out."""
    from tqdm import tqdm

    for sub in ("logs", "skills"):
        (out / sub).mkdir(parents=True, exist_ok=True)
    steps = [t.name for t in TASKS] + ["reuse", "stiff"]
    experiments: list[dict[str, Any]] = []
    with tqdm(total=len(steps), desc="paper experiments", unit="exp", disable=not progress) as bar:
        for task in TASKS:
            bar.set_postfix_str(task.name)
            experiments.append(_learn(task, hil_sim, scenarios, out, seed, n_kernels, plots))
            bar.update(1)
        bar.set_postfix_str("reuse")
        experiments.extend(_reuse(hil_sim, scenarios, out, seed, plots))
        bar.update(1)
        bar.set_postfix_str("stiff")
        experiments.extend(_stiff(hil_sim, scenarios, out, seed, n_kernels))
        bar.update(1)
    summary = {"seed": seed, "n_kernels": n_kernels, "hil_sim": str(hil_sim), "experiments": experiments}
    write_file(out / "summary.json", (json.dumps(summary, indent=2) + "\n").encode())
    write_markdown(summary, out / "report.md")
    return summary


def _cmd_report(args: argparse.Namespace) -> int:
    out = Path(args.output)
    from ..sim import find_hil_sim, scenario_dir

    hil_sim = find_hil_sim(args.hil_sim, ERR_REPORT)
    scen = scenario_dir(args.scenarios)
    if not (scen / "pressing_task1_demo.toml").is_file():
        raise FsError(ERR_REPORT, f"scenario folder without the paper scenarios: {str(scen)!r}")
    out.mkdir(parents=True, exist_ok=True)
    summary = run_report(
        out,
        hil_sim,
        scen,
        seed=args.seed,
        n_kernels=args.kernels,
        plots=not args.no_plots,
        progress=not args.quiet,
    )
    for e in summary["experiments"]:
        extra = ""
        if e["approx_max_pct_lwr"] is not None:
            extra = (
                f" approx max {e['approx_max_pct']:.2f} % (LWR N=50 {e['approx_max_pct_lwr']:.2f} %, "
                f"bound met at N={e['lwr_kernels_needed']})"
            )
        elif e["approx_max_pct"] is not None:
            extra = f" approx max {e['approx_max_pct']:.2f} %, k = {e['stiffness_Npm']:g} N/m"
        if e.get("deformation_diff_pct") is not None:
            extra += f" deformation diff {e['deformation_diff_pct']:.2f} %"
        print(
            f"{e['name']:24s} max {e['max_force_N']:6.2f} N, tracking max/RMS "
            f"{e['tracking_max_pct']:.2f}/{e['tracking_rms_pct']:.2f} %{extra}"
        )
    print(f"wrote {out / 'report.md'}, {out / 'summary.json'} and the figures")
    return 0


def register(subparsers: Any) -> None:
    """Add ``forceskill report``."""
    p = subparsers.add_parser(
        "report",
        help="run every paper experiment on the HIL simulator",
        description="Demonstrate, fit, execute and reuse every experiment of the paper "
        "on the HIL simulator; write DIR/report.md, DIR/summary.json and figures.",
    )
    p.add_argument("-o", "--output", required=True, metavar="DIR", help="output folder (created)")
    p.add_argument(
        "--hil-sim",
        metavar="PATH",
        help="hil_sim binary (default $FORCESKILL_HIL_SIM, else hil_sim on PATH, else this checkout's build)",
    )
    p.add_argument(
        "--scenarios", metavar="DIR", help="scenario folder (default: the packaged paper scenarios)"
    )
    p.add_argument("--seed", type=int, default=1, help="operator/sensor seed (1)")
    p.add_argument("--kernels", type=int, default=50, metavar="N", help="kernels of the default fit (50)")
    p.add_argument("--no-plots", action="store_true", help="skip the figures")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=_cmd_report)
