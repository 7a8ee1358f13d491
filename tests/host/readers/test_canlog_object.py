"""The object's mass in a CAN log: the device's answer to ReadDataByIdentifier 0x0130 (its object
model) reassembled from its ISO-TP frames, classic or CAN FD; no answer, or a device that does
not use the model, names no mass."""

from __future__ import annotations

from forceskill import wire as W
from forceskill.readers.canlog import isotp_messages, object_mass


def answer(use_model: int, m_v: float) -> bytes:
    return bytes([0x62, 0x01, 0x30]) + W.Object(use_model, m_v, 50.0, 100.0, 180.0, 0.019, 0.001).pack()


def classic_frames(msg: bytes) -> list[bytes]:
    frames = [bytes([0x10 | (len(msg) >> 8), len(msg) & 0xFF]) + msg[:6]]
    rest, sn = msg[6:], 1
    while rest:
        frames.append(bytes([0x20 | (sn & 0x0F)]) + rest[:7])
        rest, sn = rest[7:], sn + 1
    return frames


def test_the_object_model_answer_is_found_classic_and_fd() -> None:
    msg = answer(1, 10.0)
    other = [bytes([0x02, 0x50, 0x02]), bytes([0x30, 0, 0])]  # a session answer and a flow control
    assert isotp_messages(other + classic_frames(msg))[-1] == msg
    assert object_mass(other + classic_frames(msg)) == 10.0
    assert object_mass([bytes([0x00, len(msg)]) + msg + bytes(64 - 2 - len(msg))]) == 10.0


def test_no_answer_or_no_model_is_no_mass() -> None:
    assert object_mass([]) is None
    assert object_mass(classic_frames(answer(0, 10.0))) is None
    assert object_mass(classic_frames(answer(1, 10.0))[:-1]) is None  # cut short
