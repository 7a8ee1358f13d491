"""The golden vectors are current: regenerated in memory they equal the files, and dmp.rollout of
every image reproduces its CSV (the C tests read the same files)."""

from __future__ import annotations

import json
import sys

import numpy as np
import pytest

from forceskill.errors import SkillError
from forceskill.model import dmp
from forceskill.model.skill import Skill
from helpers.paths import VECTORS

sys.path.insert(0, str(VECTORS))
import generate


def manifest() -> list[tuple[str, float, float, str]]:
    out = []
    for ln in (VECTORS / "manifest.txt").read_text().split("\n"):
        if ln.strip():
            s, g, t, c = ln.split()
            out.append((s, float(g), float(t), c))
    return out


def test_manifest_covers_the_brief() -> None:
    m = manifest()
    skills = [Skill.read(VECTORS / s) for s, *_ in m]
    assert len({s for s, *_ in m}) == 12
    ns = {Skill.read(VECTORS / s).n_kernels for s, *_ in m}
    assert ns == {10, 50, 100}
    assert {s.end_policy for s in skills} == {"hold", "release"}
    assert {(g, t) for _, g, t, _ in m} == {(1.0, 1.0), (1.5, 1.0), (1.0, 1.3), (1.5, 1.3)}
    total = sum(p.stat().st_size for p in VECTORS.rglob("*") if p.is_file() and "__pycache__" not in p.parts)
    # the contact-wait rollouts (manifest_contact.txt) add 0.44 MB, the periodic y path 0.15 MB,
    # the band skills (manifest_band.txt) 0.3 MB
    assert total < 3_250_000


@pytest.mark.parametrize("skill,gs,ts,csv", manifest())
def test_rollout_of_each_image_reproduces_its_csv(skill: str, gs: float, ts: float, csv: str) -> None:
    sk = Skill.read(VECTORS / skill)
    t, f = dmp.rollout(sk, goal_scale=gs, time_scale=ts)
    ref = np.loadtxt(VECTORS / csv, delimiter=",", skiprows=1)
    assert (VECTORS / csv).read_text().split("\n", 1)[0] == "t,f_hat"
    assert ref.shape == (t.size, 2)
    assert t.size - 1 == round(sk.duration_s * ts / sk.dt_s)
    np.testing.assert_array_equal(ref[:, 0], t)
    assert np.max(np.abs(ref[:, 1] - f)) <= 1e-12 * np.max(np.abs(f))


def test_regenerated_skills_equal_the_files() -> None:
    skills = generate.fitted_skills()
    files, lines = generate.golden(skills)
    assert lines == (VECTORS / "manifest.txt").read_text().split("\n")[:-1]
    for name, sk in skills.items():
        disk = Skill.read(VECTORS / (name + ".skill"))
        assert (disk.n_kernels, disk.flags) == (sk.n_kernels, sk.flags)
        for k in (
            "dt_s",
            "alpha",
            "beta",
            "gamma",
            "stiffness_Npm",
            "duration_s",
            "surface_m",
            "m_d_kg",
            "k_d_Nspm",
            "k_p_Npm",
            "kkf_Npm",
            "kki_Npms",
            "force0_N",
        ):
            assert getattr(disk, k) == getattr(sk, k), k
        for k in ("tau_s", "goal_N"):
            assert getattr(disk, k) == pytest.approx(getattr(sk, k), rel=1e-12), k
        np.testing.assert_allclose(disk.centres, sk.centres, rtol=1e-12, atol=1e-15)
        np.testing.assert_allclose(disk.widths, sk.widths, rtol=1e-9)
        np.testing.assert_allclose(
            disk.weights, sk.weights, rtol=1e-7, atol=1e-9 * np.max(np.abs(sk.weights))
        )
        j = json.loads((VECTORS / (name + ".skill.json")).read_text())
        assert Skill.from_json_dict(j).to_bytes() == disk.to_bytes()
    for csv_name, data in files.items():
        if csv_name.endswith(".csv"):
            new = np.loadtxt(data.decode().split("\n")[1:-1], delimiter=",")
            old = np.loadtxt(VECTORS / csv_name, delimiter=",", skiprows=1)
            assert new.shape == old.shape
            assert np.max(np.abs(new[:, 1] - old[:, 1])) <= 1e-7 * np.max(np.abs(old[:, 1]))


def test_regenerated_bad_images_match_the_manifest() -> None:
    base = Skill.read(VECTORS / (generate.skill_name("press", 10, "ridge", "release") + ".skill"))
    base_y = Skill.read(VECTORS / "wipe_n10_ridge_hold.skill")
    base_p = Skill.read(VECTORS / "periodic_n20_ridge.skill")
    bad = (
        generate.bad_images(base)
        + generate.bad_images_y(base_y)
        + generate.bad_images_periodic(base_p, generate.discrete_as_v4(base))
        + generate.bad_images_band(Skill.read(VECTORS / "band_press_n50_ridge.skill"))
    )
    lines = [f"{n} {c}" for n, _, c in bad]
    assert lines == (VECTORS / "bad" / "manifest.txt").read_text().split("\n")[:-1]
    for name, data, code in bad:
        assert data == (VECTORS / "bad" / name).read_bytes(), name
        with pytest.raises(SkillError) as e:
            Skill.from_bytes(data)
        assert e.value.code == code


def manifest_y() -> list[tuple[str, float, float, float, str]]:
    out = []
    for ln in (VECTORS / "manifest_y.txt").read_text().split("\n"):
        if ln.strip():
            s, g, t, p, c = ln.split()
            out.append((s, float(g), float(t), float(p), c))
    return out


