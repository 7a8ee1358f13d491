#!/usr/bin/env python3
"""Write tests/vectors/wire.txt: golden vectors of the UDS payload codecs (firmware/base/wire.toml).
The host's codecs (forceskill.wire) pack the good ones; the bad ones are written byte by byte.
Each line is `record hex expect`: expect 0 (unpacks, and packs back to the same bytes), 418 (a
length the record does not allow) or 419 (a field outside its range), the C codec's status; the
host raises FsError 668 / 669 for the same. tests/firmware/proto/test_wire.c reads the same file.

usage: tests/vectors/wire_generate.py [--check]   (--check: exit 1 if wire.txt is not what it writes)
"""

from __future__ import annotations

import struct
import sys
from pathlib import Path

from forceskill import wire as W

OUT = Path(__file__).with_name("wire.txt")
OK, LENGTH, RANGE = 0, 418, 419


def vectors() -> list[tuple[str, bytes, int]]:
    entry = W.SlotEntry(1, 1234, 0xDEADBEEF, 50, 8.25, 1)
    empty = W.SlotEntry(0, 0, 0, 0, 0.0, 0)
    step = W.RunStep(2, 1.5, 1.3, 9.0)
    good: list[tuple[str, object]] = [
        ("versions", W.Versions(1, 0, 3, 256, W.SLOT_COUNT)),
        ("gains", W.Gains(40.0, 400.0, 1170.0, 3.0, 27.0)),
        ("limits", W.Limits(50.0, 2.0, -0.5, 0.5, 1.0, 60.0)),
        ("comm", W.Comm(1, 100)),
        ("object", W.Object(1, 10.0, 0.0, 1000.0, 5000.0, 0.002, 0.001)),
        ("stiffness_max", W.StiffnessMax(5e5)),
        ("stiffness_max", W.StiffnessMax(W.STIFFNESS_CEILING_NPM)),
        ("slot_entry", entry),
        ("slot_dir", W.SlotDir(W.SLOT_COUNT, (entry,) + (empty,) * (W.SLOT_COUNT - 1))),
        ("last_transfer", W.LastTransfer(W.TRANSFER_INTERRUPTED)),
        ("device_state", W.DeviceState(3, 507, 1, 2, 123456)),
        ("fault_causes", W.FaultCauses(0x80, 0x81)),
        ("contact_wait", W.ContactWait(512, 2, 0.25)),
        ("run_skill", W.RunSkill(1, 1.5, 1.0, 0)),
        ("run_skill", W.RunSkill(8, 65.535, 0.001, 2, 0.5)),
        ("run_periodic", W.RunPeriodic(2, 1.0, 1.5, 1, 1.0, 20, 0.8)),
        ("run_periodic", W.RunPeriodic(3, 1.2, 1.0, 0, 1.0, 0, 1.0)),
        ("run_skill_band", W.RunSkillBand(2, 1.0, 1.0, 0, 1.0, 50)),
        ("run_periodic", W.RunPeriodic(3, 1.2, 1.0, 0, 1.0, 0, 1.0, 100)),
        ("band", W.Band(3000, 120, 80, 2.5, 1500, 1, 50)),
        ("run_step", step),
        ("run_sequence", W.RunSequence(1, (W.RunStep(1, 1.0, 1.0, 8.0), step))),
        ("run_sequence", W.RunSequence(0, (step,) * W.SEQUENCE_STEPS_MAX)),
        ("run_results", W.RunResults(3, 1, 0, 0)),
        ("self_test", W.SelfTest(1, 502)),
        ("erase_slot", W.EraseSlot(W.SLOT_COUNT)),
        ("motion_key", W.MotionKey(bytes.fromhex("00112233445566778899aabbccddeeff"), 1, 0x5A5AA5A5)),
        ("motion_key_write", W.MotionKeyWrite(bytes(range(1, 17)))),
        ("auth_stats", W.AuthStats(1000, 64, 3, 2, 1, 558, 0, 300, 4096, 7)),
        ("fwu_status", W.FwuStatus(0x00010203, 1, 1, 0, 1, 2, W.TARGET_CORTEX_M4F, 707, 0x00010300, 2)),
        ("transfer_exit", W.TransferExit(0xCBF43926)),
        ("mark_test", W.MarkTest(1)),
        ("mark_test", W.MarkTest(0)),
    ]
    out = [(name, rec.pack(), OK) for name, rec in good]  # type: ignore[attr-defined]
    f32 = struct.Struct(">f").pack
    out += [
        ("gains", bytes(19), LENGTH),
        ("run_skill", bytes([1, 3, 0xE8, 3, 0xE8]), LENGTH),
        ("run_skill", bytes([1, 3, 0xE8, 3, 0xE8, 0, 3]), LENGTH),
        ("run_skill", bytes([1, 3, 0xE8, 3, 0xE8, 3]), RANGE),
        ("run_skill_band", bytes([1, 3, 0xE8, 3, 0xE8, 0, 3, 0xE8, 0]), LENGTH),
        ("run_skill_band", bytes([1, 3, 0xE8, 3, 0xE8, 3, 3, 0xE8, 0, 50]), RANGE),
        ("band", bytes(20), LENGTH),
        ("band", bytes(18) + bytes([2, 0, 0]), RANGE),
        ("run_periodic", bytes([1, 3, 0xE8, 3, 0xE8, 0, 3, 0xE8, 0, 20, 3]), LENGTH),
        ("run_periodic", bytes([1, 3, 0xE8, 3, 0xE8, 3, 3, 0xE8, 0, 20, 3, 0xE8]), RANGE),
        ("run_sequence", bytes([0]), LENGTH),
        ("run_sequence", bytes(11), LENGTH),
        ("run_sequence", bytes(1 + 9 * (W.SEQUENCE_STEPS_MAX + 1)), LENGTH),
        ("run_sequence", bytes([3]) + bytes(9), RANGE),
        ("erase_slot", bytes([0]), RANGE),
        ("erase_slot", bytes([W.SLOT_COUNT + 1]), RANGE),
        ("erase_slot", bytes(2), LENGTH),
        ("stiffness_max", f32(2e8), RANGE),
        ("stiffness_max", f32(0.0), RANGE),
        ("stiffness_max", f32(float("nan")), RANGE),
        ("object", bytes([2]) + f32(10.0) + f32(0.0) + f32(1.0) + f32(1.0) + f32(0.0) + f32(0.0), RANGE),
        ("object", bytes([0]) + f32(10.0) + f32(0.0) + f32(0.0) + f32(1.0) + f32(0.0) + f32(0.0), RANGE),
        ("comm", bytes([0, 0, 100]), RANGE),
        ("limits", f32(float("inf")) + bytes(20), RANGE),
        ("slot_dir", bytes([W.SLOT_COUNT]) + bytes(15), LENGTH),
        ("motion_key", bytes(17), LENGTH),
        ("motion_key", bytes(16) + bytes([2]) + bytes(4), RANGE),
        ("motion_key_write", bytes(17), LENGTH),
        ("auth_stats", bytes(34), LENGTH),
        ("auth_stats", bytes(22) + bytes([2]) + bytes(12), RANGE),
        ("slot_dir", bytes([W.SLOT_COUNT]) + bytes(16 * (W.SLOT_COUNT + 1)), LENGTH),
        ("fwu_status", bytes(16), LENGTH),
        ("fwu_status", bytes(5) + bytes([2]) + bytes(11), RANGE),
        ("transfer_exit", bytes(3), LENGTH),
        ("mark_test", bytes([2]), RANGE),
        ("mark_test", bytes(2), LENGTH),
    ]
    return out


def text() -> str:
    lines = [
        "# golden vectors of the UDS payload codecs: record hex expect (0 ok, 418 length, 419 range)",
        "# written by tests/vectors/wire_generate.py; do not edit",
    ]
    lines += [f"{name} {data.hex()} {expect}" for name, data, expect in vectors()]
    return "\n".join(lines) + "\n"


def main(argv: list[str]) -> int:
    if "--check" in argv:
        same = OUT.is_file() and OUT.read_text() == text()
        if not same:
            print(f"{OUT} differs: run {Path(__file__).name}", file=sys.stderr)
        return 0 if same else 1
    OUT.write_text(text())
    print(f"wrote {OUT}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
