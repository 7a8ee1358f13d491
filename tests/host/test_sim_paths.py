"""forceskill.sim: hil_sim from --hil-sim, then $FORCESKILL_HIL_SIM, then PATH, then the
checkout's own build; the paper
scenarios from the package itself (no repository layout assumed)."""

from __future__ import annotations

import os
import stat
from pathlib import Path

import pytest

import forceskill.sim
from forceskill.errors import FsError
from forceskill.sim import HIL_SIM_ENV, find_hil_sim, scenario_dir

REPO = Path(__file__).resolve().parents[2]


def _exe(path: Path) -> Path:
    path.write_text("#!/bin/sh\n")
    path.chmod(path.stat().st_mode | stat.S_IXUSR)
    return path


def test_order_option_env_path(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    a, b = _exe(tmp_path / "a"), _exe(tmp_path / "b")
    (tmp_path / "bin").mkdir()
    on_path = _exe(tmp_path / "bin" / "hil_sim")
    monkeypatch.setenv("PATH", str(tmp_path / "bin"))
    monkeypatch.setenv(HIL_SIM_ENV, str(b))
    assert find_hil_sim(str(a), 621) == a
    assert find_hil_sim(None, 621) == b
    monkeypatch.delenv(HIL_SIM_ENV)
    assert find_hil_sim(None, 621) == on_path


def test_the_checkout_finds_the_simulator_it_built(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """No option, no variable, nothing on PATH: the package of this checkout takes its own
    build/hil_sim/hil_sim (what scripts/setup.sh builds), the path a user of the README has."""
    built = REPO / "build" / "hil_sim" / "hil_sim"
    if not built.is_file():
        pytest.skip("build/hil_sim/hil_sim not built in this checkout (scripts/setup.sh builds it)")
    monkeypatch.delenv(HIL_SIM_ENV, raising=False)
    monkeypatch.setenv("PATH", str(tmp_path))
    assert find_hil_sim(None, 621) == built


def test_not_found_is_one_coded_line(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(forceskill.sim, "checkout_hil_sim", lambda: None)
    monkeypatch.delenv(HIL_SIM_ENV, raising=False)
    monkeypatch.setenv("PATH", str(tmp_path))
    with pytest.raises(FsError) as e:
        find_hil_sim(None, 620)
    assert e.value.code == 620 and "--hil-sim" in e.value.message and "\n" not in e.value.message
    monkeypatch.setenv(HIL_SIM_ENV, str(tmp_path / "missing"))
    with pytest.raises(FsError) as e:
        find_hil_sim(None, 621)
    assert e.value.code == 621 and HIL_SIM_ENV in e.value.message
    plain = tmp_path / "plain"
    plain.write_text("")
    os.chmod(plain, 0o644)
    with pytest.raises(FsError):
        find_hil_sim(str(plain), 621)


def test_packaged_scenarios_are_the_simulators() -> None:
    d = scenario_dir(None)
    repo = Path(__file__).resolve().parents[2] / "hil_sim" / "scenarios"
    for name in ("pressing_task1_demo.toml", "engraving_task2_exec.toml", "reuse_300_1_5x.toml"):
        assert (d / name).read_bytes() == (repo / name).read_bytes()
    assert scenario_dir("elsewhere") == Path("elsewhere")
