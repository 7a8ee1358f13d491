"""Where the tests find the repository's files and the built simulator."""

from __future__ import annotations

import os
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
SCENARIOS = REPO / "hil_sim" / "scenarios"
VECTORS = REPO / "tests" / "vectors"
TOOLS = REPO / "tools"


def hil_sim_path() -> Path:
    """$FORCESKILL_HIL_SIM, else build/hil_sim/hil_sim (the README's build); a missing binary is a
    failure naming the build command, not a skip."""
    p = Path(os.environ.get("FORCESKILL_HIL_SIM", str(REPO / "build" / "hil_sim" / "hil_sim")))
    assert p.is_file() and os.access(p, os.X_OK), (
        f"hil_sim not built at {p}: run `cmake -S . -B build -G Ninja && ninja -C build hil_sim` "
        "or set FORCESKILL_HIL_SIM"
    )
    return p