def test_manifest_y_covers_both_halves_and_every_scale() -> None:
    m = manifest_y()
    skills = [Skill.read(VECTORS / s) for s, *_ in m]
    assert all(s.has_y and s.format_version == 3 for s in skills)
    assert {s.n_kernels for s in skills} == {10, 50}
    assert any(g != 1.0 and t != 1.0 and p != 1.0 for _, g, t, p, _ in m)


@pytest.mark.parametrize("skill,gs,ts,ps,csv", manifest_y())
def test_y_rollout_of_each_image_reproduces_its_csv(
    skill: str, gs: float, ts: float, ps: float, csv: str
) -> None:
    sk = Skill.read(VECTORS / skill)
    t, f = dmp.rollout(sk, goal_scale=gs, time_scale=ts)
    _, y = dmp.rollout_path(sk, time_scale=ts, path_scale=ps)
    ref = np.loadtxt(VECTORS / csv, delimiter=",", skiprows=1)
    assert (VECTORS / csv).read_text().split("\n", 1)[0] == "t,f_hat,y_hat"
    assert ref.shape == (t.size, 3)
    np.testing.assert_array_equal(ref[:, 0], t)
    assert np.max(np.abs(ref[:, 1] - f)) <= 1e-12 * np.max(np.abs(f))
    assert np.max(np.abs(ref[:, 2] - y)) <= 1e-12 * np.max(np.abs(y))


def test_regenerated_y_skills_equal_the_files() -> None:
    files, lines = generate.golden_y(generate.fitted_y_skills())
    assert lines == (VECTORS / "manifest_y.txt").read_text().split("\n")[:-1]
    for name, data in files.items():
        if name.endswith(".skill"):
            new, disk = Skill.from_bytes(data), Skill.read(VECTORS / name)
            assert disk.y_weights is not None and new.y_weights is not None
            np.testing.assert_allclose(
                disk.y_weights, new.y_weights, rtol=1e-7, atol=1e-9 * np.max(np.abs(new.y_weights))
            )
            assert disk.goal_y_m == pytest.approx(new.goal_y_m, rel=1e-12)
            assert disk.y_start_m == new.y_start_m


def test_path_scale_scales_the_path_about_its_start_and_goal_scale_leaves_it() -> None:
    sk = Skill.read(VECTORS / "wipe_n50_ridge_release.skill")
    _, y1 = dmp.rollout_path(sk)
    _, y2 = dmp.rollout_path(sk, path_scale=1.5)
    p1, p2 = y1 - sk.y_start_m, y2 - sk.y_start_m
    assert np.max(np.abs(p2 - 1.5 * p1)) <= 1e-12 * np.max(np.abs(p1))
    _, f1 = dmp.rollout(sk)
    _, f2 = dmp.rollout(sk, goal_scale=1.5)
    assert np.max(np.abs((f2 - sk.force0_N) - 1.5 * (f1 - sk.force0_N))) <= 1e-9 * np.max(np.abs(f1))
    # time scaling stretches both on the one phase: the end of the path is the same point
    _, y13 = dmp.rollout_path(sk, time_scale=1.3)
    assert y13.size == round(sk.duration_s * 1.3 / sk.dt_s) + 1
    assert abs(y13[-1] - y1[-1]) < 2e-3 * np.ptp(y1)


def band_manifest() -> list[tuple[str, float, float, str, str]]:
    out = []
    for ln in (VECTORS / "manifest_band.txt").read_text().split("\n"):
        if ln.strip():
            s, g, t, pts, csv = ln.split()
            out.append((s, float(g), float(t), pts, csv))
    return out


@pytest.mark.parametrize("skill,gs,ts,pts,csv", band_manifest())
def test_band_images_reproduce_their_points_and_rollouts(
    skill: str, gs: float, ts: float, pts: str, csv: str
) -> None:
    sk = Skill.read(VECTORS / skill)
    assert sk.format_version == 5 and sk.band_lo_N is not None and sk.band_hi_N is not None
    p = np.loadtxt(VECTORS / pts, delimiter=",", skiprows=1)
    np.testing.assert_array_equal(p[:, 0], sk.band_lo_N)
    np.testing.assert_array_equal(p[:, 1], sk.band_hi_N)
    ref = np.loadtxt(VECTORS / csv, delimiter=",", skiprows=1)
    assert (VECTORS / csv).read_text().split("\n", 1)[0] == "t,f_hat,f_band_lo,f_band_hi"
    t, f = dmp.rollout(sk, goal_scale=gs, time_scale=ts)
    lo, hi = sk.band_at(t, gs, ts)
    np.testing.assert_array_equal(ref[:, 0], t)
    assert np.max(np.abs(ref[:, 1] - f)) <= 1e-12 * np.max(np.abs(f))
    np.testing.assert_allclose(ref[:, 2], lo, rtol=0, atol=1e-12)
    np.testing.assert_allclose(ref[:, 3], hi, rtol=0, atol=1e-12)
    assert np.all(lo <= f + 1e-9) and np.all(f <= hi + 1e-9)  # the mean skill lies inside its band


def test_regenerated_band_skills_match_the_files() -> None:
    for name, (sk, _) in generate.fitted_band_skills().items():
        disk = Skill.read(VECTORS / (name + ".skill"))
        assert disk.n_kernels == sk.n_kernels and disk.band_points == sk.band_points
        np.testing.assert_allclose(disk.band_lo_N, sk.band_lo_N, rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(disk.band_hi_N, sk.band_hi_N, rtol=1e-9, atol=1e-9)
