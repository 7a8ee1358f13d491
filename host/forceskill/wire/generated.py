"""The values the device and the host share, and the codecs of the device's UDS payloads
(big-endian, float32 for reals, scaled fields as counts of SCALE; docs/protocol.md).

Generated from firmware/base/wire.toml by tools/gen_codes.py; do not edit.
"""

from __future__ import annotations

import math
import struct
from dataclasses import dataclass
from typing import ClassVar

from ..errors import ERR_WIRE_LENGTH, ERR_WIRE_RANGE, FsError

#: One step of every scaled field (goal, time and path scales, durations): value = count * SCALE.
SCALE = 0.001
SCALE_STEPS = 1000  # counts per unit, 1 / SCALE
#: skill slots of a device, numbered 1..SLOT_COUNT (UDS addresses, HostCommand.Slot)
SLOT_COUNT = 8
#: control tick period in microseconds (the device runs at 1 kHz)
TICK_US = 1000
TICK_S = 0.001  # TICK_US in seconds
TICK_HZ = 1000  # TICK_US as a rate, per second
#: steps of a RUN_SEQUENCE start at most
SEQUENCE_STEPS_MAX = 8
#: default |force command| limit force_max_N of each axis
FORCE_LIMIT_N = 50.0
#: default skill stiffness limit (DID 0x0140) of a dynamics-compensated drive
STIFFNESS_MAX_NPM = 500000.0
#: default skill stiffness limit of a carriage rendered by admittance
STIFFNESS_MAX_RENDERED_NPM = 30000.0
#: highest stiffness a skill may declare and DID 0x0140 may be set to
STIFFNESS_CEILING_NPM = 100000000.0
#: DID 0x0201: a download is in progress
TRANSFER_IN_PROGRESS = 0xFFFF
#: DID 0x0201: the last download was interrupted or its commit refused
TRANSFER_INTERRUPTED = 0xFFFE
#: DID 0x0201: no download since power-up
TRANSFER_NONE = 0xFFFD
#: firmware image target id: Cortex-M4F (qemu mps2-an386)
TARGET_CORTEX_M4F = 1
#: firmware image target id: Cortex-M3 (qemu mps2-an385)
TARGET_CORTEX_M3 = 2
#: firmware image target id: the host port (simulator)
TARGET_HOST = 3


def to_steps(value: float) -> int:
    """A scaled field's count for a value (rounded to the nearest step)."""
    return int(round(value * SCALE_STEPS))


def from_steps(count: int) -> float:
    """The value of a scaled field's count."""
    return count / SCALE_STEPS


def _in_range(record: str, name: str, ok: bool, value: object) -> None:
    if not ok:
        raise FsError(ERR_WIRE_RANGE, f'{record}.{name} outside its range: {value!r}')


_VERSIONS = struct.Struct('>BBBHB')


@dataclass(frozen=True)
class Versions:
    """DID_VERSIONS: protocol and format versions."""

    SIZE: ClassVar[int] = 6  # bytes of the fields always present
    proto_major: int
    proto_minor: int
    skill_format: int
    max_kernels: int
    slots: int

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('versions', 'proto_major', 0 <= self.proto_major <= 255, self.proto_major)
        _in_range('versions', 'proto_minor', 0 <= self.proto_minor <= 255, self.proto_minor)
        _in_range('versions', 'skill_format', 0 <= self.skill_format <= 255, self.skill_format)
        _in_range('versions', 'max_kernels', 0 <= self.max_kernels <= 65535, self.max_kernels)
        _in_range('versions', 'slots', 0 <= self.slots <= 255, self.slots)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _VERSIONS.pack(self.proto_major, self.proto_minor, self.skill_format, self.max_kernels, self.slots)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> Versions:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _VERSIONS.size
        if len(data) != n:
            raise FsError(ERR_WIRE_LENGTH, f'versions: {len(data)} bytes, not {n}')
        raw = _VERSIONS.unpack(data[:n])
        v = cls(raw[0], raw[1], raw[2], raw[3], raw[4])
        v.check()
        return v


_GAINS = struct.Struct('>fffff')


@dataclass(frozen=True)
class Gains:
    """DID_GAINS_X / DID_GAINS_Y: controller gains of one axis (validated by pfc_config_validate)."""

    SIZE: ClassVar[int] = 20  # bytes of the fields always present
    m_d_kg: float  # kg
    k_d_Nspm: float  # N s/m
    k_p_Npm: float  # N/m
    k_f: float
    k_i_per_s: float  # 1/s

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _GAINS.pack(self.m_d_kg, self.k_d_Nspm, self.k_p_Npm, self.k_f, self.k_i_per_s)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> Gains:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _GAINS.size
        if len(data) != n:
            raise FsError(ERR_WIRE_LENGTH, f'gains: {len(data)} bytes, not {n}')
        raw = _GAINS.unpack(data[:n])
        v = cls(raw[0], raw[1], raw[2], raw[3], raw[4])
        v.check()
        return v


_LIMITS = struct.Struct('>ffffff')


