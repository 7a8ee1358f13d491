"""Skill image v2: layout, round trip, JSON twin, and every corrupt image refused with its code."""

from __future__ import annotations

import json
import struct
import zlib
from pathlib import Path

import numpy as np
import pytest

from forceskill.errors import SkillError
from forceskill.model.fit import FitResult
from forceskill.model.skill import MAGIC, Skill, image_size
from helpers.paths import VECTORS


def test_layout_matches_docs_skill_format(press_fit: FitResult) -> None:
    sk = press_fit.skill
    b = sk.to_bytes()
    n = sk.n_kernels
    assert len(b) == 136 + 24 * n + 4 == image_size(n)
    assert b[:4] == b"FSKL" and struct.unpack_from("<I", b, 0)[0] == MAGIC
    assert struct.unpack_from("<HHIHH", b, 4) == (2, 136, len(b), n, sk.flags)
    offsets = {
        16: sk.dt_s,
        24: sk.tau_s,
        32: sk.alpha,
        40: sk.beta,
        48: sk.gamma,
        56: sk.stiffness_Npm,
        64: sk.goal_N,
        72: sk.duration_s,
        80: sk.m_d_kg,
        88: sk.k_d_Nspm,
        96: sk.k_p_Npm,
        104: sk.kkf_Npm,
        112: sk.kki_Npms,
        120: sk.surface_m,
        128: sk.force0_N,
    }
    for off, val in offsets.items():
        assert struct.unpack_from("<d", b, off)[0] == val
    np.testing.assert_array_equal(np.frombuffer(b, "<f8", n, 136), sk.centres)
    np.testing.assert_array_equal(np.frombuffer(b, "<f8", n, 136 + 8 * n), sk.widths)
    np.testing.assert_array_equal(np.frombuffer(b, "<f8", n, 136 + 16 * n), sk.weights)
    assert struct.unpack_from("<I", b, 136 + 24 * n)[0] == zlib.crc32(b[: 136 + 24 * n])


def test_a_version_1_image_is_refused_naming_both_versions() -> None:
    data = (VECTORS / "bad" / "version_1.skill").read_bytes()
    with pytest.raises(SkillError) as e:
        Skill.from_bytes(data)
    assert e.value.code == 202
    assert "version 1 is not supported" in str(e.value) and "reads versions 2 to 5" in str(e.value)
    assert "fit the demonstration again" in str(e.value)


def test_firmware_images_declare_this_skill_format() -> None:
    from forceskill.model import fwimage, skill

    assert fwimage.SKILL_FORMAT == skill.FORMAT_VERSION
    assert fwimage.SKILL_FORMAT_OLDEST == skill.FORMAT_VERSION_MIN


def test_round_trip_bytes_file_and_json(press_fit: FitResult, engrave_fit: FitResult, tmp_path: Path) -> None:
    for res in (press_fit, engrave_fit):
        sk = res.skill
        b = sk.to_bytes()
        assert Skill.from_bytes(b).to_bytes() == b
        p = tmp_path / "a.skill"
        sk.write(p)
        assert p.read_bytes() == b
        d = json.loads((tmp_path / "a.skill.json").read_text())
        assert d["n_kernels"] == sk.n_kernels and d["end_policy"] == sk.end_policy
        assert d["crc32"] == f"0x{zlib.crc32(b[:-4]):08X}"
        assert Skill.from_json_dict(d).to_bytes() == b
        assert Skill.read(p).to_bytes() == b
        assert sorted(x.name for x in tmp_path.iterdir()) == ["a.skill", "a.skill.json"]  # no temp left


def test_end_policy_flag(press_fit: FitResult, engrave_fit: FitResult) -> None:
    assert press_fit.skill.end_policy == "hold" and press_fit.skill.flags == 0
    assert engrave_fit.skill.end_policy == "release" and engrave_fit.skill.flags == 1


def bad_manifest() -> list[tuple[str, int]]:
    lines = (VECTORS / "bad" / "manifest.txt").read_text().split("\n")
    return [(ln.split()[0], int(ln.split()[1])) for ln in lines if ln.strip()]


def test_bad_manifest_covers_every_code() -> None:
    codes = {c for _, c in bad_manifest()}
    assert codes == set(range(200, 212)) | set(range(228, 232)) | {233, 234}


@pytest.mark.parametrize("name,code", bad_manifest())
def test_every_bad_image_is_refused_with_its_code(name: str, code: int) -> None:
    data = (VECTORS / "bad" / name).read_bytes()
    with pytest.raises(SkillError) as e:
        Skill.from_bytes(data)
    assert e.value.code == code, str(e.value)
    assert "\n" not in str(e.value)
    if code > 204:  # refused after the CRC check: the CRC must be right to get there
        body = len(data) - 4
        assert struct.unpack_from("<I", data, body)[0] == zlib.crc32(data[:body])


def test_writing_an_invalid_skill_is_refused_and_writes_nothing(press_fit: FitResult, tmp_path: Path) -> None:
    sk = Skill.from_bytes(press_fit.skill.to_bytes())
    sk.goal_N = -1.0
    with pytest.raises(SkillError) as e:
        sk.write(tmp_path / "bad.skill")
    assert e.value.code == 207
    assert list(tmp_path.iterdir()) == []
