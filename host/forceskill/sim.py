"""Where the HIL simulator and its scenarios are, for the commands that drive them (report,
journey). An installed package needs no repository; a package installed from a checkout (the
README's set-up: an editable install) also finds the simulator that checkout built."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

from .errors import FsError

HIL_SIM_ENV = "FORCESKILL_HIL_SIM"


def checkout_hil_sim() -> Path | None:
    """build/hil_sim/hil_sim of the checkout this package is installed from in editable mode
    (the README's set-up: scripts/setup.sh installs host/ with pip -e and builds the simulator
    there), or None for a package installed otherwise or a checkout not built."""
    import json
    from importlib.metadata import distributions
    from urllib.parse import unquote, urlparse

    for dist in distributions(name="forceskill"):  # a wheel layout elsewhere on sys.path may come first
        try:
            info = json.loads(dist.read_text("direct_url.json") or "{}")
        except ValueError:
            continue
        url = urlparse(str(info.get("url", "")))
        if info.get("dir_info", {}).get("editable") and url.scheme == "file":
            break
    else:
        return None
    p = Path(unquote(url.path)).parent / "build" / "hil_sim" / "hil_sim"
    return p if p.is_file() and os.access(p, os.X_OK) else None


def find_hil_sim(explicit: str | None, code: int) -> Path:
    """The hil_sim binary: explicit path (--hil-sim), else $FORCESKILL_HIL_SIM, else hil_sim on
    PATH, else the one this checkout built; FsError(code) naming what was tried when none is an
    executable file."""
    for cand, what in ((explicit, "--hil-sim"), (os.environ.get(HIL_SIM_ENV), f"${HIL_SIM_ENV}")):
        if cand:
            p = Path(cand)
            if p.is_file() and os.access(p, os.X_OK):
                return p
            raise FsError(code, f"{what} is not an executable file: {cand!r}")
    found = shutil.which("hil_sim")
    if found:
        return Path(found)
    built = checkout_hil_sim()
    if built is not None:
        return built
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
