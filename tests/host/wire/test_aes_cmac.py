"""The host's AES-128 and AES-CMAC (forceskill.wire.aes_cmac) against the published vectors: the
FIPS 197 appendix C.1 example, the SP 800-38B appendix D.1 AES-128 subkeys and its four examples
(RFC 4493 section 4), the same the firmware's tests use (tests/firmware/security/test_cmac.c);
and the frame MAC as the truncated CMAC of the documented input (the firmware accepting the host's
frames is tests/can/test_auth.py)."""

from __future__ import annotations

from forceskill.wire import aes_cmac
from forceskill.wire.dbc import frame_mac

KEY = bytes.fromhex("2b7e151628aed2a6abf7158809cf4f3c")
MSG = bytes.fromhex(
    "6bc1bee22e409f96e93d7e117393172aae2d8a571e03ac9c9eb76fac45af8e51"
    "30c81c46a35ce411e5fbc1191a0a52eff69f2445df4f9b17ad2b417be66c3710"
)


def test_aes128_fips197_c1() -> None:
    rk = aes_cmac.expand_key(bytes(range(16)))
    ct = aes_cmac.encrypt_block(rk, bytes.fromhex("00112233445566778899aabbccddeeff"))
    assert ct.hex() == "69c4e0d86a7b0430d8cdb78070b4c55a"


def test_cmac_sp800_38b_subkeys_and_examples() -> None:
    k1, k2 = aes_cmac.subkeys(KEY)
    assert k1.hex() == "fbeed618357133667c85e08f7236a8de"
    assert k2.hex() == "f7ddac306ae266ccf90bc11ee46d513b"
    want = {
        0: "bb1d6929e95937287fa37d129b756746",
        16: "070a16b46b4d4144f79bdd9dd04a287c",
        40: "dfa66747de9ae63030ca32611497c827",
        64: "51f0bebf7e3b9d92fc49741779363cfe",
    }
    for n, tag in want.items():
        assert aes_cmac.cmac(KEY, MSG[:n]).hex() == tag


def test_frame_mac_is_the_truncated_cmac_of_id_payload_fv() -> None:
    key = bytes(range(0x30, 0x40))
    data = bytes([3, 0xE8, 0x03, 0, 0, 0, 0, 0])
    msg = bytes([0x05, 0x01, 3, 0xE8, 0x03]) + (0x01020304).to_bytes(4, "big")
    assert frame_mac(key, 0x105, data, 0x01020304) == aes_cmac.cmac(key, msg)[:3]
