#!/usr/bin/env python3
"""Compare the f_hat rollout printed by a qemu benchmark image with the host build's.

Both files hold lines `fhat XXXXXXXX ...` (raw bits, hex). float: float32 bits, must agree within
1e-4 of max |f_hat| (the M4F uses newlib's expf, the host glibc's); fixed: Q16.16 N, must be bit
for bit identical. Prints one line `qemu_vs_host ...`; exit status 1 on mismatch."""

import struct
import sys


def load(path):
    vals = []
    with open(path, encoding="ascii", errors="replace") as f:
        for line in f:
            parts = line.split()
            if parts and parts[0] == "fhat":
                vals.extend(int(p, 16) for p in parts[1:])
    return vals


def load_csv(path):
    """Golden float64 rollout (t,f_hat; row 0 is t = 0, before the first tick)."""
    with open(path, encoding="ascii") as f:
        rows = [line.strip().split(",") for line in f if line.strip()]
    return [float(r[1]) for r in rows[1:]][1:]


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
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
