#!/usr/bin/env python3
"""Run `hil_sim faults` and put its table into docs/safety.md between the fault-table markers.

usage: hil_sim/faults/update_safety_doc.py [HIL_SIM] [--seed N]
HIL_SIM defaults to $FORCESKILL_HIL_SIM, else build/hil_sim/hil_sim. Exits non-zero (and leaves
the document alone) when a row fails or the markers are missing.
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
DOC = REPO / "docs" / "safety.md"
BEGIN = "<!-- fault-table:begin -->"
END = "<!-- fault-table:end -->"


def section(table_md: str, command: str) -> str:
    return (f"{BEGIN}\n"
            f"Produced by `{command}` (also written by `tests/hil/test_hil_faults.py` to the build\n"
            f"directory as `hil_sim/fault_table.md`; scenario files and definitions:\n"
            f"`hil_sim/scenarios/faults/README.md`). Times in ms of simulated time, forces in N.\n\n"
            f"{table_md.rstrip()}\n{END}")


def replace_section(doc: str, new: str) -> str:
    i, j = doc.find(BEGIN), doc.find(END)
    if i < 0 or j < i:
        raise SystemExit(f"{DOC}: markers {BEGIN} / {END} not found")
    return doc[:i] + new + doc[j + len(END):]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("hil_sim", nargs="?",
                    default=os.environ.get("FORCESKILL_HIL_SIM", str(REPO / "build" / "hil_sim" / "hil_sim")))
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as td:
        out = Path(td) / "table.md"
        r = subprocess.run([a.hil_sim, "faults", "--seed", str(a.seed), "-o", str(out)],
                           capture_output=True, text=True)
        if r.returncode != 0:
            sys.stderr.write(r.stdout + r.stderr)
            return r.returncode
        table = out.read_text()
    doc = DOC.read_text()
    DOC.write_text(replace_section(doc, section(table, f"hil_sim faults --seed {a.seed}")))
    print(f"updated {DOC}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
