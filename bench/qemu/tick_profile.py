#!/usr/bin/env python3
"""Per-state profile of the Cortex-M image's app_tick, from the files bench/qemu_tick.sh's trace
counter writes with QEMU_TICK_PROFILE=PREFIX (what `bench/qemu_tick.sh TARGET --profile` passes):

- PREFIX.max.K: instructions per function of the largest app_tick of kind K (idle, teach,
  execute, upload, fwupdate, fault; the interrupts taken meanwhile included);
- PREFIX.min.K: the same of the smallest tick of kind K (no bus traffic: the state's floor);
- PREFIX: the mean instructions per function of an EXECUTE tick;
- PREFIX.focus.K: with QEMU_TICK_FOCUS=REGEX (`qemu_tick.sh --focus REGEX`), the functions
  matching REGEX in the tick of kind K where they ran the most instructions;
- PREFIX.softfloat: per kind, the software-float helpers (libgcc `__aeabi_d*`, `__aeabi_f*`,
  `__addsf3` & co.) executed inside app_tick, their calls and instructions over the whole run.

Prints, for each state, its worst tick's total and its top functions (symbol, instructions,
share of the tick), the same for its smallest tick, then the mean EXECUTE tick's top functions
and the soft-float helpers left.
  tick_profile.py PREFIX [--top N] [--target T]"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

KINDS = ("idle", "teach", "execute", "upload", "fwupdate", "fault")


def read_counts(path: Path) -> dict[str, float]:
    """'count symbol' lines -> {symbol: count} (a symbol's lines summed)."""
    out: dict[str, float] = {}
    for line in path.read_text().splitlines():
        parts = line.split(None, 1)
        if len(parts) == 2:
            out[parts[1]] = out.get(parts[1], 0.0) + float(parts[0])
    return out


def top_lines(counts: dict[str, float], total: float, n: int) -> list[str]:
    """The n largest entries as aligned lines: instructions, share of total, symbol."""
    rows = sorted(counts.items(), key=lambda kv: (-kv[1], kv[0]))[:n]
    return [f"  {v:>9,.0f}  {100.0 * v / total:5.1f} %  {s}" for s, v in rows] if total > 0 else []


LABELS = {"max": "worst", "min": "smallest", "focus": "focus"}


def print_states(prefix: Path, target: str, n: int, which: str = "max") -> int:
    """The worst (which="max") or smallest ("min") tick of every kind found, or the focus
    functions' largest tick ("focus", only where the run wrote one); returns how many kinds had
    a profile."""
    found = 0
    label = LABELS[which]
    for k in KINDS:
        p = Path(f"{prefix}.{which}.{k}")
        if not p.exists():
            if which != "focus":
                print(f"tick_profile target={target} state={k.upper()} {label}=- (no tick of this kind)")
            continue
        found += 1
        counts = read_counts(p)
        total = sum(counts.values())
        print(f"tick_profile target={target} state={k.upper()} {label}={total:,.0f} instructions; top {n}:")
        for line in top_lines(counts, total, n):
            print(line)
    return found


def print_mean_execute(prefix: Path, target: str, n: int) -> None:
    if not prefix.exists():
        return
    counts = read_counts(prefix)
    total = sum(counts.values())
    print(f"tick_profile target={target} mean EXECUTE tick {total:,.0f} instructions; top {n}:")
    for line in top_lines(counts, total, n):
        print(line)


def print_softfloat(prefix: Path, target: str) -> None:
    """'kind symbol calls instructions' lines -> one line per kind with the helpers left."""
    p = Path(f"{prefix}.softfloat")
    per: dict[str, list[tuple[str, int, int]]] = {k: [] for k in KINDS}
    if p.exists():
        for line in p.read_text().splitlines():
            parts = line.split()
            if len(parts) == 4 and parts[0] in per:
                per[parts[0]].append((parts[1], int(parts[2]), int(parts[3])))
    for k in KINDS:
        rows = sorted(per[k], key=lambda r: -r[2])
        names = " ".join(f"{s}({c} calls, {i} insns)" for s, c, i in rows) or "none"
        print(f"softfloat_in_app_tick target={target} state={k.upper()} helpers={len(rows)}: {names}")


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("prefix", type=Path, help="the QEMU_TICK_PROFILE prefix of a qemu_tick.sh run")
    ap.add_argument("--top", type=int, default=12, help="functions per state (default 12)")
    ap.add_argument("--target", default="-", help="the image's target, for the printed lines")
    args = ap.parse_args(argv)
    if args.top < 1:
        print("tick_profile: --top must be >= 1", file=sys.stderr)
        return 2
    if print_states(args.prefix, args.target, args.top) == 0:
        print(f"tick_profile: no {args.prefix}.max.* file (run with QEMU_TICK_PROFILE)", file=sys.stderr)
        return 1
    print_states(args.prefix, args.target, args.top, "min")
    print_states(args.prefix, args.target, args.top, "focus")
    print_mean_execute(args.prefix, args.target, args.top)
    print_softfloat(args.prefix, args.target)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
