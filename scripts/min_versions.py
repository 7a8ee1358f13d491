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


def _marker_applies(marker: str) -> bool:
    """The one kind of marker pyproject.toml uses: python_version < / >= 'X.Y'."""
    m = re.fullmatch(r"\s*python_version\s*(<|>=)\s*['\"](\d+)\.(\d+)['\"]\s*", marker)
    if not m:
        sys.exit(f"min_versions: unsupported environment marker: {marker.strip()!r}")
    below = sys.version_info[:2] < (int(m.group(2)), int(m.group(3)))
    return below if m.group(1) == "<" else not below


def pins() -> list[str]:
    deps = tomllib.loads((ROOT / "host" / "pyproject.toml").read_text())["project"]["dependencies"]
    out = []
    for dep in deps:
        d, _, marker = dep.partition(";")
        if marker and not _marker_applies(marker):
            continue  # e.g. tomli, needed only before Python 3.11
        m = re.fullmatch(r"\s*([A-Za-z0-9_.\-]+)\s*>=\s*([0-9][0-9A-Za-z.]*)\s*", d)
        if not m:
            sys.exit(f"min_versions: dependency without a plain lower bound: {dep!r}")
        out.append(f"{m.group(1)}=={m.group(2)}")
    return out


if __name__ == "__main__":
    print("\n".join(pins()))