@dataclass(frozen=True)
class Limits:
    """DID_LIMITS_X / DID_LIMITS_Y: safety limits of one axis (validated by saf_config_validate)."""

    SIZE: ClassVar[int] = 24  # bytes of the fields always present
    force_max_N: float  # N
    slew_max_N: float  # N per tick
    pos_min_m: float  # m
    pos_max_m: float  # m
    vel_max_mps: float  # m/s
    contact_force_max_N: float  # N

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('limits', 'force_max_N', math.isfinite(self.force_max_N), self.force_max_N)
        _in_range('limits', 'slew_max_N', math.isfinite(self.slew_max_N), self.slew_max_N)
        _in_range('limits', 'pos_min_m', math.isfinite(self.pos_min_m), self.pos_min_m)
        _in_range('limits', 'pos_max_m', math.isfinite(self.pos_max_m), self.pos_max_m)
        _in_range('limits', 'vel_max_mps', math.isfinite(self.vel_max_mps), self.vel_max_mps)
        _in_range('limits', 'contact_force_max_N', math.isfinite(self.contact_force_max_N), self.contact_force_max_N)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _LIMITS.pack(self.force_max_N, self.slew_max_N, self.pos_min_m, self.pos_max_m, self.vel_max_mps, self.contact_force_max_N)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> Limits:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _LIMITS.size
        if len(data) != n:
            raise FsError(ERR_WIRE_LENGTH, f'limits: {len(data)} bytes, not {n}')
        raw = _LIMITS.unpack(data[:n])
        v = cls(raw[0], raw[1], raw[2], raw[3], raw[4], raw[5])
        v.check()
        return v


_COMM = struct.Struct('>BH')


@dataclass(frozen=True)
class Comm:
    """DID_COMM: telemetry period in TEACH/EXECUTE and host-silence timeout."""

    SIZE: ClassVar[int] = 3  # bytes of the fields always present
    telemetry_period_ms: int  # ms
    host_timeout_ms: int  # ms

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('comm', 'telemetry_period_ms', 1 <= self.telemetry_period_ms <= 255, self.telemetry_period_ms)
        _in_range('comm', 'host_timeout_ms', 0 <= self.host_timeout_ms <= 65535, self.host_timeout_ms)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _COMM.pack(self.telemetry_period_ms, self.host_timeout_ms)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> Comm:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _COMM.size
        if len(data) != n:
            raise FsError(ERR_WIRE_LENGTH, f'comm: {len(data)} bytes, not {n}')
        raw = _COMM.unpack(data[:n])
        v = cls(raw[0], raw[1])
        v.check()
        return v


_OBJECT = struct.Struct('>Bffffff')


@dataclass(frozen=True)
class Object:
    """DID_OBJECT: the object model of the execution reference."""

    SIZE: ClassVar[int] = 25  # bytes of the fields always present
    use_model: int
    m_v_kg: float  # kg
    d_v_Nspm: float  # N s/m
    k1_Npm: float  # N/m
    k2_Npm: float  # N/m
    layer_depth_m: float  # m
    surface_m: float  # m

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('object', 'use_model', 0 <= self.use_model <= 1, self.use_model)
        _in_range('object', 'm_v_kg', math.isfinite(self.m_v_kg) and self.m_v_kg >= 0.0, self.m_v_kg)
        _in_range('object', 'd_v_Nspm', math.isfinite(self.d_v_Nspm) and self.d_v_Nspm >= 0.0, self.d_v_Nspm)
        _in_range('object', 'k1_Npm', math.isfinite(self.k1_Npm) and self.k1_Npm > 0.0, self.k1_Npm)
        _in_range('object', 'k2_Npm', math.isfinite(self.k2_Npm) and self.k2_Npm > 0.0, self.k2_Npm)
        _in_range('object', 'layer_depth_m', math.isfinite(self.layer_depth_m) and self.layer_depth_m >= 0.0, self.layer_depth_m)
        _in_range('object', 'surface_m', math.isfinite(self.surface_m), self.surface_m)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _OBJECT.pack(self.use_model, self.m_v_kg, self.d_v_Nspm, self.k1_Npm, self.k2_Npm, self.layer_depth_m, self.surface_m)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> Object:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _OBJECT.size
        if len(data) != n:
            raise FsError(ERR_WIRE_LENGTH, f'object: {len(data)} bytes, not {n}')
        raw = _OBJECT.unpack(data[:n])
        v = cls(raw[0], raw[1], raw[2], raw[3], raw[4], raw[5], raw[6])
        v.check()
        return v


_BAND = struct.Struct('>IIIHIBH')


