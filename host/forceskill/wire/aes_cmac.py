"""AES-128 encryption (FIPS 197) and AES-CMAC (NIST SP 800-38B, RFC 4493), the MAC of the
authenticated host frames (docs/protocol.md), in pure Python: the reference of the firmware's
``sec_aes.c``, checked against the same published vectors (tests/host/wire/test_aes_cmac.py).

A frame MAC costs ~0.1 ms here (the one-line timing loop in docs/protocol.md); the host sends
~110 authenticated frames a second.
"""

from __future__ import annotations

import functools

BLOCK = 16


def _xtime(a: int) -> int:
    return ((a << 1) ^ (0x1B if a & 0x80 else 0)) & 0xFF


def _gmul(a: int, b: int) -> int:
    r = 0
    while b:
        if b & 1:
            r ^= a
        a = _xtime(a)
        b >>= 1
    return r


@functools.cache
def _tables() -> tuple[tuple[int, ...], tuple[tuple[int, ...], ...]]:
    """The S-box (FIPS 197 5.1.1: inverse in GF(2^8), then the affine map) and the four round
    tables T_k[x] = S[x] * (02, 01, 01, 03) rotated right by 8k bits."""
    exp = [1] * 255  # powers of the generator 3
    for i in range(1, 255):
        exp[i] = _gmul(exp[i - 1], 3)
    log = {v: i for i, v in enumerate(exp)}
    inv = [0] + [exp[(255 - log[a]) % 255] for a in range(1, 256)]
    sbox = []
    for a in range(256):
        b = inv[a]
        s = b
        for k in range(1, 5):
            s ^= ((b << k) | (b >> (8 - k))) & 0xFF
        sbox.append(s ^ 0x63)
    t0 = [(_gmul(s, 2) << 24) | (s << 16) | (s << 8) | _gmul(s, 3) for s in sbox]
    rot = [tuple(((v >> (8 * k)) | (v << (32 - 8 * k))) & 0xFFFFFFFF for v in t0) for k in range(4)]
    return tuple(sbox), tuple(rot)


def expand_key(key: bytes) -> list[int]:
    """The 44 round-key words of an AES-128 key (FIPS 197 5.2)."""
    if len(key) != 16:
        raise ValueError(f"AES-128 key must be 16 bytes, not {len(key)}")
    sbox, _ = _tables()
    rk = [int.from_bytes(key[4 * i : 4 * i + 4], "big") for i in range(4)]
    rcon = 1
    for i in range(4, 44):
        t = rk[i - 1]
        if i % 4 == 0:
            t = ((t << 8) | (t >> 24)) & 0xFFFFFFFF
            t = (
                (sbox[t >> 24] << 24)
                | (sbox[(t >> 16) & 0xFF] << 16)
                | (sbox[(t >> 8) & 0xFF] << 8)
                | sbox[t & 0xFF]
            )
            t ^= rcon << 24
            rcon = _xtime(rcon)
        rk.append(rk[i - 4] ^ t)
    return rk


def encrypt_block(rk: list[int], block: bytes) -> bytes:
    """One AES-128 block encryption under the round keys rk (expand_key)."""
    sbox, (t0, t1, t2, t3) = _tables()
    s0, s1, s2, s3 = (int.from_bytes(block[4 * i : 4 * i + 4], "big") ^ rk[i] for i in range(4))
    for r in range(4, 40, 4):
        s0, s1, s2, s3 = (
            t0[s0 >> 24] ^ t1[(s1 >> 16) & 0xFF] ^ t2[(s2 >> 8) & 0xFF] ^ t3[s3 & 0xFF] ^ rk[r],
            t0[s1 >> 24] ^ t1[(s2 >> 16) & 0xFF] ^ t2[(s3 >> 8) & 0xFF] ^ t3[s0 & 0xFF] ^ rk[r + 1],
            t0[s2 >> 24] ^ t1[(s3 >> 16) & 0xFF] ^ t2[(s0 >> 8) & 0xFF] ^ t3[s1 & 0xFF] ^ rk[r + 2],
            t0[s3 >> 24] ^ t1[(s0 >> 16) & 0xFF] ^ t2[(s1 >> 8) & 0xFF] ^ t3[s2 & 0xFF] ^ rk[r + 3],
        )
    out = bytearray()
    for c, (a, b, d, e) in enumerate(
        ((s0, s1, s2, s3), (s1, s2, s3, s0), (s2, s3, s0, s1), (s3, s0, s1, s2))
    ):
        w = (
            (sbox[a >> 24] << 24)
            | (sbox[(b >> 16) & 0xFF] << 16)
            | (sbox[(d >> 8) & 0xFF] << 8)
            | sbox[e & 0xFF]
        )
        out += (w ^ rk[40 + c]).to_bytes(4, "big")
    return bytes(out)


def _dbl(b: bytes) -> bytes:
    v = int.from_bytes(b, "big") << 1
    if v >> 128:
        v ^= 0x87
    return (v & ((1 << 128) - 1)).to_bytes(16, "big")


def subkeys(key: bytes) -> tuple[bytes, bytes]:
    """K1, K2 of SP 800-38B 6.1."""
    k1 = _dbl(encrypt_block(expand_key(key), bytes(16)))
    return k1, _dbl(k1)


@functools.lru_cache(maxsize=8)
def _keyed(key: bytes) -> tuple[list[int], bytes, bytes]:
    return expand_key(key), *subkeys(key)


def cmac(key: bytes, msg: bytes) -> bytes:
    """AES-CMAC of msg (any length) under a 16-byte key: the full 16-byte tag."""
    rk, k1, k2 = _keyed(bytes(key))
    n = max(1, -(-len(msg) // BLOCK))
    last = msg[BLOCK * (n - 1) :]
    if len(last) == BLOCK:
        last = bytes(a ^ b for a, b in zip(last, k1, strict=True))
    else:
        last = bytes(a ^ b for a, b in zip(last + b"\x80" + bytes(BLOCK - 1 - len(last)), k2, strict=True))
    x = bytes(BLOCK)
    for i in range(n - 1):
        x = encrypt_block(rk, bytes(a ^ b for a, b in zip(x, msg[BLOCK * i : BLOCK * (i + 1)], strict=True)))
    return encrypt_block(rk, bytes(a ^ b for a, b in zip(x, last, strict=True)))
