"""forceskill.wire.dbc: the packaged DBC, node offsets and the E2E protection of safety frames,
against the published CRC-8/SAE-J1850 check value and a bitwise reference written here."""

from __future__ import annotations

import pytest

from forceskill.wire import dbc
from helpers.paths import REPO


def _crc8_reference(data: bytes) -> int:
    """CRC-8/SAE-J1850 as the catalogue defines it: poly 0x1D, init 0xFF, no reflection, xorout 0xFF,
    computed over the message as one big-endian bit string."""
    bits = "".join(f"{b:08b}" for b in data)
    reg = 0xFF
    for bit in bits:
        top = (reg >> 7) & 1
        reg = (reg << 1) & 0xFF
        if top ^ int(bit):
            reg ^= 0x1D
    return reg ^ 0xFF


def test_crc8_check_value_and_reference() -> None:
    assert dbc.crc8_j1850(b"123456789") == 0x4B  # the catalogue's check value
    for data in (b"", b"\x00", b"\xff" * 8, bytes(range(8)), b"forceskill"):
        assert dbc.crc8_j1850(data) == _crc8_reference(data)


def test_protect_then_check_and_any_flipped_bit_is_caught() -> None:
    frame = dbc.protect(0x120, bytes([1, 2, 3, 4, 5, 6, 0xA0, 0]), counter=0x17)
    assert frame[6] == 0xA7  # high nibble kept, counter's low nibble
    assert dbc.check(0x120, frame)
    assert not dbc.check(0x121, frame)  # the identifier is protected too
    for i in range(8):
        for bit in range(8):
            bad = bytearray(frame)
            bad[i] ^= 1 << bit
            assert not dbc.check(0x120, bytes(bad)), (i, bit)
    assert not dbc.check(0x120, frame[:7])


def test_the_packaged_dbc_is_the_firmwares_and_nodes_shift_every_id() -> None:
    assert dbc.dbc_path().read_bytes() == (REPO / "firmware" / "proto" / "forceskill.dbc").read_bytes()
    base = {m.name: m.frame_id for m in dbc.load_db(0).messages}
    shifted = {m.name: m.frame_id for m in dbc.load_db(5).messages}
    assert base and all(shifted[n] == base[n] + 5 for n in base)
    with pytest.raises(ValueError):
        dbc.load_db(16)
