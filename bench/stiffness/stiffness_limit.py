#!/usr/bin/env python3
"""Execution against object stiffness on the HIL simulator: the table of docs/hil.md.

    FORCESKILL_HIL_SIM=build/hil_sim/hil_sim .venv/bin/python bench/stiffness/stiffness_limit.py

For each plant (ideal, realistic) and stiffness k, a synthetic pressing and engraving profile (the
report's, seed 7, 8 s) is fitted at k (gains for a 10 kg object, as `fit --object-mass 10`) and executed by hil_sim on an object of stiffness k
(stiff_<kind>_1e4_exec.toml with k replaced: m_v 10 kg, d_v 50 Ns/m, surface known to 0.5 mm and
taken from the first contact), the device's own stiffness limit lifted (``stiffness_max_Npm``) so
that it executes every k. Prints tracking RMS / max in % of the maximum force, the maximum contact
force, the device's faults (code of the first, pressing / engraving; 0 = none) and whether every run
stayed finite without a limit violation; then, per plant, the stiffness limit (LIMIT_RMS_PCT): the
figure firmware/app/app.h configures (APP_STIFFNESS_MAX_NPM, APP_STIFFNESS_MAX_RENDERED_NPM).
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "host"))

from forceskill.commands.report import STIFF_SEED, SURFACE_M  # noqa: E402
from forceskill.model import synthetic  # noqa: E402
from forceskill.model.fit import fit  # noqa: E402
from forceskill.model.params import gains_for_object  # noqa: E402
from forceskill.sim import find_hil_sim  # noqa: E402

#: The scenario's object mass (m_v): the default gains are scaled down on soft objects as
#: `forceskill fit --object-mass 10` does.
OBJECT_MASS_KG = 10.0
STIFFNESSES = (1e2, 3e2, 1e3, 3e3, 1e4, 2e4, 3e4, 5e4, 1e5, 2e5, 3e5, 5e5, 1e6, 3e6, 1e7)
#: A stiffness is within the device's limit when both profiles track within this RMS (% of the
#: maximum force), with no fault, finite and within the force limit, at it and every softer k
#: from 1e4 N/m up (the range of real surfaces).
LIMIT_RMS_PCT = 5.0
LIMIT_FROM_NPM = 1e4


def run(hil_sim: Path, kind: str, k: float, plant: str, tmp: Path) -> dict:
    demo = synthetic.pressing(STIFF_SEED, 8.0) if kind == "pressing" else synthetic.engraving(STIFF_SEED, 8.0)
    res = fit(demo, k, surface_m=SURFACE_M, gains=gains_for_object(k, OBJECT_MASS_KG))
    skill = tmp / "s.skill"
    res.skill.write(skill)
    text = (REPO / "hil_sim" / "scenarios" / f"stiff_{kind}_1e4_exec.toml").read_text()
    scen = tmp / "scen.toml"
    text = text.replace("k1_Npm = 1e4", f"k1_Npm = {k:g}").replace("k2_Npm = 1e4", f"k2_Npm = {k:g}")
    scen.write_text(text.replace("seed = 1\n", "seed = 1\nstiffness_max_Npm = 1e8\n", 1))
    log = tmp / "log.csv"
    subprocess.run(
        [str(hil_sim), "run", str(scen), "--skill", str(skill), "--plant", plant, "-o", str(log)],
        check=True,
        capture_output=True,
    )
    return json.loads(log.with_suffix(".summary.json").read_text())


def main() -> int:
    hil_sim = find_hil_sim(None, 621)
    print(
        "| plant | k [N/m] | pressing RMS / max [%] | engraving RMS / max [%] | max contact force [N] "
        "| faults | finite, no violation |"
    )
    print("|---|---:|---:|---:|---:|---:|---|")
    limits: dict[str, float] = {}
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        for plant in ("ideal", "realistic"):
            within = True
            for k in STIFFNESSES:
                p = run(hil_sim, "pressing", k, plant, tmp)
                e = run(hil_sim, "engraving", k, plant, tmp)
                ok = all(s["nonfinite_ticks"] == 0 and s["limit_violations"] == 0 for s in (p, e))
                good = ok and all(
                    s["fault_code"] == 0 and s["tracking_rms_pct"] <= LIMIT_RMS_PCT for s in (p, e)
                )
                if k >= LIMIT_FROM_NPM:
                    within = within and good
                    if within:
                        limits[plant] = k
                print(
                    f"| {plant} | {k:.0e} | {p['tracking_rms_pct']:.2f} / {p['tracking_max_pct']:.1f} | "
                    f"{e['tracking_rms_pct']:.2f} / {e['tracking_max_pct']:.1f} | "
                    f"{max(p['max_force_N'], e['max_force_N']):.2f} | {p['fault_code']} / {e['fault_code']} | "
                    f"{'yes' if ok else 'NO'} |"
                )
    for plant in ("ideal", "realistic"):
        k_lim = limits.get(plant)
        text = f"{k_lim:.0e} N/m" if k_lim is not None else f"below {LIMIT_FROM_NPM:.0e} N/m"
        print(
            f"limit {plant}: {text} (RMS <= {LIMIT_RMS_PCT:g} %, no fault, from {LIMIT_FROM_NPM:.0e} N/m up)"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
