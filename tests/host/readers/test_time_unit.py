"""A CSV time column in milliseconds: read as such when its name says so (`time_ms`, `t_ms`,
`t [ms]`, `time (ms)`), and when nothing says so the refusal of its implausible times (a span
over the skill limit, 642, or 1 s gaps, 606) names `--time-unit ms`; nothing is written."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from forceskill import cli
from forceskill.errors import ERR_DEMO_DURATION, ERR_DEMO_GAP
from forceskill.model import synthetic
from forceskill.model.skill import Skill

HINT = "the median sample step reads 1 s: a time column in milliseconds needs --time-unit ms"


def write(path: Path, time_name: str, t: np.ndarray, f: np.ndarray, x: np.ndarray) -> Path:
    rows = np.column_stack([t, x, f])
    path.write_text(f"{time_name},x,f_contact\n" + "".join(f"{a:.9g},{b:.9g},{c:.9g}\n" for a, b, c in rows))
    return path


def fit(path: Path, out: Path, capsys: pytest.CaptureFixture[str], *extra: str) -> tuple[int, str, str]:
    rc = cli.main(["fit", str(path), "-k", "100", "--surface-m", "0.001", "-o", str(out), *extra])
    o, e = capsys.readouterr()
    return rc, o, e


@pytest.fixture(scope="module")
def press() -> synthetic.Demo:
    return synthetic.pressing(seed=3, duration_s=6.0)


@pytest.mark.parametrize("name", ["time_ms", "t_ms", "t [ms]", "time (ms)", "Time_MS"])
def test_a_time_column_named_in_ms_is_read_in_ms(
    name: str, press: synthetic.Demo, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    ref = write(tmp_path / "s.csv", "t", press.t_s, press.force_N, press.pos_m)
    ms = write(tmp_path / "ms.csv", name, press.t_s * 1e3, press.force_N, press.pos_m)
    rc, _, err = fit(ref, tmp_path / "s.skill", capsys)
    assert rc == 0, err
    rc, out_ms, err = fit(ms, tmp_path / "ms.skill", capsys)
    assert rc == 0, err
    assert "T = 6.000 s, 6001 samples at 1 ms" in out_ms
    a = Skill.from_bytes((tmp_path / "s.skill").read_bytes())
    b = Skill.from_bytes((tmp_path / "ms.skill").read_bytes())
    assert a.tau_s == pytest.approx(b.tau_s, rel=1e-12) and np.allclose(
        a.weights, b.weights, rtol=1e-9, atol=1e-9
    )


@pytest.mark.parametrize(
    ("duration_s", "code"), [(6.0, ERR_DEMO_DURATION), (3.0, ERR_DEMO_GAP)], ids=["over-limit", "gaps"]
)
def test_t_in_ms_read_as_seconds_is_refused_with_the_hint(
    duration_s: float, code: int, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # 6,000 "s" is over the 3,600 s skill limit: refused from the first and last rows; 3,000 "s"
    # passes that and is refused for its 1 s gaps
    d = synthetic.pressing(seed=3, duration_s=duration_s)
    ms = write(tmp_path / "ms.csv", "t", d.t_s * 1e3, d.force_N, d.pos_m)
    rc, out, err = fit(ms, tmp_path / "x.skill", capsys)
    assert rc == 2 and out == "" and err.count("\n") == 1
    assert err.endswith(f"{HINT} [{code}]\n"), err
    assert not (tmp_path / "x.skill").exists()
    rc, out, err = fit(ms, tmp_path / "x.skill", capsys, "--time-unit", "ms")
    assert rc == 0, err
    assert f"T = {duration_s:.3f} s, {int(duration_s * 1000) + 1} samples at 1 ms" in out


def test_no_hint_when_the_unit_was_told_or_the_step_is_plausible(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    d = synthetic.pressing(seed=3, duration_s=3.0)
    ms = write(tmp_path / "ms.csv", "t", d.t_s * 1e3, d.force_N, d.pos_m)
    rc, _, err = fit(ms, tmp_path / "x.skill", capsys, "--time-unit", "s")
    assert rc == 2 and err.endswith(f"[{ERR_DEMO_GAP}]\n") and "--time-unit" not in err
    # seconds with one real gap of 0.5 s: the median step is 1 ms, nothing hints at another unit
    keep = (d.t_s < 1.0) | (d.t_s > 1.5)
    gap = write(tmp_path / "gap.csv", "t", d.t_s[keep], d.force_N[keep], d.pos_m[keep])
    rc, _, err = fit(gap, tmp_path / "x.skill", capsys)
    assert rc == 2 and "gap of 502 ms" in err and "--time-unit" not in err
