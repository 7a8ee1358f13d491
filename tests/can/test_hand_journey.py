"""The journey typed by hand as the README shows it, on the demo's simulator
(`hil_sim serve --scenario hil_sim/scenarios/pressing_task1_demo.toml`, a 10 kg object on a
100 N/m outer layer): `record`, `fit` without `--object-mass`, `upload`, `run`. The recording
holds the device's object model, so `fit` makes the gains for the 10 kg object and the run
tracks without a fault; a skill whose gains the object makes unstable is refused by `run`
before anything moves, naming the remedy."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from forceskill import cli
from forceskill.model import synthetic
from forceskill.model.demo import write_csv
from helpers.canbus import Server


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    rc = cli.main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def test_record_fit_upload_run_by_hand(
    server: Server, capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    bus = server.bus_args()
    demo, skill = tmp_path / "demo.blf", tmp_path / "press.skill"
    rc, out, err = run(capsys, "record", "-o", str(demo), "--duration", "6", *bus)
    assert rc == 0, err
    rc, out, err = run(
        capsys, "fit", str(demo), "--stiffness", "100", "--surface-m", "0.001", "-o", str(skill)
    )
    assert rc == 0, err
    assert out.splitlines()[0] == (
        "object mass 10 kg from the recording (the device's object model): force gains scaled to it: "
        "kkf = 300 N/m, kki = 2700 N/(m s) (k_f*m_v/m_d = 0.75)"
    )
    rc, out, err = run(capsys, "upload", str(skill), "--slot", "1", "-q", *bus)
    assert rc == 0, err
    csv = tmp_path / "run.csv"
    rc, out, err = run(capsys, "run", "--slot", "1", "--csv", str(csv), *bus)
    assert rc == 0, err  # no fault 508: the gains are stable on the 10 kg object
    m = re.search(r"force tracking: max ([0-9.]+) %, RMS ([0-9.]+) %", out)
    assert m and float(m.group(1)) < 10.0 and float(m.group(2)) < 3.0, out
    a = np.genfromtxt(csv, delimiter=",", names=True)
    assert np.all(a["fault"] == 0) and a["f_hat"].max() > 4.0


def test_gains_unstable_on_the_devices_object_are_refused_before_anything_moves(
    server: Server, capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    """A CSV recording names no object: the default gains (k_f*m_v/m_d = 1.35 on the 10 kg
    object at 100 N/m) upload, and run refuses them with the remedy; the device stays IDLE."""
    d = synthetic.pressing(seed=2, duration_s=3.0)
    write_csv(tmp_path / "demo.csv", {"t": d.t_s, "x": d.pos_m, "f_contact": d.force_N})
    skill = tmp_path / "soft.skill"
    rc, _, err = run(capsys, "fit", str(tmp_path / "demo.csv"), "-k", "100", "-o", str(skill))
    assert rc == 0, err
    bus = server.bus_args()
    rc, _, err = run(capsys, "upload", str(skill), "--slot", "2", "-q", *bus)
    assert rc == 0, err
    rc, out, err = run(capsys, "run", "--slot", "2", "--csv", str(tmp_path / "r.csv"), *bus)
    assert rc == 2 and "executing" not in out and not (tmp_path / "r.csv").exists()
    assert err == (
        "forceskill: error: slot 2 of node 0: its force gains are unstable on the device's 10 kg object "
        "(k_f*m_v/m_d = 1.35 >= 1, k_f = kkf/k = 5.4, m_d = 40 kg: the force loop feeds back the "
        "object's inertia, fault 508 within a second of contact); fit it again with --object-mass 10; "
        "nothing was started [112]\n"
    )
    rc, out, _ = run(capsys, "status", *bus)
    assert rc == 0 and ": IDLE, fault none" in out
