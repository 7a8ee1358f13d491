"""The device's cyclic frames on a python-can bus: presence (judged by frames received, never by
a send succeeding), the host heartbeat, commands, and the status/telemetry/emergency streams,
all encoded and decoded through the DBC."""

from __future__ import annotations

import gc
import logging
import sys
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import can

from ..errors import FsError
from ..wire.dbc import AUTH_FRAMES, END_POLICIES, MODES, STATES, authenticate, check, load_db, protect
from ..wire.telemetry import TelemetryPairer
from . import ERR_LINK_NO_RESPONSE, ERR_LINK_TIMEOUT
from .bus import error_summary

# python-can logs a failed periodic send with its traceback; the commands report it as one line
logging.getLogger("can.bcm").setLevel(logging.CRITICAL)

HEARTBEAT_PERIOD_S = 0.010  # well inside the device's 100 ms silence timeout, at any speed factor
#: While the heartbeat runs, a thread waiting for the GIL asks for it after this long (Python's
#: default 5 ms): the heartbeat thread shares the interpreter with the receive thread, which decodes
#: 2 kHz of telemetry, and on a loaded machine each wait is stretched by the CPU share.
HEARTBEAT_GIL_SWITCH_S = 0.0005
#: Commands without effect after which command_until re-establishes the motion session (a frame
#: lost on the bus three times in a row is unlikely; a device that forgot the key is not).
RESYNC_AFTER = 3
#: The 1 kHz frames, decoded only while telemetry is collected (``start_telemetry``).
_TELEMETRY_FRAMES = frozenset({"TelemetryPosition", "TelemetryForce"})


@dataclass
class Status:
    state: str
    fault_code: int
    slot: int
    tick: int
    actuator_enabled: bool
    host_alive: bool
    sequence_step: int
    t_s: float


@dataclass
class Sample:
    tick: int
    x_m: float
    y_m: float
    f_contact_N: float
    f_operator_N: float
    f_cmd_N: float
    f_ref_N: float
    band_out: float = 0.0  # TelemetryPosition.BandOutside: outside the demonstrated band


@dataclass
class Telemetry:
    """Telemetry samples in arrival order and the device's states from its status frames over the
    same time (``states``: (tick, state) in arrival order); ticks are the device's 1 kHz tick,
    unwrapped from their 16 bits (a frame a little behind the latest one, as the two telemetry
    frames and the status pass each other on the bus, keeps its place)."""

    samples: list[Sample] = field(default_factory=list)
    states: list[tuple[int, str]] = field(default_factory=list)
    _latest: int = -1

    def unwrap(self, tick16: int) -> int:
        """The unwrapped tick nearest the latest one seen with these low 16 bits."""
        if self._latest < 0:
            self._latest = tick16
            return tick16
        full = self._latest + ((tick16 - self._latest + 32768) & 0xFFFF) - 32768
        self._latest = max(self._latest, full)
        return full


@dataclass
class MotionSession:
    """The host's side of an authenticated session: the motion key (never sent) and the last
    freshness value sent on each authenticated frame."""

    key: bytes
    fv: dict[str, int] = field(default_factory=lambda: dict.fromkeys(AUTH_FRAMES, 0))
    #: The freshness value of the last HostCommand whose send returned: every heartbeat built
    #: after it carries its low byte (CommandFreshness), so a command withheld from the bus is
    #: refused by the device once the next heartbeat is in.
    command_sent: int = 0