@dataclass(frozen=True)
class Band:
    """DID_BAND: the demonstrated band's check of the running or last execution."""

    SIZE: ClassVar[int] = 21  # bytes of the fields always present
    checked_ms: int  # ms
    outside_ms: int  # ms
    longest_ms: int  # ms
    max_widths: float
    first_ms: int  # ms
    outside: int
    stop_ms: int  # ms

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('band', 'checked_ms', 0 <= self.checked_ms <= 4294967295, self.checked_ms)
        _in_range('band', 'outside_ms', 0 <= self.outside_ms <= 4294967295, self.outside_ms)
        _in_range('band', 'longest_ms', 0 <= self.longest_ms <= 4294967295, self.longest_ms)
        _in_range('band', 'max_widths', 0 <= to_steps(self.max_widths) <= 65535, self.max_widths)
        _in_range('band', 'first_ms', 0 <= self.first_ms <= 4294967295, self.first_ms)
        _in_range('band', 'outside', 0 <= self.outside <= 1, self.outside)
        _in_range('band', 'stop_ms', 0 <= self.stop_ms <= 65535, self.stop_ms)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _BAND.pack(self.checked_ms, self.outside_ms, self.longest_ms, to_steps(self.max_widths), self.first_ms, self.outside, self.stop_ms)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> Band:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _BAND.size
        if len(data) != n:
            raise FsError(ERR_WIRE_LENGTH, f'band: {len(data)} bytes, not {n}')
        raw = _BAND.unpack(data[:n])
        v = cls(raw[0], raw[1], raw[2], from_steps(raw[3]), raw[4], raw[5], raw[6])
        v.check()
        return v


_STIFFNESS_MAX = struct.Struct('>f')


@dataclass(frozen=True)
class StiffnessMax:
    """DID_STIFFNESS_MAX: the highest nominal skill stiffness the device accepts."""

    SIZE: ClassVar[int] = 4  # bytes of the fields always present
    stiffness_max_Npm: float  # N/m

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('stiffness_max', 'stiffness_max_Npm', math.isfinite(self.stiffness_max_Npm) and self.stiffness_max_Npm > 0.0 and self.stiffness_max_Npm <= 100000000.0, self.stiffness_max_Npm)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _STIFFNESS_MAX.pack(self.stiffness_max_Npm)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> StiffnessMax:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _STIFFNESS_MAX.size
        if len(data) != n:
            raise FsError(ERR_WIRE_LENGTH, f'stiffness_max: {len(data)} bytes, not {n}')
        raw = _STIFFNESS_MAX.unpack(data[:n])
        v = cls(raw[0])
        v.check()
        return v


_SLOT_ENTRY = struct.Struct('>BIIHfB')


@dataclass(frozen=True)
class SlotEntry:
    """one slot of DID_SLOT_DIR (all zero for an empty slot)."""

    SIZE: ClassVar[int] = 16  # bytes of the fields always present
    valid: int
    length: int  # bytes
    crc32: int
    n_kernels: int
    duration_s: float  # s
    end: int

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('slot_entry', 'valid', 0 <= self.valid <= 1, self.valid)
        _in_range('slot_entry', 'length', 0 <= self.length <= 4294967295, self.length)
        _in_range('slot_entry', 'crc32', 0 <= self.crc32 <= 4294967295, self.crc32)
        _in_range('slot_entry', 'n_kernels', 0 <= self.n_kernels <= 65535, self.n_kernels)
        _in_range('slot_entry', 'end', 0 <= self.end <= 255, self.end)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _SLOT_ENTRY.pack(self.valid, self.length, self.crc32, self.n_kernels, self.duration_s, self.end)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> SlotEntry:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _SLOT_ENTRY.size
        if len(data) != n:
            raise FsError(ERR_WIRE_LENGTH, f'slot_entry: {len(data)} bytes, not {n}')
        raw = _SLOT_ENTRY.unpack(data[:n])
        v = cls(raw[0], raw[1], raw[2], raw[3], raw[4], raw[5])
        v.check()
        return v


_SLOT_DIR = struct.Struct('>B')


@dataclass(frozen=True)
class SlotDir:
    """DID_SLOT_DIR: the slot directory."""

    SIZE: ClassVar[int] = 1  # bytes of the fields always present
    count: int
    entries: tuple[SlotEntry, ...]

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('slot_dir', 'count', 0 <= self.count <= 8, self.count)
        _in_range('slot_dir', 'n_entries', 0 <= len(self.entries) <= 8, len(self.entries))
        for e in self.entries:
            e.check()

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _SLOT_DIR.pack(self.count)
        out += b''.join(e.pack() for e in self.entries)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> SlotDir:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _SLOT_DIR.size
        m = SlotEntry.SIZE
        count = (len(data) - n) // m
        if len(data) < n or (len(data) - n) % m or not 0 <= count <= 8:
            raise FsError(ERR_WIRE_LENGTH, f'slot_dir: {len(data)} bytes is not {n} + {m} x 0..8')
        raw = _SLOT_DIR.unpack(data[:n])
        v = cls(raw[0], tuple(SlotEntry.unpack(data[n + m * i : n + m * (i + 1)]) for i in range(count)))
        v.check()
        return v


_LAST_TRANSFER = struct.Struct('>H')


