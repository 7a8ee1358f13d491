"""Shared plumbing of the CAN commands: bus options, connecting to a node, telemetry figures."""

from __future__ import annotations

import argparse
from collections.abc import Iterator
from contextlib import contextmanager

import numpy as np

from ..link import logs as _logs  # noqa: F401  (registers the CAN log readers for `fit`)
from ..link.bus import add_bus_args, describe, open_bus
from ..link.device import Device, Sample


def add_common(p: argparse.ArgumentParser) -> None:
    add_bus_args(p)


@contextmanager
def connect(args: argparse.Namespace) -> Iterator[Device]:
    """Open the bus, start listening, and wait for the node's status frame (presence)."""
    bus, cfg = open_bus(args)
    try:
        with Device(bus, node=args.node, channel=describe(cfg), timeout_s=args.timeout) as dev:
            dev.wait_present()
            yield dev
    finally:
        bus.shutdown()


def columns(samples: list[Sample]) -> dict[str, np.ndarray]:
    """Telemetry as HIL log columns (t from the device tick, 1 ms)."""
    if not samples:
        return {k: np.zeros(0) for k in ("t", "x", "y", "f_contact", "f_operator", "f_cmd", "f_hat")}
    tick = np.array([s.tick for s in samples], float)
    return {
        "t": (tick - tick[0]) * 1e-3,
        "x": np.array([s.x_m for s in samples]),
        "y": np.array([s.y_m for s in samples]),
        "f_contact": np.array([s.f_contact_N for s in samples]),
        "f_operator": np.array([s.f_operator_N for s in samples]),
        "f_cmd": np.array([s.f_cmd_N for s in samples]),
        "f_hat": np.array([s.f_ref_N for s in samples]),
    }


def tracking(cols: dict[str, np.ndarray]) -> dict[str, float]:
    """Force tracking figures (docs/hil.md): max/RMS |f_contact - f_hat| in % of max f_hat."""
    f, ref = cols["f_contact"], cols["f_hat"]
    peak = float(np.max(ref)) if ref.size else 0.0
    if peak <= 0.0:
        return {
            "max_force_N": float(np.max(f)) if f.size else 0.0,
            "max_ref_N": peak,
            "tracking_max_pct": float("nan"),
            "tracking_rms_pct": float("nan"),
        }
    e = f - ref
    return {
        "max_force_N": float(np.max(f)),
        "max_ref_N": peak,
        "tracking_max_pct": 100.0 * float(np.max(np.abs(e))) / peak,
        "tracking_rms_pct": 100.0 * float(np.sqrt(np.mean(e * e))) / peak,
    }
