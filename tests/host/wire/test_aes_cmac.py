"""The host's AES-CMAC (forceskill.wire.dbc.cmac, the `cryptography` package's) against the
published vectors: the SP 800-38B appendix D.1 AES-128 examples (RFC 4493 section 4), the same the
firmware's tests use (tests/firmware/security/test_cmac.c); and the frame MAC as the truncated CMAC
of the documented input (the firmware accepting the host's frames is tests/can/test_auth.py)."""

from __future__ import annotations

from forceskill.wire.dbc import cmac, frame_mac

KEY = bytes.fromhex("2b7e151628aed2a6abf7158809cf4f3c")
MSG = bytes.fromhex(
    "6bc1bee22e409f96e93d7e117393172aae2d8a571e03ac9c9eb76fac45af8e51"
    "30c81c46a35ce411e5fbc1191a0a52eff69f2445df4f9b17ad2b417be66c3710"
)


def test_cmac_sp800_38b_examples() -> None:
    want = {
        0: "bb1d6929e95937287fa37d129b756746",
        16: "070a16b46b4d4144f79bdd9dd04a287c",
        40: "dfa66747de9ae63030ca32611497c827",
        64: "51f0bebf7e3b9d92fc49741779363cfe",
    }
    for n, tag in want.items():
        assert cmac(KEY, MSG[:n]).hex() == tag


def test_frame_mac_is_the_truncated_cmac_of_id_payload_fv() -> None:
    key = bytes(range(0x30, 0x40))
    data = bytes([3, 0xE8, 0x03, 0, 0, 0, 0, 0])
    msg = bytes([0x05, 0x01, 3, 0xE8, 0x03]) + (0x01020304).to_bytes(4, "big")
    assert frame_mac(key, 0x105, data, 0x01020304) == cmac(key, msg)[:3]