@dataclass(frozen=True)
class LastTransfer:
    """DID_LAST_TRANSFER: status of the last download (0 ok, a code, TRANSFER_*)."""

    SIZE: ClassVar[int] = 2  # bytes of the fields always present
    status: int

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('last_transfer', 'status', 0 <= self.status <= 65535, self.status)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _LAST_TRANSFER.pack(self.status)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> LastTransfer:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _LAST_TRANSFER.size
        if len(data) != n:
            raise FsError(ERR_WIRE_LENGTH, f'last_transfer: {len(data)} bytes, not {n}')
        raw = _LAST_TRANSFER.unpack(data[:n])
        v = cls(raw[0])
        v.check()
        return v


_DEVICE_STATE = struct.Struct('>BHBBI')


@dataclass(frozen=True)
class DeviceState:
    """DID_DEVICE_STATE: state, latched fault, active slot, sequence step, tick."""

    SIZE: ClassVar[int] = 9  # bytes of the fields always present
    state: int
    fault: int
    slot: int
    step: int
    tick: int

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('device_state', 'state', 0 <= self.state <= 255, self.state)
        _in_range('device_state', 'fault', 0 <= self.fault <= 65535, self.fault)
        _in_range('device_state', 'slot', 0 <= self.slot <= 255, self.slot)
        _in_range('device_state', 'step', 0 <= self.step <= 255, self.step)
        _in_range('device_state', 'tick', 0 <= self.tick <= 4294967295, self.tick)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _DEVICE_STATE.pack(self.state, self.fault, self.slot, self.step, self.tick)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> DeviceState:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _DEVICE_STATE.size
        if len(data) != n:
            raise FsError(ERR_WIRE_LENGTH, f'device_state: {len(data)} bytes, not {n}')
        raw = _DEVICE_STATE.unpack(data[:n])
        v = cls(raw[0], raw[1], raw[2], raw[3], raw[4])
        v.check()
        return v


_CONTACT_WAIT = struct.Struct('>IHH')


@dataclass(frozen=True)
class ContactWait:
    """DID_CONTACT_WAIT: the contact wait of the running or last execution."""

    SIZE: ClassVar[int] = 8  # bytes of the fields always present
    hold_ms: int  # ms
    losses: int
    rate: float

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('contact_wait', 'hold_ms', 0 <= self.hold_ms <= 4294967295, self.hold_ms)
        _in_range('contact_wait', 'losses', 0 <= self.losses <= 65535, self.losses)
        _in_range('contact_wait', 'rate', 0 <= to_steps(self.rate) <= 1000, self.rate)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _CONTACT_WAIT.pack(self.hold_ms, self.losses, to_steps(self.rate))
        return out

    @classmethod
    def unpack(cls, data: bytes) -> ContactWait:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _CONTACT_WAIT.size
        if len(data) != n:
            raise FsError(ERR_WIRE_LENGTH, f'contact_wait: {len(data)} bytes, not {n}')
        raw = _CONTACT_WAIT.unpack(data[:n])
        v = cls(raw[0], raw[1], from_steps(raw[2]))
        v.check()
        return v


_FAULT_CAUSES = struct.Struct('>II')


@dataclass(frozen=True)
class FaultCauses:
    """DID_FAULT_CAUSES: latched faults and the causes present at the last tick (bit n: fault 500 + n)."""

    SIZE: ClassVar[int] = 8  # bytes of the fields always present
    latched_mask: int
    present_mask: int

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('fault_causes', 'latched_mask', 0 <= self.latched_mask <= 4294967295, self.latched_mask)
        _in_range('fault_causes', 'present_mask', 0 <= self.present_mask <= 4294967295, self.present_mask)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _FAULT_CAUSES.pack(self.latched_mask, self.present_mask)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> FaultCauses:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _FAULT_CAUSES.size
        if len(data) != n:
            raise FsError(ERR_WIRE_LENGTH, f'fault_causes: {len(data)} bytes, not {n}')
        raw = _FAULT_CAUSES.unpack(data[:n])
        v = cls(raw[0], raw[1])
        v.check()
        return v


_RUN_SKILL = struct.Struct('>BHHB')


@dataclass(frozen=True)
class RunSkill:
    """RID_RUN_SKILL start: one skill (end 0 the skill's own, 1 hold, 2 release)."""

    SIZE: ClassVar[int] = 6  # bytes of the fields always present
    slot: int
    goal_scale: float
    time_scale: float
    end: int
    path_scale: float | None = None

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('run_skill', 'slot', 0 <= self.slot <= 255, self.slot)
        _in_range('run_skill', 'goal_scale', 0 <= to_steps(self.goal_scale) <= 65535, self.goal_scale)
        _in_range('run_skill', 'time_scale', 0 <= to_steps(self.time_scale) <= 65535, self.time_scale)
        _in_range('run_skill', 'end', 0 <= self.end <= 2, self.end)
        if self.path_scale is not None:
            _in_range('run_skill', 'path_scale', 0 <= to_steps(self.path_scale) <= 65535, self.path_scale)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _RUN_SKILL.pack(self.slot, to_steps(self.goal_scale), to_steps(self.time_scale), self.end)
        if self.path_scale is not None:
            out += struct.pack('>H', to_steps(self.path_scale))
        return out

    @classmethod
    def unpack(cls, data: bytes) -> RunSkill:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _RUN_SKILL.size
        if len(data) not in (n, n + 2):
            raise FsError(ERR_WIRE_LENGTH, f'run_skill: {len(data)} bytes, not {n} or {n + 2}')
        raw = _RUN_SKILL.unpack(data[:n])
        v = cls(raw[0], from_steps(raw[1]), from_steps(raw[2]), raw[3], from_steps(struct.unpack_from('>H', data, n)[0]) if len(data) > n else None)
        v.check()
        return v


