"""Print the host package's dependencies pinned to their lower bounds ("numpy==1.23.2" ...), one a
line, from host/pyproject.toml: scripts/test.sh installs these into .venv-min."""
from __future__ import annotations

import re
import sys
from pathlib import Path

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib  # type: ignore[no-redef]

ROOT = Path(__file__).resolve().parents[1]


def pins() -> list[str]:
    deps = tomllib.loads((ROOT / "host" / "pyproject.toml").read_text())["project"]["dependencies"]
    out = []
    for d in deps:
        m = re.fullmatch(r"\s*([A-Za-z0-9_.\-]+)\s*>=\s*([0-9][0-9A-Za-z.]*)\s*", d)
        if not m:
            sys.exit(f"min_versions: dependency without a plain lower bound: {d!r}")
        out.append(f"{m.group(1)}=={m.group(2)}")
    return out


if __name__ == "__main__":
    print("\n".join(pins()))
