"""The other parts' benchmark programs, run and read by bench/run_all.py.

Each function runs one part's own benchmark (it owns its folder; we only read what it prints)
and returns (markdown body, rows for the targets table, raw data). A part that has not landed,
or whose program fails, gives "not available: <why>" and no number.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

Result = tuple[str, list[list[str]], dict[str, Any]]


def _run(
    cmd: list[str], cwd: Path, timeout: float, env: dict[str, str] | None = None
) -> subprocess.CompletedProcess[str]:
    e = dict(os.environ)
    if env:
        e.update(env)
    return subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=timeout, env=e)


def _na(why: str) -> Result:
    return f"not available: {why}", [], {"not_available": why}


def _kv(line: str) -> dict[str, str]:
    return dict(m.groups() for m in re.finditer(r"([A-Za-z_][\w.\-]*)=(\S+)", line))


def _num(s: str) -> float:
    return float(re.sub(r"[^0-9eE+\-.]", "", s))


def _table(header: list[str], rows: list[list[str]]) -> str:
    out = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    out += ["| " + " | ".join(r) + " |" for r in rows]
    return "\n".join(out)


def _verdict(value: float | None, must: float, aim: float | None, higher: bool) -> str:
    if value is None:
        return "not available"
    ok = (lambda lim: value >= lim) if higher else (lambda lim: value <= lim)
    if aim is not None and ok(aim):
        return "meets must and aim"
    return "meets must" if ok(must) else "**misses must**"


# ---------------------------------------------------------------------------------------------
def _exe(bld: Any, rel: str, part: str) -> tuple[Path | None, str]:
    p = bld.exe(rel)
    if p is not None:
        return p, ""
    failed = getattr(bld, "failed", {})
    if rel in failed:
        return None, failed[rel]
    why = f"{rel} was not built"
    if getattr(bld, "why_not_all", ""):
        why += f" ({bld.why_not_all})"
    return None, why


def hil_speed(root: Path, bld: Any, cfg: dict[str, Any]) -> Result:
    folder = root / "bench" / "hil_speed"
    if not (folder / "CMakeLists.txt").is_file():
        return _na("bench/hil_speed has not landed (no bench/hil_speed)")
    exe, why = _exe(bld, "bench/hil_speed/bench_hil_speed", "hil")
    if exe is None:
        return _na(why)
    p = _run([str(exe)], root, timeout=600)
    rows, data = [], {}
    worst: float | None = None
    for line in p.stdout.splitlines():
        kv = _kv(line)
        if line.startswith("hil_lockstep") and "scenario" in kv:
            x = _num(kv["x_realtime"])
            xl = _num(kv.get("x_realtime_with_log", "nan"))
            sim_s = _num(kv.get("sim_s", "nan"))
            data[kv["scenario"]] = {"x_realtime": x, "x_realtime_with_log": xl, "sim_s": sim_s}
            rows.append([kv["scenario"], f"{sim_s:.1f}", f"{x:,.0f}x", f"{xl:,.0f}x"])
            worst = x if worst is None else min(worst, x)
    if p.returncode != 0 or not rows:
        return _na(f"bench_hil_speed exited {p.returncode}: {(p.stderr or p.stdout).strip()[:200]}")
    body = _table(["scenario", "simulated s", "x real time", "x real time, writing the CSV log"], rows)
    body += (
        "\n\nbench/hil_speed/bench_hil_speed (the HIL part's program, -O2): lockstep, both axes, one "
        "core, the plant integrated in substeps inside each 1 ms firmware tick (10, i.e. 0.1 ms, by default); best of 5 runs per scenario "
        "(best of 3 with the CSV log written to /dev/null). Execution scenarios run the golden N = 50 skills."
    )
    targets = [
        [
            "HIL lockstep speed, both axes, one core (slowest scenario)",
            ">= 1,000x",
            ">= 5,000x",
            f"{worst:,.0f}x",
            _verdict(worst, 1000, 5000, True),
        ]
    ]
    return body, targets, data


def can_upload(root: Path, bld: Any, cfg: dict[str, Any]) -> Result:
    script = root / "bench" / "can_upload" / "can_upload.py"
    if not script.is_file():
        return _na("bench/can_upload has not landed (no bench/can_upload)")
    sim, why = _exe(bld, "hil_sim/hil_sim", "hil")
    if sim is None:
        return _na(why)
    repeat = "3" if cfg.get("quick") else "9"
    try:
        p = _run([sys.executable, str(script), "--hil-sim", str(sim), "--repeat", repeat], root, timeout=600)
    except subprocess.TimeoutExpired:
        return _na("can_upload.py did not finish within 600 s")
    line = next((ln for ln in p.stdout.splitlines() if ln.startswith("can_upload")), None)
    if line is None:
        err = [ln for ln in (p.stdout + p.stderr).splitlines() if ln.strip()]
        return _na(f"can_upload.py exited {p.returncode}: {(err[-1] if err else 'no output')[:200]}")
    kv = _kv(line)
    limit = _num(kv["bus_limited_ms"])
    med = _num(kv["measured_median_ms"])
    best = _num(kv["measured_best_ms"])
    span = _num(kv["bus_span_median_ms"]) if "bus_span_median_ms" in kv else None
    ratio = med / limit
    load = limit / med
    data = dict(kv.items())
    data.update({"ratio": ratio, "bus_load": load, "exit": p.returncode})
    rows = [
        [
            kv.get("kernels", "?"),
            kv.get("bytes", "?"),
            kv.get("frames", "?"),
            f"{limit:.2f}",
            f"{med:.2f}",
            f"{best:.2f}",
            f"{span:.2f}" if span is not None else "n/a",
            f"{ratio:.2f}x",
            f"{100 * load:.0f} %",
        ]
    ]
    body = _table(
        [
            "N",
            "image bytes",
            "frames on the bus",
            "bus-limited ms",
            "measured ms (median)",
            "measured ms (best)",
            "first to last frame on the bus, ms",
            "measured / bus-limited",
            "bus load during the upload",
        ],
        rows,
    )
    body += (
        f"\n\nbench/can_upload/can_upload.py (the CAN part's program, {repeat} uploads): the product's "
        "udsoncan + can-isotp client uploads the skill (RequestDownload, TransferData, RequestTransferExit) to "
        "`hil_sim serve` in real time over the socketcand bus; bus-limited time = the wire time of every frame "
        "of the exchange (both directions, flow control included) at 1 Mbit/s with its actual bit stuffing. "
        "Bus load = bus-limited time / measured time: the share of the bus the transfer kept busy."
    )
    if p.returncode != 0:
        body += f"\n\n- can_upload.py exited {p.returncode} (it fails when the median exceeds 2x the bus-limited time)."
    targets = [
        [
            "skill upload, N = 50, simulated 1 Mbit/s bus (measured / bus-limited)",
            "<= 2x",
            "<= 1.2x",
            f"{ratio:.2f}x",
            _verdict(ratio, 2.0, 1.2, False),
        ]
    ]
    return body, targets, data


QEMU_TARGETS = [
    ("cortex-m4f", "float32 (FPU)", 850, 850),
    ("cortex-m3", "fixed point (DMP + law)", 1250, 1250),
]
TICK_CYCLES = {"168 MHz": 168_000, "72 MHz": 72_000}


def _elf_size(elf: Path) -> tuple[int, int] | None:
    """(flash, RAM) bytes with bench/qemu/image_report.py's definition: flash = .text +
    .ARM.exidx + .data (its load image), RAM = .data + .bss + .stack (reserved stack)."""
    try:
        out = subprocess.run(
            ["arm-none-eabi-size", "-A", str(elf)], capture_output=True, text=True, check=True
        ).stdout
    except (OSError, subprocess.CalledProcessError):
        return None
    sec: dict[str, int] = {}
    for line in out.splitlines():
        f = line.split()
        if len(f) >= 3 and f[0].startswith(".") and f[1].isdigit():
            sec[f[0]] = int(f[1])
    flash = sec.get(".text", 0) + sec.get(".ARM.exidx", 0) + sec.get(".data", 0)
    ram = sec.get(".data", 0) + sec.get(".bss", 0) + sec.get(".stack", 0)
    return flash, ram


def qemu_tick(root: Path, bld: Any, cfg: dict[str, Any]) -> Result:
    script = root / "bench" / "qemu_tick.sh"
    if not script.is_file():
        return _na("bench/qemu_tick.sh has not landed (no bench/qemu_tick.sh)")
    rows, size_rows, notes, targets, app_rows = [], [], [], [], []
    data: dict[str, Any] = {}
    for target, numeric, must, aim in QEMU_TARGETS:
        bdir = bld.dir / f"qemu-{target}"
        cmd = ["bash", str(script), target, "--build-dir", str(bdir)]
        try:
            p = _run(cmd, root, timeout=float(cfg.get("qemu_timeout_s", 600)))
        except subprocess.TimeoutExpired:
            rows.append(
                [target, numeric, f"not available: qemu_tick.sh {target} timed out", "", "", "", "", ""]
            )
            continue
        line = next((ln for ln in p.stdout.splitlines() if ln.startswith("tick_instructions")), None)
        if line is None:
            err = [ln for ln in (p.stdout + p.stderr).splitlines() if ln.strip()]
            rows.append(
                [
                    target,
                    numeric,
                    f"not available: qemu_tick.sh exited {p.returncode}: "
                    f"{(err[-1] if err else 'no output')[:200]}",
                    "",
                    "",
                    "",
                    "",
                    "",
                ]
            )
            continue
        kv = _kv(line)
        lo, med, hi = int(kv["min"]), int(kv["median"]), int(kv["max"])
        data[target] = {
            "min": lo,
            "median": med,
            "max": hi,
            "kernels": kv.get("kernels"),
            "exit": p.returncode,
        }
        shares = [f"{100.0 * hi / c:.2f} %" for c in TICK_CYCLES.values()]
        rows.append([target, numeric, kv.get("kernels", "?"), f"{lo:,}", f"{med:,}", f"{hi:,}", *shares])
        targets.append(
            [
                f"DMP + control law of the product tick, {target} ({numeric}), N = {kv.get('kernels', '?')}, "
                "instructions (max)",
                f"<= {must:,}",
                f"<= {aim:,}",
                f"{hi:,}",
                _verdict(float(hi), must, aim, False),
            ]
        )
        # every figure line of the run, as printed (performance.json), for docs/cortex-m.md
        data[target]["lines"] = [
            ln for ln in p.stdout.splitlines() if ln.split(" ", 1)[0].endswith("_instructions")
        ]
        # the whole app_tick per state and the ticks of a download's commit
        for ln in p.stdout.splitlines():
            if ln.startswith(("app_tick_instructions", "commit_tick_instructions")):
                akv = _kv(ln)
                what = akv.get("state", "commit (any state)")
                app_rows.append(
                    [
                        target,
                        what,
                        *(
                            f"{int(akv[k]):,}" if akv.get(k, "-").isdigit() else "-"
                            for k in ("min", "median", "max", "ticks")
                        ),
                    ]
                )
                data[target][f"app_tick_{what.split()[0].lower()}"] = {
                    k: akv.get(k) for k in ("min", "median", "max", "ticks")
                }
        bench_line = next((ln for ln in p.stdout.splitlines() if ln.startswith("== benchmark:")), "")
        ticks = next((_kv(ln).get("rows") for ln in p.stdout.splitlines() if ln.startswith("bench ")), None)
        data[target]["ticks"] = ticks
        checks = [
            ln.strip()
            for ln in p.stdout.splitlines()
            if ln.startswith(("qemu_vs_host", "loop ", "budget", "counter check"))
        ]
        if p.returncode != 0:
            failed = [c for c in checks if "FAILED" in c] or [f"exit status {p.returncode}"]
            notes.append(
                f"{target}: qemu_tick.sh exited {p.returncode} ({'; '.join(failed)}); "
                f"the instruction count above was printed before that check"
            )
        if bench_line:
            notes.append(
                f"{target}: skill {bench_line.split(':', 1)[1].strip()}, {ticks or '?'} ticks counted"
            )
        notes += [f"{target}: {c}" for c in checks if c.startswith(("qemu_vs_host", "loop "))]
        for img in ("fs_pil",):
            elf = bdir / "firmware" / "ports" / "mps2" / f"{img}.elf"
            sz = _elf_size(elf) if elf.is_file() else None
            if sz is not None:
                data[target][f"{img}_flash"], data[target][f"{img}_ram"] = sz
                size_rows.append([target, f"{img}.elf", f"{sz[0]:,}", f"{sz[1]:,}"])
    if not rows:
        return _na("qemu_tick.sh gave no figure")
    body = _table(
        [
            "target",
            "numeric",
            "N",
            "instructions per tick, min",
            "median",
            "max",
            "share of a 1 ms tick at 168 MHz (max)",
            "at 72 MHz (max)",
        ],
        rows,
    )
    body += (
        "\n\nbench/qemu_tick.sh TARGET (the Cortex-M part's program): the DMP and control-law part "
        "(dmp_step + pfc_step with their callees) of the product image's app_tick, counted instruction by "
        "instruction under qemu (a TCG plugin, bench/qemu/tick_plugin.c) over every EXECUTE tick of the "
        "run (min/median/max; the script "
        "also prints the whole app_tick per state, docs/cortex-m.md). The share "
        "of the tick assumes one cycle per instruction: an approximation (loads, taken branches, divides "
        "and flash wait states take more), so the true cycle share is somewhat higher."
    )
    if app_rows:
        body += "\n\n" + _table(
            ["target", "tick", "whole app_tick, instructions min", "median", "max", "ticks"], app_rows
        )
        body += (
            "\n\nThe whole application tick (app_tick with the UART interrupts taken during it) per "
            "state of the same run, and the ticks that worked on a download's commit (the parse, the "
            "parameter check, the rollout, the flash write: each a bounded slice)."
        )
    if size_rows:
        body += "\n\n" + _table(
            ["target", "image", "flash, bytes", "RAM, bytes (incl. reserved stack)"], size_rows
        )
        body += (
            "\n\nflash = .text + .ARM.exidx + .data, RAM = .data + .bss + .stack (the definition of "
            "bench/qemu/image_report.py), from `arm-none-eabi-size -A`. fs_pil is the product image (the "
            "application on the port, with the simulator's plant linked in)."
        )
    if notes:
        body += "\n\n" + "\n".join(f"- {n}" for n in notes)
    return body, targets, data


def own_benchmarks(root: Path, bld: Any, cfg: dict[str, Any]) -> Result:
    """The core's own step benchmark (bench/core_step) and the fit's (bench/fit_time), run as they
    are, beside this run's figures: a check that the driver here measures what they measure."""
    parts: list[str] = []
    data: dict[str, Any] = {}
    mine = cfg.get("rep_data", {}).get("scaling_kernels", {}).get("median", {})
    if not (root / "bench" / "core_step" / "CMakeLists.txt").is_file():
        parts.append("bench/core_step: not available: it has not landed")
    else:
        exe, why = _exe(bld, "bench/core_step/bench_core_step", "core-c")
        if exe is None:
            parts.append(f"bench/core_step: not available: {why}")
        else:
            p = _run([str(exe)], root, timeout=600)
            rows = []
            for line in p.stdout.splitlines():
                kv = _kv(line)
                if line.startswith("dmp_step") and "N" in kv:
                    n = int(kv["N"])
                    d, f = _num(kv["double"]), _num(kv["float"])
                    data[f"core_step_N{n}"] = {"double": d, "float": f}
                    md = mine.get("C double step, ns", {}).get(n)
                    mf = mine.get("C float step, ns", {}).get(n)
                    rows.append(
                        [
                            str(n),
                            f"{d:.1f}",
                            f"{f:.1f}",
                            f"{md:.1f}" if md else "n/a",
                            f"{mf:.1f}" if mf else "n/a",
                        ]
                    )
            if p.returncode != 0 or not rows:
                parts.append(
                    f"bench/core_step: not available: bench_core_step exited {p.returncode}: "
                    f"{(p.stderr or p.stdout).strip()[:200]}"
                )
            else:
                parts.append(
                    _table(
                        [
                            "N",
                            "bench_core_step double, ns",
                            "bench_core_step float, ns",
                            "fs_bench_step double, ns (this run)",
                            "fs_bench_step float, ns (this run)",
                        ],
                        rows,
                    )
                    + "\n\nbench_core_step (the core part's program) steps its own synthetic models, "
                    "compiled -O2; fs_bench_step steps the skills fitted from the benchmark demonstration "
                    "with the Release libraries."
                )
    script = root / "bench" / "fit_time" / "fit_time.py"
    if not script.is_file():
        parts.append("bench/fit_time: not available: it has not landed")
    else:
        runs = "5" if cfg.get("quick") else "15"
        p = _run([sys.executable, str(script), "--runs", runs], root, timeout=600)
        rows = []
        for line in p.stdout.splitlines():
            kv = _kv(line)
            if line.startswith("fit_ms") and "median" in kv:
                data[f"fit_time_{kv.get('method')}"] = dict(kv.items())
                rows.append(
                    [
                        kv.get("method", "?"),
                        kv.get("N", "?"),
                        kv.get("T", "?"),
                        kv["median"],
                        kv.get("min", "?"),
                        kv.get("err_max", "?"),
                    ]
                )
        if p.returncode != 0 or not rows:
            parts.append(
                f"bench/fit_time: not available: fit_time.py exited {p.returncode}: "
                f"{(p.stderr or p.stdout).strip()[-200:]}"
            )
        else:
            parts.append(
                _table(["method", "N", "demo", "ms (median)", "ms (min)", "max error"], rows)
                + "\n\nbench/fit_time/fit_time.py (the host part's program) fits its own synthetic "
                "17 s engraving demonstration (forceskill.model.synthetic, seed 7)."
            )
    return "\n\n".join(parts), [], data


PARTS: list[tuple[str, Callable[[Path, Any, dict[str, Any]], Result]]] = [
    ("HIL lockstep speed (both axes, one core)", hil_speed),
    ("Skill upload over the simulated 1 Mbit/s CAN bus", can_upload),
    ("Cortex-M control tick under qemu (N = 50)", qemu_tick),
    ("Cross-check: the core's and the fit's own benchmarks", own_benchmarks),
]