_RUN_SKILL_BAND = struct.Struct('>BHHBHH')


@dataclass(frozen=True)
class RunSkillBand:
    """RID_RUN_SKILL start with a band stop time: run_skill's fields with the path scale, then the ms outside the demonstrated band (consecutive) that stop the run with FLT_BAND (0: report only; the device tells the starts by their length)."""

    SIZE: ClassVar[int] = 10  # bytes of the fields always present
    slot: int
    goal_scale: float
    time_scale: float
    end: int
    path_scale: float
    band_stop_ms: int  # ms

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('run_skill_band', 'slot', 0 <= self.slot <= 255, self.slot)
        _in_range('run_skill_band', 'goal_scale', 0 <= to_steps(self.goal_scale) <= 65535, self.goal_scale)
        _in_range('run_skill_band', 'time_scale', 0 <= to_steps(self.time_scale) <= 65535, self.time_scale)
        _in_range('run_skill_band', 'end', 0 <= self.end <= 2, self.end)
        _in_range('run_skill_band', 'path_scale', 0 <= to_steps(self.path_scale) <= 65535, self.path_scale)
        _in_range('run_skill_band', 'band_stop_ms', 0 <= self.band_stop_ms <= 65535, self.band_stop_ms)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _RUN_SKILL_BAND.pack(self.slot, to_steps(self.goal_scale), to_steps(self.time_scale), self.end, to_steps(self.path_scale), self.band_stop_ms)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> RunSkillBand:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _RUN_SKILL_BAND.size
        if len(data) != n:
            raise FsError(ERR_WIRE_LENGTH, f'run_skill_band: {len(data)} bytes, not {n}')
        raw = _RUN_SKILL_BAND.unpack(data[:n])
        v = cls(raw[0], from_steps(raw[1]), from_steps(raw[2]), raw[3], from_steps(raw[4]), raw[5])
        v.check()
        return v


_RUN_PERIODIC = struct.Struct('>BHHBHHH')


@dataclass(frozen=True)
class RunPeriodic:
    """RID_RUN_SKILL start of a periodic skill: run_skill's fields with the path scale, then the periods to run (0: until stopped) and the stroke's amplitude scale, optionally the band stop time (the device tells the two starts by their length)."""

    SIZE: ClassVar[int] = 12  # bytes of the fields always present
    slot: int
    goal_scale: float
    time_scale: float
    end: int
    path_scale: float
    cycles: int
    amplitude_scale: float
    band_stop_ms: int | None = None  # ms

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('run_periodic', 'slot', 0 <= self.slot <= 255, self.slot)
        _in_range('run_periodic', 'goal_scale', 0 <= to_steps(self.goal_scale) <= 65535, self.goal_scale)
        _in_range('run_periodic', 'time_scale', 0 <= to_steps(self.time_scale) <= 65535, self.time_scale)
        _in_range('run_periodic', 'end', 0 <= self.end <= 2, self.end)
        _in_range('run_periodic', 'path_scale', 0 <= to_steps(self.path_scale) <= 65535, self.path_scale)
        _in_range('run_periodic', 'cycles', 0 <= self.cycles <= 65535, self.cycles)
        _in_range('run_periodic', 'amplitude_scale', 0 <= to_steps(self.amplitude_scale) <= 65535, self.amplitude_scale)
        if self.band_stop_ms is not None:
            _in_range('run_periodic', 'band_stop_ms', 0 <= self.band_stop_ms <= 65535, self.band_stop_ms)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _RUN_PERIODIC.pack(self.slot, to_steps(self.goal_scale), to_steps(self.time_scale), self.end, to_steps(self.path_scale), self.cycles, to_steps(self.amplitude_scale))
        if self.band_stop_ms is not None:
            out += struct.pack('>H', self.band_stop_ms)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> RunPeriodic:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _RUN_PERIODIC.size
        if len(data) not in (n, n + 2):
            raise FsError(ERR_WIRE_LENGTH, f'run_periodic: {len(data)} bytes, not {n} or {n + 2}')
        raw = _RUN_PERIODIC.unpack(data[:n])
        v = cls(raw[0], from_steps(raw[1]), from_steps(raw[2]), raw[3], from_steps(raw[4]), raw[5], from_steps(raw[6]), struct.unpack_from('>H', data, n)[0] if len(data) > n else None)
        v.check()
        return v


_RUN_STEP = struct.Struct('>BHHI')


