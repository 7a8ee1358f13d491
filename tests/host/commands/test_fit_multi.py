"""forceskill fit with several recordings: mixed formats, the alignment printed, an outlier."""

from __future__ import annotations

import gzip
from pathlib import Path

import numpy as np
import pytest

from forceskill import cli
from forceskill.model import synthetic
from forceskill.model.demo import Demo, write_csv
from forceskill.model.skill import Skill


def _write(path: Path, d: Demo) -> Path:
    write_csv(path, {"t": d.t_s, "x": d.pos_m, "f_contact": d.force_N})
    return path


@pytest.fixture(scope="module")
def recordings(tmp_path_factory: pytest.TempPathFactory) -> list[Path]:
    """Four recordings of one pressing task: CSV, gzip-compressed CSV and a text table."""
    root = tmp_path_factory.mktemp("multi")
    _, demos = synthetic.pressing_set(seed=1, n=4)
    paths = [_write(root / f"d{i}.csv", d) for i, d in enumerate(demos)]
    gz = root / "d1.csv.gz"
    gz.write_bytes(gzip.compress(paths[1].read_bytes()))
    txt = root / "d2.txt"
    txt.write_bytes(paths[2].read_bytes())
    return [paths[0], gz, txt, paths[3]]


def test_fit_several_recordings_prints_each_alignment(
    recordings: list[Path], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "m.skill"
    assert cli.main(["fit", *map(str, recordings), "-k", "100", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "4 recordings aligned" in text
    for p in recordings:
        line = next(ln for ln in text.splitlines() if ln.strip().startswith(p.name))
        assert "stretch" in line and "lag" in line and "deviation from the others' mean" in line
    assert "OUTLIER" not in text and "mean profile of 4 recordings" in text
    Skill.read(out)


def test_fit_names_an_outlier_and_leaves_it_out(
    recordings: list[Path], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    odd = synthetic.engraving(seed=4, duration_s=6.5, k_v=100.0, f_max_N=4.5, noise_N=0.03)
    odd_csv = _write(tmp_path / "odd.csv", odd)
    args = ["fit", *map(str, recordings), str(odd_csv), "-k", "100", "-o", str(tmp_path / "m.skill")]
    assert cli.main(args) == 0
    text = capsys.readouterr().out
    assert (
        "odd.csv:f_contact" in text and "OUTLIER: left out" in text and "mean profile of 4 recordings" in text
    )
    assert cli.main([*args, "--keep-outliers"]) == 0
    text = capsys.readouterr().out
    assert "OUTLIER (kept" in text and "mean profile of 5 recordings" in text


def test_fit_periodic_several_recordings(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    paths = []
    for i, per in enumerate((1.2, 1.25, 1.17)):
        d = synthetic.wiping_strokes(
            seed=5, n_strokes=6, period_s=per, approach_s=1.0 + 0.3 * i, noise_N=0.02
        )
        paths.append(str(_write(tmp_path / f"w{i}.csv", d)))
    out = tmp_path / "w.skill"
    assert cli.main(["fit", *paths, "-k", "100", "--periodic", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "3 recordings, strokes aligned in phase" in text
    assert Skill.read(out).periodic


def test_the_band_is_stored_rolled_out_shown_and_plotted(
    recordings: list[Path], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out, png, csv = tmp_path / "m.skill", tmp_path / "m.png", tmp_path / "r.csv"
    args = ["fit", *map(str, recordings), "-k", "100", "-o", str(out), "--plot", str(png)]
    assert cli.main([*args, "--band-k", "2.5", "--band-floor", "4", "--band-points", "40"]) == 0
    assert "band: mean +- max(2.5 sigma, floor 4 % of max force" in capsys.readouterr().out
    sk = Skill.read(out)
    assert sk.format_version == 5 and sk.band_points == 40 and png.stat().st_size > 10_000
    assert sk.band_lo_N is not None and sk.band_hi_N is not None
    assert np.all(sk.band_hi_N - sk.band_lo_N >= 2 * 0.04 * 0.99 * np.max(sk.band_hi_N) / 1.1)
    assert cli.main(["rollout", str(out), "-o", str(csv), "--goal-scale", "1.5"]) == 0
    assert csv.read_text().split("\n", 1)[0] == "t,f_hat,f_band_lo,f_band_hi"
    r = np.loadtxt(csv, delimiter=",", skiprows=1)
    assert np.all(r[:, 2] <= r[:, 1] + 1e-9) and np.all(r[:, 1] <= r[:, 3] + 1e-9)
    capsys.readouterr()
    assert cli.main(["show", str(out)]) == 0
    assert "demonstrated band at 40 points" in capsys.readouterr().out


def test_one_recording_writes_no_band(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    _, demos = synthetic.pressing_set(seed=4, n=1)
    out = tmp_path / "one.skill"
    assert cli.main(["fit", str(_write(tmp_path / "d.csv", demos[0])), "-k", "100", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "band" not in text and "aligned" not in text
    assert Skill.read(out).format_version == 2


def test_the_command_defaults_are_the_models() -> None:
    from forceskill.commands import fit
    from forceskill.model import multi

    assert (fit.BAND_K, fit.BAND_FLOOR_REL, fit.BAND_POINTS) == (
        multi.BAND_K,
        multi.BAND_FLOOR_REL,
        multi.BAND_POINTS,
    )
