"""The contact wait's Python reference (forceskill.model.contact): the golden contact-wait vectors
are current, the loop without a wait is the plain rollout, the phase holds for the loss window and
continues without a step, and the skill image carries the wait's parameters (format v4)."""

from __future__ import annotations

import sys

import numpy as np
import pytest

from forceskill.errors import SkillError
from forceskill.model import contact, dmp, periodic
from forceskill.model.skill import Skill
from helpers.paths import REPO

VECTORS = REPO / "tests" / "vectors"
sys.path.insert(0, str(VECTORS))
import generate  # noqa: E402

PRESS = VECTORS / "press_n50_lwr_hold.skill"
WIPE = VECTORS / "periodic_n50_ridge.skill"


def test_regenerated_contact_vectors_equal_the_files() -> None:
    images = {p.name: p.read_bytes() for p in VECTORS.glob("*.skill")}
    files, manifest = generate.golden_contact(images)
    assert manifest == (VECTORS / "manifest_contact.txt").read_text().split("\n")[:-1]
    for name, data in files.items():
        assert data == (VECTORS / name).read_bytes(), name


def test_without_a_wait_the_loop_is_the_plain_rollout() -> None:
    sk = Skill.read(PRESS)
    _, f = dmp.rollout(sk, goal_scale=1.5, time_scale=1.3)
    _, f_hat, rate, hold = contact.rollout(
        sk, np.zeros(f.size - 1), threshold_N=0.0, goal_scale=1.5, time_scale=1.3
    )
    assert np.max(np.abs(f_hat - f[1:])) <= 1e-12 * np.max(f)  # tick n reports row n + 1
    assert np.all(rate == 1.0) and hold == 0.0
    sp = Skill.read(WIPE)
    _, fp = periodic.rollout(sp, cycles=2, goal_scale=1.2, amplitude_scale=1.5)
    _, fp_hat, _, _ = contact.rollout(
        sp, np.zeros(fp.size - 1), threshold_N=0.0, goal_scale=1.2, amplitude_scale=1.5
    )
    assert np.max(np.abs(fp_hat - fp[1:])) <= 1e-12 * np.max(fp)


@pytest.mark.parametrize("path,window", [(PRESS, (0.6, 0.9)), (WIPE, (0.3, 0.5))])
def test_the_phase_holds_for_the_loss_and_continues_without_a_step(path, window) -> None:  # type: ignore[no-untyped-def]
    sk = Skill.read(path)
    n = 2000
    _, f_hat, rate, hold = contact.loss_window(sk, n, window, threshold_N=0.5, tau_s=0.02)
    assert hold == pytest.approx(window[1] - window[0], abs=1e-6)  # the deficit of a first-order rate
    lost = slice(int(window[0] / sk.dt_s) + 100, int(window[1] / sk.dt_s))
    assert np.max(rate[lost]) < 0.01  # holding (tau 20 ms: e^-5 after 100 ms)
    # the reference steps no more than the nominal run does: it held, then continued
    nominal = np.max(np.abs(np.diff(contact.rollout(sk, np.zeros(n), threshold_N=0.0)[1])))
    assert np.max(np.abs(np.diff(f_hat))) <= nominal * (1.0 + 1e-9)
    # after the loss the run is the nominal one, late by the hold (discrete: until its end)
    shift = int(round(hold / sk.dt_s))
    f_nom = contact.rollout(sk, np.zeros(n), threshold_N=0.0)[1]
    after = np.arange(int(window[1] / sk.dt_s) + 300, n)
    assert np.max(np.abs(f_hat[after] - f_nom[after - shift])) <= 0.01 * np.max(np.abs(f_nom))


def test_the_image_carries_the_contact_wait() -> None:
    sk = Skill.read(PRESS)
    assert sk.format_version == 2 and not sk.contact_wait
    sk2 = Skill.from_bytes(sk.to_bytes())
    sk2.contact_cN, sk2.contact_tau_ms, sk2.format_version = 150, 50, 4
    back = Skill.from_bytes(sk2.to_bytes())
    assert back.format_version == 4 and back.contact_wait
    assert back.contact_threshold_N == pytest.approx(1.5) and back.contact_tau_s == pytest.approx(0.05)
    assert Skill.from_json_dict(back.to_json_dict()).to_bytes() == back.to_bytes()
    sk2.contact_cN = 0
    with pytest.raises(SkillError) as e:
        sk2.to_bytes()
    assert e.value.code == 233


def test_rollout_command_simulates_a_contact_loss(tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    from forceskill import cli

    sk = Skill.from_bytes(Skill.read(PRESS).to_bytes())
    sk.contact_cN, sk.contact_tau_ms, sk.format_version = 50, 20, 4
    sk.write(tmp_path / "w.skill")
    out_csv = tmp_path / "r.csv"
    assert (
        cli.main(["rollout", str(tmp_path / "w.skill"), "-o", str(out_csv), "--contact-loss", "0.6,0.9"]) == 0
    )
    out = capsys.readouterr().out
    assert "the phase held 300.0 ms" in out
    cols = np.genfromtxt(out_csv, delimiter=",", names=True)
    _, f_hat, rate, _ = contact.loss_window(sk, cols["t"].size, (0.6, 0.9))
    assert np.max(np.abs(cols["f_hat"] - f_hat)) <= 1e-6 * np.max(np.abs(f_hat))
    assert np.max(np.abs(cols["rate"] - rate)) <= 1e-6