@dataclass(frozen=True)
class RunStep:
    """one step of a RUN_SEQUENCE start (duration 0: the skill's T times its time scale)."""

    SIZE: ClassVar[int] = 9  # bytes of the fields always present
    slot: int
    goal_scale: float
    time_scale: float
    duration_s: float  # s

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('run_step', 'slot', 0 <= self.slot <= 255, self.slot)
        _in_range('run_step', 'goal_scale', 0 <= to_steps(self.goal_scale) <= 65535, self.goal_scale)
        _in_range('run_step', 'time_scale', 0 <= to_steps(self.time_scale) <= 65535, self.time_scale)
        _in_range('run_step', 'duration_s', 0 <= to_steps(self.duration_s) <= 4294967295, self.duration_s)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _RUN_STEP.pack(self.slot, to_steps(self.goal_scale), to_steps(self.time_scale), to_steps(self.duration_s))
        return out

    @classmethod
    def unpack(cls, data: bytes) -> RunStep:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _RUN_STEP.size
        if len(data) != n:
            raise FsError(ERR_WIRE_LENGTH, f'run_step: {len(data)} bytes, not {n}')
        raw = _RUN_STEP.unpack(data[:n])
        v = cls(raw[0], from_steps(raw[1]), from_steps(raw[2]), from_steps(raw[3]))
        v.check()
        return v


_RUN_SEQUENCE = struct.Struct('>B')


@dataclass(frozen=True)
class RunSequence:
    """RID_RUN_SEQUENCE start: the end policy, then 1..SEQUENCE_STEPS_MAX steps."""

    SIZE: ClassVar[int] = 1  # bytes of the fields always present
    end: int
    steps: tuple[RunStep, ...]

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('run_sequence', 'end', 0 <= self.end <= 2, self.end)
        _in_range('run_sequence', 'n_steps', 1 <= len(self.steps) <= 8, len(self.steps))
        for e in self.steps:
            e.check()

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _RUN_SEQUENCE.pack(self.end)
        out += b''.join(e.pack() for e in self.steps)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> RunSequence:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _RUN_SEQUENCE.size
        m = RunStep.SIZE
        count = (len(data) - n) // m
        if len(data) < n or (len(data) - n) % m or not 1 <= count <= 8:
            raise FsError(ERR_WIRE_LENGTH, f'run_sequence: {len(data)} bytes is not {n} + {m} x 1..8')
        raw = _RUN_SEQUENCE.unpack(data[:n])
        v = cls(raw[0], tuple(RunStep.unpack(data[n + m * i : n + m * (i + 1)]) for i in range(count)))
        v.check()
        return v


_RUN_RESULTS = struct.Struct('>BBBH')


@dataclass(frozen=True)
class RunResults:
    """RID_RUN_SKILL / RID_RUN_SEQUENCE results."""

    SIZE: ClassVar[int] = 5  # bytes of the fields always present
    state: int
    step: int
    done: int
    fault: int

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('run_results', 'state', 0 <= self.state <= 255, self.state)
        _in_range('run_results', 'step', 0 <= self.step <= 255, self.step)
        _in_range('run_results', 'done', 0 <= self.done <= 1, self.done)
        _in_range('run_results', 'fault', 0 <= self.fault <= 65535, self.fault)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _RUN_RESULTS.pack(self.state, self.step, self.done, self.fault)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> RunResults:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _RUN_RESULTS.size
        if len(data) != n:
            raise FsError(ERR_WIRE_LENGTH, f'run_results: {len(data)} bytes, not {n}')
        raw = _RUN_RESULTS.unpack(data[:n])
        v = cls(raw[0], raw[1], raw[2], raw[3])
        v.check()
        return v


_SELF_TEST = struct.Struct('>BH')


@dataclass(frozen=True)
class SelfTest:
    """RID_SELF_TEST results: 0 pass / 1 fail, the first failing check's code."""

    SIZE: ClassVar[int] = 3  # bytes of the fields always present
    status: int
    code: int

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('self_test', 'status', 0 <= self.status <= 1, self.status)
        _in_range('self_test', 'code', 0 <= self.code <= 65535, self.code)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _SELF_TEST.pack(self.status, self.code)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> SelfTest:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _SELF_TEST.size
        if len(data) != n:
            raise FsError(ERR_WIRE_LENGTH, f'self_test: {len(data)} bytes, not {n}')
        raw = _SELF_TEST.unpack(data[:n])
        v = cls(raw[0], raw[1])
        v.check()
        return v


_ERASE_SLOT = struct.Struct('>B')


@dataclass(frozen=True)
class EraseSlot:
    """RID_ERASE_SLOT start."""

    SIZE: ClassVar[int] = 1  # bytes of the fields always present
    slot: int

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('erase_slot', 'slot', 1 <= self.slot <= 8, self.slot)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _ERASE_SLOT.pack(self.slot)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> EraseSlot:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _ERASE_SLOT.size
        if len(data) != n:
            raise FsError(ERR_WIRE_LENGTH, f'erase_slot: {len(data)} bytes, not {n}')
        raw = _ERASE_SLOT.unpack(data[:n])
        v = cls(raw[0])
        v.check()
        return v


