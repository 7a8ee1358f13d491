#!/usr/bin/env python3
"""Execution against object stiffness on the HIL simulator: the table of docs/hil.md.

    FORCESKILL_HIL_SIM=build/hil_sim/hil_sim .venv/bin/python bench/stiffness/stiffness_limit.py

For each plant (ideal, realistic) and stiffness k, a synthetic pressing and engraving profile (the
report's, seed 7, 8 s) is fitted at k and executed by hil_sim on an object of stiffness k
(stiff_<kind>_1e4_exec.toml with k replaced: m_v 10 kg, d_v 50 Ns/m, surface known to 0.5 mm and
taken from the first contact). Prints tracking RMS / max in % of the maximum force, the maximum
contact force, and whether every run stayed finite without a limit violation.
"""
from __future__ import annotations

import json
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "host"))

from forceskill.model import synthetic  # noqa: E402
from forceskill.model.fit import fit  # noqa: E402
from forceskill.commands.report import STIFF_SEED, SURFACE_M, find_hil_sim  # noqa: E402

STIFFNESSES = (1e3, 3e3, 1e4, 3e4, 1e5, 3e5, 1e6, 3e6, 1e7)


def run(hil_sim: Path, kind: str, k: float, plant: str, tmp: Path) -> dict:
    demo = synthetic.pressing(STIFF_SEED, 8.0) if kind == "pressing" else synthetic.engraving(STIFF_SEED, 8.0)
    res = fit(demo, k, surface_m=SURFACE_M)
    skill = tmp / "s.skill"
    res.skill.write(skill)
    text = (REPO / "hil_sim" / "scenarios" / f"stiff_{kind}_1e4_exec.toml").read_text()
    scen = tmp / "scen.toml"
    scen.write_text(text.replace("k1_Npm = 1e4", f"k1_Npm = {k:g}").replace("k2_Npm = 1e4", f"k2_Npm = {k:g}"))
    log = tmp / "log.csv"
    subprocess.run([str(hil_sim), "run", str(scen), "--skill", str(skill), "--plant", plant, "-o", str(log)],
                   check=True, capture_output=True)
    return json.loads(log.with_suffix(".summary.json").read_text())


def main() -> int:
    hil_sim = find_hil_sim()
    print("| plant | k [N/m] | pressing RMS / max [%] | engraving RMS / max [%] | max contact force [N] | finite, no violation |")
    print("|---|---:|---:|---:|---:|---|")
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        for plant in ("ideal", "realistic"):
            for k in STIFFNESSES:
                p = run(hil_sim, "pressing", k, plant, tmp)
                e = run(hil_sim, "engraving", k, plant, tmp)
                ok = all(s["nonfinite_ticks"] == 0 and s["limit_violations"] == 0 for s in (p, e))
                print(f"| {plant} | {k:.0e} | {p['tracking_rms_pct']:.2f} / {p['tracking_max_pct']:.1f} | "
                      f"{e['tracking_rms_pct']:.2f} / {e['tracking_max_pct']:.1f} | "
                      f"{max(p['max_force_N'], e['max_force_N']):.2f} | {'yes' if ok else 'NO'} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
