"""Firmware image tool (forceskill.model.fwimage, `forceskill image build|show`, `flash --dry-run`)."""

from __future__ import annotations

import hashlib
import hmac
import struct

import pytest

from forceskill import cli
from forceskill.model import fwimage as fw
from helpers.paths import REPO

GOLDEN = REPO / "tests" / "firmware" / "boot" / "vectors" / "golden_host_1.2.3.fwimg"


def golden_payload() -> bytes:
    return bytes((i * 7) % 251 for i in range(1000))


def test_golden_vector_is_reproduced_exactly():
    # the C tests verify this file (hash, tag) with firmware/security; Python must keep writing it
    # the golden image was written when skills were format 1: it declares (1, 1)
    img = fw.build_image(
        golden_payload(), "1.2.3", "host", fw.DEV_KEY, build_id="golden-1", skill_format=(1, 1)
    )
    assert img == GOLDEN.read_bytes()


def test_layout_against_an_independent_packing():
    payload = b"\x01\x02\x03\x04" * 100
    img = fw.build_image(
        payload,
        "2.5.17",
        "cortex-m3",
        fw.DEV_KEY,
        build_id="x",
        entry_offset=0x40,
        skill_format=(2, 1),
        config_format=(3, 3),
    )
    assert len(img) == 128 + 400 + 32
    magic, fmt, hsize, ver, length, target, flags = struct.unpack_from("<IHHIIII", img)
    assert (magic, fmt, hsize, ver, length, target, flags) == (0x57465346, 1, 128, 0x02050011, 400, 2, 0)
    assert img[:4] == b"FSFW"
    assert struct.unpack_from("<HHHHI", img, 24) == (2, 1, 3, 3, 0x40)
    assert img[36:64] == bytes(28)
    assert img[64:96] == hashlib.sha256(payload).digest()
    assert img[96:128].rstrip(b"\0") == b"x"
    assert img[-32:] == hmac.new(fw.DEV_KEY, img[:-32], hashlib.sha256).digest()


@pytest.mark.parametrize(
    "mutate, code",
    [
        (lambda b: b[:100], fw.ERR_TRUNCATED),
        (lambda b: b"XSFW" + b[4:], fw.ERR_MAGIC),
        (lambda b: b[:4] + b"\x02" + b[5:], fw.ERR_FORMAT),
        (lambda b: b[:40] + b"\x01" + b[41:], fw.ERR_FORMAT),
        (lambda b: b[:16] + b"\x09" + b[17:], fw.ERR_TARGET),
        (lambda b: b[:-1], fw.ERR_TRUNCATED),
        (lambda b: b + b"\0", fw.ERR_FORMAT),
        (lambda b: b[:300] + bytes([b[300] ^ 1]) + b[301:], fw.ERR_HASH),
        (lambda b: b[:-1] + bytes([b[-1] ^ 1]), fw.ERR_TAG),
    ],
)
def test_each_defect_gives_its_code(mutate, code):
    img = fw.build_image(b"\x55" * 1000, "1.0.0", "host", fw.DEV_KEY)
    with pytest.raises(fw.ImageError) as e:
        fw.parse_image(mutate(img), fw.DEV_KEY)
    assert e.value.code == code


def test_versions_and_arguments():
    assert fw.pack_version("1.2.3") == 0x01020003
    assert fw.unpack_version(fw.pack_version("255.255.65535")) == "255.255.65535"
    assert fw.pack_version("1.10.0") > fw.pack_version("1.9.99")
    for bad in ("1.2", "1.2.3.4", "256.0.0", "v1.2.3"):
        with pytest.raises(fw.ImageError) as e:
            fw.pack_version(bad)
        assert e.value.code == fw.ERR_ARGS
    with pytest.raises(fw.ImageError):
        fw.build_image(b"x", "1.0.0", "pdp-11", fw.DEV_KEY)
    with pytest.raises(fw.ImageError):
        fw.build_image(b"x" * 8, "1.0.0", "host", fw.DEV_KEY, entry_offset=8)


def test_cli_build_show_and_dry_run(tmp_path, capsys, monkeypatch):
    monkeypatch.delenv(fw.KEY_ENV, raising=False)
    binary = tmp_path / "fw.bin"
    binary.write_bytes(golden_payload())
    key = tmp_path / "key.hex"
    key.write_text(bytes(range(100, 132)).hex())
    out = tmp_path / "fw.fwimg"
    assert (
        cli.main(
            [
                "image",
                "build",
                str(binary),
                "-o",
                str(out),
                "--version",
                "3.1.4",
                "--target",
                "cortex-m4f",
                "--key",
                str(key),
                "--build-id",
                "g1234",
            ]
        )
        == 0
    )
    text = capsys.readouterr().out
    assert "firmware version  3.1.4" in text and "target            cortex-m4f" in text
    assert "tag (HMAC-SHA256) valid" in text
    assert cli.main(["image", "show", str(out), "--key", str(key)]) == 0
    assert "tag (HMAC-SHA256) valid" in capsys.readouterr().out
    assert cli.main(["image", "show", str(out), "--dev-key"]) == 2  # not the development key
    assert "authentication tag wrong for this key [706]" in capsys.readouterr().err
    assert cli.main(["image", "show", str(out)]) == 0  # no key: header only
    assert "not checked (no key)" in capsys.readouterr().out
    assert cli.main(["flash", str(out), "--dry-run", "--key", str(key)]) == 0
    text = capsys.readouterr().out
    assert "image:  firmware 3.1.4 for cortex-m4f, build 'g1234', 1160 bytes" in text
    assert "dry run: no device contacted, nothing written" in text
    # bad input: one line, no traceback, exit 2, no file
    assert (
        cli.main(
            [
                "image",
                "build",
                str(binary),
                "-o",
                str(tmp_path / "no.fwimg"),
                "--version",
                "1.x",
                "--target",
                "host",
            ]
        )
        == 2
    )
    assert "version '1.x' is not MAJOR.MINOR.PATCH [731]" in capsys.readouterr().err
    assert not (tmp_path / "no.fwimg").exists()
    assert cli.main(["flash", str(tmp_path / "missing.fwimg"), "--dry-run"]) == 2
    assert "[731]" in capsys.readouterr().err
