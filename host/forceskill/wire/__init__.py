"""What the device and the host share on the wire, below ``readers`` and ``link``: the constants
and the UDS payload codecs generated from firmware/base/wire.toml (``generated``: one frozen
dataclass per payload with ``pack()``, ``unpack()`` and its range check, FsError 668/669), the
DBC and the E2E protection of the cyclic frames (``dbc``) and the pairing of the telemetry frames
(``telemetry``)."""

from __future__ import annotations

from .generated import *  # noqa: F403
from .generated import __all__  # noqa: F401
