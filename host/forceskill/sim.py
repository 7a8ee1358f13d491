"""Where the HIL simulator and its scenarios are, for the commands that drive them (report,
journey): nothing here assumes the repository layout, so an installed package works alike."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

from .errors import FsError

HIL_SIM_ENV = "FORCESKILL_HIL_SIM"


def find_hil_sim(explicit: str | None, code: int) -> Path:
    """The hil_sim binary: explicit path (--hil-sim), else $FORCESKILL_HIL_SIM, else hil_sim on
    PATH; FsError(code) naming what was tried when none is an executable file."""
    for cand, what in ((explicit, "--hil-sim"), (os.environ.get(HIL_SIM_ENV), f"${HIL_SIM_ENV}")):
        if cand:
            p = Path(cand)
            if p.is_file() and os.access(p, os.X_OK):
                return p
            raise FsError(code, f"{what} is not an executable file: {cand!r}")
    found = shutil.which("hil_sim")
    if found:
        return Path(found)
    raise FsError(
        code,
        f"hil_sim not found: pass --hil-sim PATH, set ${HIL_SIM_ENV} or put hil_sim on "
        "PATH (build it: cmake --preset host-release && cmake --build --preset host-release)",
    )


def scenario_dir(explicit: str | None) -> Path:
    """The scenario folder: explicit (--scenarios), else the copy packaged with forceskill."""
    if explicit:
        return Path(explicit)
    from importlib.resources import files

    return Path(str(files("forceskill") / "data" / "scenarios"))