_MOTION_KEY = struct.Struct('>16sBI')


@dataclass(frozen=True)
class MotionKey:
    """DID_MOTION_KEY read: the device nonce of the motion key in use (zeros before any), whether a key is established, and the key's confirmation (the first 4 bytes of AES-CMAC(key, SECOC_CONFIRM_LABEL) big-endian, 0 without a key): a host whose own key gives another value re-establishes the session."""

    SIZE: ClassVar[int] = 21  # bytes of the fields always present
    nonce: bytes
    keyed: int
    confirm: int

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('motion_key', 'nonce', isinstance(self.nonce, bytes) and len(self.nonce) == 16, self.nonce)
        _in_range('motion_key', 'keyed', 0 <= self.keyed <= 1, self.keyed)
        _in_range('motion_key', 'confirm', 0 <= self.confirm <= 4294967295, self.confirm)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _MOTION_KEY.pack(self.nonce, self.keyed, self.confirm)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> MotionKey:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _MOTION_KEY.size
        if len(data) != n:
            raise FsError(ERR_WIRE_LENGTH, f'motion_key: {len(data)} bytes, not {n}')
        raw = _MOTION_KEY.unpack(data[:n])
        v = cls(raw[0], raw[1], raw[2])
        v.check()
        return v


_MOTION_KEY_WRITE = struct.Struct('>16s')


@dataclass(frozen=True)
class MotionKeyWrite:
    """DID_MOTION_KEY write: the host nonce of a new host session."""

    SIZE: ClassVar[int] = 16  # bytes of the fields always present
    nonce: bytes

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('motion_key_write', 'nonce', isinstance(self.nonce, bytes) and len(self.nonce) == 16, self.nonce)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _MOTION_KEY_WRITE.pack(self.nonce)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> MotionKeyWrite:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _MOTION_KEY_WRITE.size
        if len(data) != n:
            raise FsError(ERR_WIRE_LENGTH, f'motion_key_write: {len(data)} bytes, not {n}')
        raw = _MOTION_KEY_WRITE.unpack(data[:n])
        v = cls(raw[0])
        v.check()
        return v


_AUTH_STATS = struct.Struct('>IIIIIHBIII')


@dataclass(frozen=True)
class AuthStats:
    """DID_AUTH_STATS: authenticated host frames accepted and refused, the last refusal's code, the freshness values last accepted, UDS writes refused because the other tester owns the session."""

    SIZE: ClassVar[int] = 35  # bytes of the fields always present
    accepted: int
    wrong_mac: int
    replayed: int
    no_key: int
    discarded: int
    last_refusal: int
    keyed: int
    fv_command: int
    fv_heartbeat: int
    foreign_writes: int

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('auth_stats', 'accepted', 0 <= self.accepted <= 4294967295, self.accepted)
        _in_range('auth_stats', 'wrong_mac', 0 <= self.wrong_mac <= 4294967295, self.wrong_mac)
        _in_range('auth_stats', 'replayed', 0 <= self.replayed <= 4294967295, self.replayed)
        _in_range('auth_stats', 'no_key', 0 <= self.no_key <= 4294967295, self.no_key)
        _in_range('auth_stats', 'discarded', 0 <= self.discarded <= 4294967295, self.discarded)
        _in_range('auth_stats', 'last_refusal', 0 <= self.last_refusal <= 65535, self.last_refusal)
        _in_range('auth_stats', 'keyed', 0 <= self.keyed <= 1, self.keyed)
        _in_range('auth_stats', 'fv_command', 0 <= self.fv_command <= 4294967295, self.fv_command)
        _in_range('auth_stats', 'fv_heartbeat', 0 <= self.fv_heartbeat <= 4294967295, self.fv_heartbeat)
        _in_range('auth_stats', 'foreign_writes', 0 <= self.foreign_writes <= 4294967295, self.foreign_writes)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _AUTH_STATS.pack(self.accepted, self.wrong_mac, self.replayed, self.no_key, self.discarded, self.last_refusal, self.keyed, self.fv_command, self.fv_heartbeat, self.foreign_writes)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> AuthStats:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _AUTH_STATS.size
        if len(data) != n:
            raise FsError(ERR_WIRE_LENGTH, f'auth_stats: {len(data)} bytes, not {n}')
        raw = _AUTH_STATS.unpack(data[:n])
        v = cls(raw[0], raw[1], raw[2], raw[3], raw[4], raw[5], raw[6], raw[7], raw[8], raw[9])
        v.check()
        return v


_FWU_STATUS = struct.Struct('>IBBBBBBHIB')


