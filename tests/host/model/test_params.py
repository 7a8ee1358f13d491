"""Parameter derivation (corrected eq. 14 in force units), gains files and their refusals."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from forceskill.errors import FsError, ParamError
from forceskill.model.params import Gains, check_inertia, derive, goal, load_gains


def test_default_gains_give_alpha_9_beta_2_25_gamma_13_5() -> None:
    p = derive(Gains())
    assert (p.alpha, p.beta, p.gamma) == (9.0, 2.25, 13.5)  # exact: the kkf, kki terms cancel


@pytest.mark.parametrize("k", [10.0, 180.0, 1e4, 1e7])
def test_force_gains_scale_with_the_stiffness(k: float) -> None:
    k_f, k_i = Gains().force_gains(k)
    assert k_f == pytest.approx(540.0 / k, rel=1e-15)
    assert k_i == pytest.approx(4860.0 / k, rel=1e-15)
    if k == 180.0:
        assert (k_f, k_i) == pytest.approx((3.0, 27.0), rel=1e-15)  # the paper's stiffness


def test_derivation_matches_the_formulas_for_other_gains() -> None:
    # controller gains k_f = 1, k_i = 5 on k = 300 N/m
    k = 300.0
    g = Gains(m_d_kg=10.0, k_d_Nspm=150.0, k_p_Npm=400.0, kkf_Npm=k * 1.0, kki_Npms=k * 5.0)
    alpha = 150.0 / 10.0 - 1.0
    gamma = k * 5.0 / (10.0 * alpha)
    beta = (400.0 + k * 1.0 - 10.0 * gamma) / (10.0 * alpha) - 1.0
    p = derive(g)
    assert (p.alpha, p.beta, p.gamma) == pytest.approx((alpha, beta, gamma), rel=1e-15)


@pytest.mark.parametrize(
    "gains,code",
    [
        (Gains(m_d_kg=math.nan), 101),
        (Gains(kki_Npms=math.inf), 101),
        (Gains(m_d_kg=0.0), 102),
        (Gains(k_d_Nspm=40.0), 103),
        (Gains(k_d_Nspm=30.0), 103),
        (Gains(k_p_Npm=0.0, kkf_Npm=0.0), 104),
        (Gains(k_p_Npm=1500.0), 105),
        (Gains(kkf_Npm=600.0), 105),
        (Gains(kki_Npms=-1.0), 107),
        (Gains(m_d_kg=1e-300, k_d_Nspm=1e300), 101),
    ],
)
def test_invalid_gains_are_refused_with_their_code(gains: Gains, code: int) -> None:
    with pytest.raises(ParamError) as e:
        derive(gains)
    assert e.value.code == code
    assert "\n" not in str(e.value)


def test_goal_is_c_over_alpha_beta_in_newtons() -> None:
    g = Gains()
    p = derive(g)
    c = (1170.0 * 5.6 + 540.0 * 4.0 + 4860.0 * 10.0) / 40.0
    assert goal(p, g, 5.6, 4.0, 10.0) == pytest.approx(c / (9.0 * 2.25), rel=1e-14)


def test_inertia_check() -> None:
    # k_f = 540/k: on 180 N/m k_f = 3, so m_v must stay below m_d/3 = 13.3 kg
    check_inertia(Gains(), 180.0, 13.0)
    with pytest.raises(ParamError) as e:
        check_inertia(Gains(), 180.0, 14.0)
    assert e.value.code == 112 and "k_f*m_v/m_d" in str(e.value)
    check_inertia(Gains(), 1e5, 1000.0)  # stiff objects: k_f is tiny


def test_gains_file(tmp_path: Path) -> None:
    f = tmp_path / "g.toml"
    f.write_text("# softer force loop\nk_p_Npm = 1000\nkkf_Npm = 400.0\nm_v_kg = 2.5\n")
    gains, m_v = load_gains(str(f))
    assert gains == Gains(k_p_Npm=1000.0, kkf_Npm=400.0)
    assert m_v == 2.5
    f.write_text("[gains]\nm_d_kg = 20\nk_d_Nspm = 200\nk_p_Npm = 585\nkkf_Npm = 270\nkki_Npms = 2430\n")
    assert load_gains(str(f)) == (Gains(20.0, 200.0, 585.0, 270.0, 2430.0), None)


@pytest.mark.parametrize(
    "text,code,words",
    [
        ("k_p_Npm = \n", 613, "not valid TOML"),
        ("k_f = 3\n", 613, "unknown key 'k_f'"),
        ("k_p_Npm = 'a'\n", 613, "must be a number"),
        ("m_v_kg = -1\n", 613, "m_v_kg must be > 0"),
        ("k_p_Npm = 1500\n", 105, "alpha/4"),
        ("k_d_Nspm = 30\n", 103, "k_d must exceed m_d"),
    ],
)
def test_bad_gains_files_are_refused(tmp_path: Path, text: str, code: int, words: str) -> None:
    f = tmp_path / "g.toml"
    f.write_text(text)
    with pytest.raises(FsError) as e:
        load_gains(str(f))
    assert e.value.code == code and words in str(e.value), str(e.value)
    with pytest.raises(FsError) as e:
        load_gains(str(tmp_path / "missing.toml"))
    assert e.value.code == 613
