#!/usr/bin/env python3
"""Compare the f_hat rollout printed by a qemu benchmark image with the host build's.

Both files hold lines `fhat XXXXXXXX ...` (raw bits, hex). float: float32 bits, must agree within
1e-4 of max |f_hat| (the M4F uses newlib's expf, the host glibc's); fixed: Q16.16 N, must be bit
for bit identical. Prints one line `qemu_vs_host ...`; exit status 1 on mismatch. Lines
`ypath XXXXXXXX ...` hold the y DMP's p (float32 bits, or Q8.24 m; all 0 for a force-only skill):
compared the same way relative to max |p| (line `qemu_vs_host_path ...`), and with a golden CSV
of three columns (t,f_hat,y_hat) against y_hat - y_hat(0)."""

import struct
import sys


def load(path, tag="fhat"):
    vals = []
    with open(path, encoding="ascii", errors="replace") as f:
        for line in f:
            parts = line.split()
            if parts and parts[0] == tag:
                vals.extend(int(p, 16) for p in parts[1:])
    return vals


def load_csv(path, column=1):
    """Golden float64 rollout (t,f_hat[,y_hat]; row 0 is t = 0, before the first tick); the y
    column as p = y_hat - y_hat(0)."""
    with open(path, encoding="ascii") as f:
        rows = [line.strip().split(",") for line in f if line.strip()]
    if len(rows[0]) <= column:
        return None
    v = [float(r[column]) for r in rows[1:]]
    base = v[0] if column == 2 else 0.0
    return [x - base for x in v][1:]


def compare_path(numeric, target, qemu_path, host_path, golden):
    """The y DMP's p of qemu vs host (and vs the golden y_hat); True when within the limits."""
    q, h = load(qemu_path, "ypath"), load(host_path, "ypath")
    if not q and not h:
        return True
    if len(q) != len(h):
        print(f"qemu_vs_host_path target={target} FAILED: {len(q)} qemu rows vs {len(h)} host rows")
        return False
    if numeric == "fixed":

        def conv(b):
            return struct.unpack("<i", struct.pack("<I", b))[0] / 16777216.0
    else:

        def conv(b):
            return struct.unpack("<f", struct.pack("<I", b))[0]

    qp, hp = [conv(b) for b in q], [conv(b) for b in h]
    pmax = max(abs(v) for v in hp)
    if pmax == 0.0:
        ok = q == h
        print(f"qemu_vs_host_path target={target} no y DMP (p = 0 on every row) {'ok' if ok else 'FAILED'}")
        return ok
    rel = max(abs(a - b) for a, b in zip(qp, hp, strict=False)) / pmax
    ok = (q == h) if numeric == "fixed" else (rel <= 1e-4)
    print(
        f"qemu_vs_host_path target={target} numeric={numeric} rows={len(q)} max_path_m={pmax:.6g} "
        f"rel={rel:.3g} {'ok' if ok else 'FAILED'} "
        f"({'bit-exact required' if numeric == 'fixed' else 'limit 1e-4 of max |p|'})"
    )
    g = load_csv(golden, 2) if golden else None
    if g is not None:
        grel = max(abs(a - b) for a, b in zip(qp, g, strict=False)) / max(abs(v) for v in g)
        limit = 2e-4 if numeric == "float" else 1e-3
        gok = len(g) == len(qp) and grel <= limit
        print(
            f"qemu_vs_float64_path target={target} numeric={numeric} max_err={100 * grel:.5f} % of "
            f"max |p| (limit {100 * limit:g} %) {'ok' if gok else 'FAILED'}"
        )
        ok = ok and gok
    return ok


def main():
    numeric, target, qemu_path, host_path = sys.argv[1:5]
    golden = sys.argv[5] if len(sys.argv) > 5 else None
    q, h = load(qemu_path), load(host_path)
    if not q or len(q) != len(h):
        print(f"qemu_vs_host target={target} FAILED: {len(q)} qemu rows vs {len(h)} host rows")
        return 1
    if numeric == "fixed":

        def conv(b):
            return struct.unpack("<i", struct.pack("<I", b))[0] / 65536.0
    else:

        def conv(b):
            return struct.unpack("<f", struct.pack("<I", b))[0]

    qf, hf = [conv(b) for b in q], [conv(b) for b in h]
    fmax = max(abs(v) for v in hf)
    diff = max(abs(a - b) for a, b in zip(qf, hf, strict=False))
    same = sum(1 for a, b in zip(q, h, strict=False) if a == b)
    rel = diff / fmax if fmax > 0 else diff
    ok = (q == h) if numeric == "fixed" else (rel <= 1e-4)
    print(
        f"qemu_vs_host target={target} numeric={numeric} rows={len(q)} max_force_N={fmax:.6g} "
        f"max_diff_N={diff:.3g} rel={rel:.3g} identical_rows={same}/{len(q)} "
        f"{'ok' if ok else 'FAILED'} ({'bit-exact required' if numeric == 'fixed' else 'limit 1e-4 of max force'})"
    )
    if golden:
        g = load_csv(golden)
        if len(g) != len(qf):
            print(f"qemu_vs_float64 FAILED: {len(g)} golden rows vs {len(qf)} qemu rows")
            return 1
        gmax = max(abs(v) for v in g)
        grel = max(abs(a - b) for a, b in zip(qf, g, strict=False)) / gmax
        # float32 within 0.02 % of max force of float64, fixed within 0.1 %
        limit = 2e-4 if numeric == "float" else 1e-3
        gok = grel <= limit
        print(
            f"qemu_vs_float64 target={target} numeric={numeric} golden={golden.split('/')[-1]} "
            f"max_err={100 * grel:.5f} % of max force (limit {100 * limit:g} %) "
            f"{'ok' if gok else 'FAILED'}"
        )
        ok = ok and gok
    ok = compare_path(numeric, target, qemu_path, host_path, golden) and ok
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
