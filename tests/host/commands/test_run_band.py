"""forceskill run with a skill that carries the demonstrated band: the CSV's band_out column, the
pieces outside the band and the --plot that shows them (no device: the run's result as
run_on_device returns it)."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from forceskill import cli, plot
from forceskill.commands import run
from forceskill.errors import ERR_OUTPUT_IS_INPUT
from forceskill.model.skill import Skill
from forceskill.outputs import Outputs
from forceskill.wire import Band

VECTORS = Path(__file__).resolve().parents[2] / "vectors"


def _columns(n: int, outside: list[tuple[int, int]]) -> dict[str, np.ndarray]:
    """A run of n rows (1 ms) with the band left over the row ranges [a, b)."""
    t = np.arange(n) * 1e-3
    cols = {k: np.zeros(n) for k in run.CSV_COLUMNS}
    cols["t"] = t
    cols["f_contact"] = cols["f_hat"] = 2.0 * np.sin(np.pi * t / t[-1])
    cols["x"] = 1e-3 * t
    band_out = np.zeros(n)
    for a, b in outside:
        band_out[a:b] = 1.0
    cols[run.CSV_BAND_COLUMN] = band_out
    return cols


def test_the_csv_has_band_out_after_the_fault_column_only_with_a_band() -> None:
    cols = _columns(50, [(10, 20)])
    names, block = run.run_table(cols, banded=True)
    assert names == (*run.CSV_COLUMNS, "band_out") and names[-2] == "fault"
    assert block.shape == (50, len(run.CSV_COLUMNS) + 1)
    assert set(np.unique(block[:, -1])) == {0.0, 1.0}
    assert np.array_equal(np.flatnonzero(block[:, -1]), np.arange(10, 20))
    names, block = run.run_table(cols, banded=False)
    assert names == run.CSV_COLUMNS and block.shape == (50, len(run.CSV_COLUMNS))


def test_the_pieces_outside_span_from_their_first_row_to_one_past_their_last() -> None:
    t = np.arange(100) * 1e-3
    out = np.zeros(100)
    out[[0, 1, 2, 40, 97, 98, 99]] = 1.0
    spans = plot.outside_spans(t, out)
    np.testing.assert_allclose(spans, [[0.0, 0.003], [0.040, 0.041], [0.097, 0.100]])
    assert plot.outside_spans(t, np.zeros(100)).shape == (0, 2)
    assert plot.outside_spans(np.zeros(0), np.zeros(0)).shape == (0, 2)


def _args(**kw: Any) -> argparse.Namespace:
    base = {
        "node": 0,
        "slot": 1,
        "sequence": None,
        "goal_scale": 1.0,
        "time_scale": 1.0,
        "amplitude_scale": 1.0,
    }
    return argparse.Namespace(**{**base, **kw, "plot": kw.get("plot", "run.png")})


def _band_result(cols: dict[str, np.ndarray], sk: Skill | None, fault: int = 0) -> dict[str, Any]:
    return {
        "columns": cols,
        "band": Band(1000, 30, 30, 1.5, 10, 0, 0),
        "skill": sk,
        "fault": fault,
        "fault_row": 45 if fault else None,
    }


def test_the_plot_draws_the_band_and_shades_the_pieces_outside(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    sk = Skill.read(VECTORS / "band_press_n20_ridge.skill")
    n = int(round(sk.duration_s * 1000)) + 1
    cols = _columns(n, [(n // 2, n // 2 + 30), (n - 20, n - 10)])
    drawn: list[Any] = []
    monkeypatch.setattr(plot, "write_figure", lambda fig, path, outs=None: drawn.append(fig))
    run.write_run_plot(_args(goal_scale=1.5), _band_result(cols, sk, fault=515), Outputs())
    ax = drawn[0].axes[0]
    band, outside = ax.collections[0], ax.collections[1]
    assert band.get_label() == "band" and outside.get_label() == "outside the band"
    assert len(outside.get_paths()) == 2  # one collection, a rectangle a piece
    lo, hi = sk.band_at(cols["t"], 1.5)
    ys = np.concatenate([p.vertices[:, 1] for p in band.get_paths()])
    assert np.isclose(ys.min(), lo.min()) and np.isclose(ys.max(), hi.max())
    assert "outside the demonstrated band: 3.0 %" in ax.get_title()
    assert any(ln.get_xdata()[0] == cols["t"][45] for ln in ax.lines)  # the fault's line


def test_a_sequence_is_plotted_with_its_pieces_outside_but_no_band(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    drawn: list[Any] = []
    monkeypatch.setattr(plot, "write_figure", lambda fig, path, outs=None: drawn.append(fig))
    cols = _columns(200, [(50, 60)])
    run.write_run_plot(_args(slot=None, sequence="1:0.1s,2:0.1s"), _band_result(cols, None), Outputs())
    labels = [c.get_label() for c in drawn[0].axes[0].collections]
    assert labels == ["outside the band"]


def test_the_plot_is_written_as_a_png(tmp_path: Path) -> None:
    sk = Skill.read(VECTORS / "band_press_n20_ridge.skill")
    target = tmp_path / "run.png"
    with Outputs() as outs:
        run.write_run_plot(_args(plot=str(target)), _band_result(_columns(500, [(100, 140)]), sk), outs)
        outs.commit()
    assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_the_plot_and_the_csv_on_one_file_are_refused_before_connecting(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    same = str(tmp_path / "run.out")
    assert cli.main(["run", "--slot", "1", "--csv", same, "--plot", same]) == 2
    assert f"[{ERR_OUTPUT_IS_INPUT}]" in capsys.readouterr().err