class Device(can.Listener):
    """One node on a bus. Use as a context manager: starts a Notifier (shared with ISO-TP)."""

    def __init__(
        self,
        bus: can.BusABC,
        node: int = 0,
        channel: str = "can0",
        timeout_s: float = 2.0,
        fd: bool = False,
        request_timeout_s: float | None = None,
    ):
        self.bus = bus
        #: Each UDS request's wait (``--request-timeout``) instead of the command's own (link.uds).
        self.request_timeout_s = request_timeout_s
        #: The bus was opened for CAN FD (``--fd``): UDS goes in 64-byte FD frames (link.uds).
        self.fd = fd
        self.node = node
        self.channel = channel
        self.timeout_s = timeout_s
        self.db = load_db(node)
        self._m = {m.name: m for m in self.db.messages}
        self._ids = {m.frame_id: m for m in self.db.messages}
        self.status: Status | None = None
        self.status_event = threading.Event()
        self.emergencies: list[tuple[float, dict[str, Any]]] = []
        self.telemetry: Telemetry | None = None
        self.frames_seen = 0
        self.bad_crc = 0
        self._pairs: TelemetryPairer[tuple[int, float, float, float]] = TelemetryPairer()
        self._lock = threading.Lock()
        self._counter = {"HostCommand": 0, "HostHeartbeat": 0}
        #: The motion key and freshness values (``link.uds.motion_session``); without one only a
        #: stop (HostCommand IDLE) is accepted by the device.
        self.session: MotionSession | None = None
        #: Re-establishes the session (set by ``link.uds.motion_session``): command_until calls it
        #: when a command had no effect (device reset, freshness lost after a bus-off).
        self.resync: Callable[[], None] | None = None
        self._hb_task: can.broadcastmanager.CyclicSendTaskABC | None = None
        self.heartbeat_sent: list[float] = []  # monotonic send times (diagnostics)
        self.telemetry_period_ms = 0
        self.notifier: can.Notifier | None = None
        self.on_status: Callable[[Status], None] | None = None
        self.link_error: BaseException | None = None
        self._saved_switch_s = sys.getswitchinterval()

    # -- lifecycle ------------------------------------------------------------------------------
    def __enter__(self) -> Device:
        self.notifier = can.Notifier(self.bus, [self], timeout=0.05)
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop_heartbeat()
        if self.notifier is not None:
            self.notifier.stop()

    # -- receiving ------------------------------------------------------------------------------
    def on_message_received(self, msg: can.Message) -> None:
        m = self._ids.get(msg.arbitration_id)
        if m is None or msg.is_extended_id or msg.is_error_frame:
            return
        if m.name in ("DeviceStatus", "Emergency") and not check(msg.arbitration_id, bytes(msg.data)):
            self.bad_crc += 1
            return
        if self.telemetry is None and m.name in _TELEMETRY_FRAMES:
            # nobody collects samples (record logs the raw frames): counted, not decoded, which is
            # most of this thread's work at 2 kHz and what a slow host (a TCG guest) cannot afford
            self.frames_seen += 1
            return
        try:
            sig: Any = m.decode(bytes(msg.data), decode_choices=False)
        except Exception:
            return
        self.frames_seen += 1
        if m.name == "DeviceStatus":
            st = Status(
                STATES.get(int(sig["State"]), str(sig["State"])),
                int(sig["FaultCode"]),
                int(sig["Slot"]),
                int(sig["Tick"]),
                bool(sig["ActuatorEnabled"]),
                bool(sig["HostAlive"]),
                int(sig["SequenceStep"]),
                float(msg.timestamp),
            )
            self.status = st
            tel = self.telemetry
            if tel is not None:
                with self._lock:
                    tel.states.append((tel.unwrap(st.tick & 0xFFFF), st.state))
            self.status_event.set()
            if self.on_status is not None:
                self.on_status(st)
        elif m.name == "Emergency":
            self.emergencies.append((float(msg.timestamp), dict(sig)))
        elif m.name == "TelemetryPosition":
            self._pairs.position(
                (int(sig["Tick"]), float(sig["PosX"]), float(sig["PosY"]), float(sig.get("BandOutside", 0)))
            )
        elif m.name == "TelemetryForce":
            pos = self._pairs.force()
            tel = self.telemetry
            if pos is not None and tel is not None:
                with self._lock:
                    tel.samples.append(
                        Sample(
                            tel.unwrap(pos[0]),
                            pos[1],
                            pos[2],
                            float(sig["ForceContact"]),
                            float(sig["ForceOperator"]),
                            float(sig["ForceCmd"]),
                            float(sig["ForceRef"]),
                            pos[3],
                        )
                    )

    def on_error(self, exc: Exception) -> None:
        """The Notifier's receive thread failed (connection lost): remember the first error for
        ``check_link`` (the commands report it as one line) and pace the thread's retries."""
        if self.link_error is None:
            self.link_error = exc
        time.sleep(0.05)

    def check_link(self) -> None:
        """FsError(635) if the bus failed under the receive thread."""
        e = self.link_error
        if e is not None:
            raise FsError(
                ERR_LINK_TIMEOUT, f"link to node {self.node} on {self.channel} lost: {error_summary(e)}"
            )

    # -- presence -------------------------------------------------------------------------------
    def wait_present(self) -> Status:
        """The next status frame of this node, or FsError 'no response from node N on CHANNEL'."""
        self.status_event.clear()
        if not self.status_event.wait(self.timeout_s):
            raise FsError(
                ERR_LINK_NO_RESPONSE,
                f"no response from node {self.node} on {self.channel} "
                f"(no status frame 0x{self._m['DeviceStatus'].frame_id:03X} within {self.timeout_s:g} s)",
            )
        assert self.status is not None
        return self.status

    def wait_state(self, states: set[str], timeout_s: float) -> Status:
        """Wait until the status reports one of states."""
        end = time.monotonic() + timeout_s
        while True:
            st = self.status
            if st is not None and st.state in states:
                return st
            remaining = end - time.monotonic()
            if remaining <= 0.0:
                break
            self.status_event.clear()
            w = min(self.timeout_s, remaining)
            if not self.status_event.wait(w) and w >= self.timeout_s:
                raise FsError(ERR_LINK_TIMEOUT, f"node {self.node} on {self.channel} stopped sending status")
        st = self.status
        raise FsError(
            ERR_LINK_TIMEOUT,
            f"node {self.node} did not reach {'/'.join(sorted(states))} "
            f"within {timeout_s:g} s (state {st.state if st else '?'})",
        )

    # -- sending --------------------------------------------------------------------------------
    def _frame(self, name: str, signals: dict[str, Any]) -> tuple[bytes, int]:
        """Encode a host frame (of a multiplexed frame only the signals of its mode) and protect it:
        freshness value, MAC and CRC with a session (a heartbeat also carries the last command's
        freshness), else the E2E counter and CRC only. Returns the frame and its freshness value
        (0 without a session)."""
        m = self._m[name]
        mode = signals.get("Mode")
        full = {s.name: 0 for s in m.signals if s.multiplexer_ids is None or mode in s.multiplexer_ids}
        full.update({k: v for k, v in signals.items() if k in full})
        with self._lock:
            s = self.session
            if s is not None:
                if name == "HostHeartbeat":
                    full["CommandFreshness"] = s.command_sent & 0xFF
                s.fv[name] += 1
                fv = s.fv[name]
                return authenticate(m.frame_id, m.encode(full, strict=True), fv, s.key), fv
            c = self._counter[name] = (self._counter[name] + 1) & 0x0F
        return protect(m.frame_id, m.encode(full, strict=True), c), 0

    def _send_safety(self, name: str, signals: dict[str, Any]) -> None:
        data, fv = self._frame(name, signals)
        self.bus.send(can.Message(arbitration_id=self._m[name].frame_id, data=data, is_extended_id=False))
        s = self.session
        if name == "HostCommand" and s is not None and fv > s.command_sent:
            with self._lock:
                s.command_sent = fv  # only now: a heartbeat never voids a command not yet sent

    def set_session(self, key: bytes) -> None:
        """Use a newly established motion key: both freshness values restart at 0 (as the
        device's do)."""
        with self._lock:
            self.session = MotionSession(key)

    def heartbeat(self) -> None:
        self._send_safety("HostHeartbeat", {"TelemetryPeriod": self.telemetry_period_ms})

    def _heartbeat_update(self, msg: can.Message) -> None:
        """Cyclic task callback: the next heartbeat's content (telemetry period, freshness, MAC,
        CRC)."""
        msg.data[:] = self._frame("HostHeartbeat", {"TelemetryPeriod": self.telemetry_period_ms})[0]
        self.heartbeat_sent.append(time.monotonic())
        if len(self.heartbeat_sent) > 100000:
            del self.heartbeat_sent[:50000]

    def start_heartbeat(self, telemetry_period_ms: int = 0) -> None:
        """Send the host heartbeat every HEARTBEAT_PERIOD_S with python-can's cyclic task
        (bus.send_periodic), each frame with its own counter and CRC (modifier_callback; with a
        per-frame change python-can runs its timer thread, deadline-based, for every interface).
        The first heartbeat is sent here, before the task's thread runs: a command sent next
        (TEACH, EXECUTE) reaches the device after it, so the telemetry period is in effect from
        the command's first tick (a thread slow to start would let it stream every tick first)."""
        self.telemetry_period_ms = telemetry_period_ms
        if self._hb_task is not None:
            return
        # the heartbeat must not wait behind the receive thread or a full garbage collection of
        # everything the process holds: short GIL switches, and the objects that exist now are
        # left out of collections until the heartbeat stops
        self._saved_switch_s = sys.getswitchinterval()
        sys.setswitchinterval(min(self._saved_switch_s, HEARTBEAT_GIL_SWITCH_S))
        gc.freeze()
        self.heartbeat()
        m = self._m["HostHeartbeat"]
        msg = can.Message(arbitration_id=m.frame_id, data=bytearray(8), is_extended_id=False)
        self._hb_task = self.bus.send_periodic(
            msg, HEARTBEAT_PERIOD_S, store_task=False, modifier_callback=self._heartbeat_update
        )
        if hasattr(self._hb_task, "on_error"):  # the thread-based task: a failed send ends it quietly
            self._hb_task.on_error = self._heartbeat_failed

    def _heartbeat_failed(self, exc: Exception) -> bool:
        """The heartbeat could not be sent (link lost): remember it for ``check_link``, stop."""
        if self.link_error is None:
            self.link_error = exc
        return False

    def stop_heartbeat(self) -> None:
        if self._hb_task is not None:
            self._hb_task.stop()
            self._hb_task = None
            sys.setswitchinterval(self._saved_switch_s)
            gc.unfreeze()

    def command(
        self, mode: str, slot: int = 0, goal_scale: float = 1.0, time_scale: float = 1.0, end: str = "skill"
    ) -> None:
        """One HostCommand (each valid frame is one command); EXECUTE is two frames, its
        RUN_OPTIONS (time scale, end policy) and then EXECUTE (slot, goal scale)."""
        if mode == "execute":
            self._send_safety(
                "HostCommand",
                {"Mode": MODES["run_options"], "TimeScale": time_scale, "EndPolicy": END_POLICIES[end]},
            )
        self._send_safety("HostCommand", {"Mode": MODES[mode], "Slot": slot, "GoalScale": goal_scale})

    def command_until(self, mode: str, states: set[str], timeout_s: float, retry_s: float = 0.2) -> Status:
        """Send a mode command and repeat it (each with a new freshness value) until the status
        shows one of states: a command frame lost or corrupted on the bus is simply sent again;
        after RESYNC_AFTER commands without effect the session is re-established once (``resync``:
        the device was reset, or lost more frames than the freshness window absorbs)."""
        end = time.monotonic() + timeout_s
        tries = 0
        while True:
            if tries == RESYNC_AFTER and self.resync is not None and mode != "idle":
                try:
                    self.resync()
                except FsError:
                    pass  # e.g. refused while the device still moves: the next try tells
            tries += 1
            self.command(mode)
            try:
                return self.wait_state(states, min(retry_s, max(0.0, end - time.monotonic())))
            except FsError:
                if time.monotonic() >= end:
                    raise

    def telemetry_samples(self, tel: Telemetry) -> list[Sample]:
        """A copy of the samples ``tel`` holds so far, taken while the receiving thread waits."""
        with self._lock:
            return list(tel.samples)

    def telemetry_states(self, tel: Telemetry) -> list[tuple[int, str]]:
        """A copy of the (tick, state) of the status frames received while ``tel`` collected."""
        with self._lock:
            return list(tel.states)

    def start_telemetry(self) -> Telemetry:
        self.telemetry = Telemetry()
        return self.telemetry
