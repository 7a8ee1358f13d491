"""forceskill.wire: the golden vectors of tests/vectors/wire.txt (the C codec reads the same file,
tests/firmware/proto/test_wire.c), the values they carry, and the pack-side range checks."""

from __future__ import annotations

import math
import runpy
import struct
from pathlib import Path

import pytest

from forceskill import wire as W
from forceskill.errors import ERR_WIRE_LENGTH, ERR_WIRE_RANGE, FsError

VECTORS = Path(__file__).parents[2] / "vectors"
CLASSES = {
    "versions": W.Versions,
    "gains": W.Gains,
    "limits": W.Limits,
    "comm": W.Comm,
    "object": W.Object,
    "stiffness_max": W.StiffnessMax,
    "slot_entry": W.SlotEntry,
    "slot_dir": W.SlotDir,
    "last_transfer": W.LastTransfer,
    "device_state": W.DeviceState,
    "fault_causes": W.FaultCauses,
    "contact_wait": W.ContactWait,
    "band": W.Band,
    "run_skill_band": W.RunSkillBand,
    "run_skill": W.RunSkill,
    "run_periodic": W.RunPeriodic,
    "run_step": W.RunStep,
    "run_sequence": W.RunSequence,
    "run_results": W.RunResults,
    "self_test": W.SelfTest,
    "erase_slot": W.EraseSlot,
    "motion_key": W.MotionKey,
    "motion_key_write": W.MotionKeyWrite,
    "auth_stats": W.AuthStats,
    "fwu_status": W.FwuStatus,
    "transfer_exit": W.TransferExit,
    "mark_test": W.MarkTest,
}
HOST_CODE = {418: ERR_WIRE_LENGTH, 419: ERR_WIRE_RANGE}


def _vectors() -> list[tuple[str, bytes, int]]:
    rows = []
    for line in (VECTORS / "wire.txt").read_text().splitlines():
        if line and not line.startswith("#"):
            name, hexdata, expect = line.split()
            rows.append((name, bytes.fromhex(hexdata), int(expect)))
    return rows


def test_the_vectors_are_what_the_generator_writes() -> None:
    gen = runpy.run_path(str(VECTORS / "wire_generate.py"))
    assert (VECTORS / "wire.txt").read_text() == gen["text"](), "run tests/vectors/wire_generate.py"


def test_every_record_has_vectors_both_good_and_bad() -> None:
    rows = _vectors()
    assert {n for n, _, e in rows if e == 0} == set(CLASSES)
    assert {e for _, _, e in rows} == {0, 418, 419}


@pytest.mark.parametrize(("name", "data", "expect"), _vectors())
def test_a_vector_unpacks_and_packs_back_or_is_refused_with_its_code(
    name: str, data: bytes, expect: int
) -> None:
    cls = CLASSES[name]
    if expect == 0:
        assert cls.unpack(data).pack() == data  # type: ignore[attr-defined]
    else:
        with pytest.raises(FsError) as e:
            cls.unpack(data)  # type: ignore[attr-defined]
        assert e.value.code == HOST_CODE[expect]


def test_the_values_are_the_documented_layouts() -> None:
    # against struct layouts written from docs/protocol.md, independent of the generated code
    r = W.RunSkill.unpack(bytes.fromhex("0105dc03e800"))
    assert (r.slot, r.goal_scale, r.time_scale, r.end, r.path_scale) == (1, 1.5, 1.0, 0, None)
    r = W.RunSkill.unpack(struct.pack(">BHHBH", 2, 1000, 1300, 1, 500))
    assert (r.slot, r.goal_scale, r.time_scale, r.end, r.path_scale) == (2, 1.0, 1.3, 1, 0.5)
    s = W.RunSequence(0, (W.RunStep(1, 1.0, 1.0, 8.0), W.RunStep(2, 1.5, 1.0, 9.0))).pack()
    assert s == bytes([0]) + struct.pack(">BHHIBHHI", 1, 1000, 1000, 8000, 2, 1500, 1000, 9000)
    e = struct.pack(">BIIHfB", 1, 1234, 0xDEADBEEF, 50, 8.25, 1)
    d = W.SlotDir.unpack(bytes([8]) + e + bytes(16 * 7))
    assert d.count == 8 and d.entries[0] == W.SlotEntry(1, 1234, 0xDEADBEEF, 50, 8.25, 1)
    assert W.StiffnessMax.unpack(struct.pack(">f", 3e4)).stiffness_max_Npm == 3e4
    assert W.FaultCauses.unpack(struct.pack(">II", 1, 2)) == W.FaultCauses(1, 2)
    st = W.FwuStatus.unpack(struct.pack(">IBBBBBBHIB", 0x010203, 1, 0, 1, 0, 6, 3, 707, 0x010300, 3))
    assert (st.running_version, st.on_test, st.path, st.last_refusal, st.phase) == (0x010203, 0, 6, 707, 3)
    nonce = bytes(range(16))
    assert W.MotionKey(nonce, 1, 7).pack() == nonce + bytes([1]) + struct.pack(">I", 7)
    assert W.TransferExit(0xCBF43926).pack() == bytes.fromhex("cbf43926")
    assert W.MarkTest.unpack(b"") == W.MarkTest() and W.MarkTest().pack() == b""  # no options


def test_a_byte_string_field_takes_its_length_only() -> None:
    for bad in (bytes(15), bytes(17)):
        with pytest.raises(FsError) as e:
            W.MotionKeyWrite(bad).pack()
        assert e.value.code == ERR_WIRE_RANGE


def test_pack_refuses_a_value_outside_its_range_with_669() -> None:
    for bad in (
        W.RunSkill(1, 65.536, 1.0, 0),
        W.RunSkill(1, -0.001, 1.0, 0),
        W.RunSkill(1, 1.0, 1.0, 3),
        W.EraseSlot(0),
        W.StiffnessMax(math.inf),
        W.Object(0, 1.0, 0.0, 1.0, 1.0, 0.0, math.nan),
        W.RunSequence(0, ()),
    ):
        with pytest.raises(FsError) as e:
            bad.pack()
        assert e.value.code == ERR_WIRE_RANGE


def test_the_scale_is_one_thousandth_and_its_counts_round() -> None:
    assert W.SCALE == 1e-3 and W.SCALE_STEPS == 1000
    assert W.to_steps(1.5) == 1500 and W.to_steps(0.0005) == 0 and W.from_steps(1300) == 1.3
    assert W.TICK_US == 1000 and W.TICK_S == 1e-3
