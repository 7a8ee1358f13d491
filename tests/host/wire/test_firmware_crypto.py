"""The firmware's AES-128, AES-CMAC, SHA-256 and HMAC-SHA256 (firmware/security/sec_aes.c,
sec_sha256.c) against the `cryptography` package and Python's hashlib/hmac, on random keys and
messages of every length class (empty, below, at and across block boundaries, longer than an HMAC
block key): tests/firmware/security/crypto_vectors.c, compiled here with the firmware's
warnings, answers each input; the AES block also through the firmware's sliced job, SHA-256 also
fed in pieces."""

from __future__ import annotations

import hashlib
import hmac
import random
import shutil
import subprocess
from pathlib import Path

import pytest
from cryptography.hazmat.primitives.ciphers import Cipher, algorithms, modes

from forceskill.wire.dbc import cmac

ROOT = Path(__file__).resolve().parents[3]
SEC = ROOT / "firmware" / "security"
PROGRAM = ROOT / "tests" / "firmware" / "security" / "crypto_vectors.c"
LENGTHS = [0, 1, 15, 16, 17, 31, 32, 33, 55, 56, 63, 64, 65, 100, 127, 128, 129, 200, 511]
FLAGS = ["-std=c11", "-O1", "-Wall", "-Wextra", "-Wconversion", "-Wdouble-promotion", "-Werror"]


@pytest.fixture(scope="module")
def firmware(tmp_path_factory: pytest.TempPathFactory) -> Path:
    cc = shutil.which("cc")
    if cc is None:
        pytest.skip("no C compiler")
    exe = tmp_path_factory.mktemp("crypto") / "crypto_vectors"
    sources = [PROGRAM, SEC / "sec_aes.c", SEC / "sec_sha256.c"]
    subprocess.run([cc, *FLAGS, f"-I{SEC}", *map(str, sources), "-o", str(exe)], check=True)
    return exe


def _ask(exe: Path, lines: list[str]) -> list[str]:
    res = subprocess.run(
        [str(exe)], input="\n".join(lines) + "\n", capture_output=True, text=True, check=True
    )
    return res.stdout.split()


def _hex(b: bytes) -> str:
    return b.hex() or "-"


def _aes(key: bytes, block: bytes) -> bytes:
    enc = Cipher(algorithms.AES(key), modes.ECB()).encryptor()
    return enc.update(block) + enc.finalize()


def test_aes128_and_its_sliced_job_against_cryptography(firmware: Path) -> None:
    rng = random.Random(1)
    cases = [(rng.randbytes(16), rng.randbytes(16)) for _ in range(64)]
    out = _ask(firmware, [f"aes {k.hex()} {p.hex()}" for k, p in cases])
    assert len(out) == 2 * len(cases)
    for i, (k, p) in enumerate(cases):
        want = _aes(k, p).hex()
        assert (out[2 * i], out[2 * i + 1]) == (want, want), f"key {k.hex()} block {p.hex()}"


def test_cmac_against_cryptography(firmware: Path) -> None:
    rng = random.Random(2)
    cases = [(rng.randbytes(16), rng.randbytes(n)) for n in LENGTHS for _ in range(3)]
    out = _ask(firmware, [f"cmac {k.hex()} {_hex(m)}" for k, m in cases])
    assert out == [cmac(k, m).hex() for k, m in cases]


def test_sha256_whole_and_in_pieces_against_hashlib(firmware: Path) -> None:
    rng = random.Random(3)
    cases = [rng.randbytes(n) for n in LENGTHS for _ in range(3)]
    out = _ask(firmware, [f"sha {_hex(m)}" for m in cases])
    assert out == [h for m in cases for h in (hashlib.sha256(m).hexdigest(),) * 2]


def test_hmac_sha256_against_hmac(firmware: Path) -> None:
    rng = random.Random(4)
    keys = [0, 1, 16, 32, 63, 64, 65, 100]
    cases = [(rng.randbytes(k), rng.randbytes(n)) for k in keys for n in LENGTHS[::3]]
    out = _ask(firmware, [f"hmac {_hex(k)} {_hex(m)}" for k, m in cases])
    assert out == [hmac.new(k, m, hashlib.sha256).hexdigest() for k, m in cases]
