"""`fit` without --kernels on a recording the default N is too few for (a long smooth ramp): the
smallest N above it within the default 10 % is used and said; --kernels N still refuses (641)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from forceskill import cli
from forceskill.errors import ERR_FIT_INACCURATE


def test_a_long_ramp_fits_by_default_and_says_its_n(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    t = np.arange(60001) / 100.0  # 600 s at 100 Hz
    f = 0.5 + 19.5 * t / 600.0
    p = tmp_path / "ramp.csv"
    np.savetxt(
        p,
        np.column_stack((t, 0.002 + f / 2000.0, f)),
        fmt="%.6f",
        delimiter=",",
        header="t,x,f_contact",
        comments="",
    )
    base = ["fit", str(p), "-k", "2000", "--surface-m", "0.002"]
    assert cli.main([*base, "-o", str(tmp_path / "a.skill")]) == 0
    out = capsys.readouterr().out
    assert "the smallest within 10 % (the default N = 50 gives" in out and (tmp_path / "a.skill").exists()
    n = int(out.split("kernels: N = ")[1].split(",")[0])
    assert 50 < n <= 1024 and f"N = {n}, k = 2000" in out
    assert cli.main([*base, "-o", str(tmp_path / "b.skill"), "--kernels", "50"]) == 2
    err = capsys.readouterr().err
    assert f"[{ERR_FIT_INACCURATE}]" in err and "--max-error PCT searches N" in err
    assert not (tmp_path / "b.skill").exists()
