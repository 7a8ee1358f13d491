"""Transmit priority as on a CAN controller (bench/can_priority/flood.py): with the bus flooded by
frames the device ignores, a queued UDS answer (0x680) or a telemetry backlog (0x190/0x1A0) never
holds back the device's status frames (period 10 ms) or its emergency frame (within 2 ms of the
tick that latched the fault), because the simulator's bus arbitrates all pending frames of all
nodes by identifier and the device queues by priority, keeping room for its safety frames."""

from __future__ import annotations

import importlib.util
import sys

from helpers.canbus import REPO, hil_sim_path


def _flood():
    spec = importlib.util.spec_from_file_location("flood", REPO / "bench" / "can_priority" / "flood.py")
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    sys.modules["flood"] = mod
    spec.loader.exec_module(mod)
    return mod


def test_safety_frames_keep_their_time_on_a_flooded_bus():
    flood = _flood()
    proc, port = flood.start_server(hil_sim_path())
    try:
        res = flood.measure(port, 1.5)
    finally:
        proc.terminate()
        proc.communicate(timeout=10)
    print("\n".join(res.lines()))
    for name in ("UDS", "telemetry"):
        t0, t1 = res.phases[name]
        assert t1 - t0 > 0.8, f"{name} flood too short: {res.lines()}"
        assert res.flood_load[name] > 0.6, res.lines()  # the flood owns the bus
        assert res.status_gap_ms[name] <= 11.0, res.lines()  # period 10 ms kept
    assert res.emcy_code == 500, res.lines()
    assert res.emcy_latency_ms <= 2.0, res.lines()
    # the UDS answer, lowest priority of all, waited for the flood to end
    _uds_t0, uds_t1 = res.phases["UDS"]
    assert res.uds_answer_t >= uds_t1 - 0.005, res.lines()