@dataclass(frozen=True)
class FwuStatus:
    """DID_FWU_STATUS: the update status (fwu_status): the running image's version (0 when none runs), its slot, whether it runs on test (not confirmed yet), the active slot, the slot marked for a test boot, the boot path, the device's target id, the last refusal's code, the received image's version, the update phase."""

    SIZE: ClassVar[int] = 17  # bytes of the fields always present
    running_version: int
    running_slot: int
    on_test: int
    active_slot: int
    test_slot: int
    path: int
    target: int
    last_refusal: int
    received_version: int
    phase: int

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('fwu_status', 'running_version', 0 <= self.running_version <= 4294967295, self.running_version)
        _in_range('fwu_status', 'running_slot', 0 <= self.running_slot <= 255, self.running_slot)
        _in_range('fwu_status', 'on_test', 0 <= self.on_test <= 1, self.on_test)
        _in_range('fwu_status', 'active_slot', 0 <= self.active_slot <= 255, self.active_slot)
        _in_range('fwu_status', 'test_slot', 0 <= self.test_slot <= 255, self.test_slot)
        _in_range('fwu_status', 'path', 0 <= self.path <= 255, self.path)
        _in_range('fwu_status', 'target', 0 <= self.target <= 255, self.target)
        _in_range('fwu_status', 'last_refusal', 0 <= self.last_refusal <= 65535, self.last_refusal)
        _in_range('fwu_status', 'received_version', 0 <= self.received_version <= 4294967295, self.received_version)
        _in_range('fwu_status', 'phase', 0 <= self.phase <= 255, self.phase)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _FWU_STATUS.pack(self.running_version, self.running_slot, self.on_test, self.active_slot, self.test_slot, self.path, self.target, self.last_refusal, self.received_version, self.phase)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> FwuStatus:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _FWU_STATUS.size
        if len(data) != n:
            raise FsError(ERR_WIRE_LENGTH, f'fwu_status: {len(data)} bytes, not {n}')
        raw = _FWU_STATUS.unpack(data[:n])
        v = cls(raw[0], raw[1], raw[2], raw[3], raw[4], raw[5], raw[6], raw[7], raw[8], raw[9])
        v.check()
        return v


_TRANSFER_EXIT = struct.Struct('>I')


@dataclass(frozen=True)
class TransferExit:
    """RequestTransferExit's positive answer after a download: the CRC-32 of the received image (the host compares its own)."""

    SIZE: ClassVar[int] = 4  # bytes of the fields always present
    crc32: int

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        _in_range('transfer_exit', 'crc32', 0 <= self.crc32 <= 4294967295, self.crc32)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _TRANSFER_EXIT.pack(self.crc32)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> TransferExit:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _TRANSFER_EXIT.size
        if len(data) != n:
            raise FsError(ERR_WIRE_LENGTH, f'transfer_exit: {len(data)} bytes, not {n}')
        raw = _TRANSFER_EXIT.unpack(data[:n])
        v = cls(raw[0])
        v.check()
        return v


_MARK_TEST = struct.Struct('>')


@dataclass(frozen=True)
class MarkTest:
    """FWU_RID_MARK_TEST start: the options (bit 0: allow a downgrade, FWU_OPT_ALLOW_DOWNGRADE); absent: none."""

    SIZE: ClassVar[int] = 0  # bytes of the fields always present
    options: int | None = None

    def check(self) -> None:
        """FsError ERR_WIRE_RANGE if a field is outside its range."""
        if self.options is not None:
            _in_range('mark_test', 'options', 0 <= self.options <= 1, self.options)

    def pack(self) -> bytes:
        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""
        self.check()
        out = _MARK_TEST.pack()
        if self.options is not None:
            out += struct.pack('>B', self.options)
        return out

    @classmethod
    def unpack(cls, data: bytes) -> MarkTest:
        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""
        data = bytes(data)
        n = _MARK_TEST.size
        if len(data) not in (n, n + 1):
            raise FsError(ERR_WIRE_LENGTH, f'mark_test: {len(data)} bytes, not {n} or {n + 1}')
        raw = _MARK_TEST.unpack(data[:n])
        v = cls(struct.unpack_from('>B', data, n)[0] if len(data) > n else None)
        v.check()
        return v


__all__ = [
    'SCALE',
    'SCALE_STEPS',
    'SLOT_COUNT',
    'TICK_US',
    'TICK_S',
    'TICK_HZ',
    'SEQUENCE_STEPS_MAX',
    'FORCE_LIMIT_N',
    'STIFFNESS_MAX_NPM',
    'STIFFNESS_MAX_RENDERED_NPM',
    'STIFFNESS_CEILING_NPM',
    'TRANSFER_IN_PROGRESS',
    'TRANSFER_INTERRUPTED',
    'TRANSFER_NONE',
    'TARGET_CORTEX_M4F',
    'TARGET_CORTEX_M3',
    'TARGET_HOST',
    'from_steps',
    'to_steps',
    'Versions',
    'Gains',
    'Limits',
    'Comm',
    'Object',
    'Band',
    'StiffnessMax',
    'SlotEntry',
    'SlotDir',
    'LastTransfer',
    'DeviceState',
    'ContactWait',
    'FaultCauses',
    'RunSkill',
    'RunSkillBand',
    'RunPeriodic',
    'RunStep',
    'RunSequence',
    'RunResults',
    'SelfTest',
    'EraseSlot',
    'MotionKey',
    'MotionKeyWrite',
    'AuthStats',
    'FwuStatus',
    'TransferExit',
    'MarkTest',
]
