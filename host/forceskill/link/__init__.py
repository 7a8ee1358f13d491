"""The CAN link to a forceskill device, built on python-can, cantools, can-isotp and udsoncan.

``bus``: python-can bus options (like python-can's own CLI) and opening with one-line errors.
``device``: cyclic frames: presence, heartbeat, commands, status and telemetry.
``uds``: udsoncan client over can-isotp (SecurityAccess key, data identifiers, transfers).
The DBC and E2E protection (``forceskill.wire.dbc``), the telemetry pairing
(``forceskill.wire.telemetry``) and the UDS payload codecs are in ``forceskill.wire``, below the
readers: demonstrations from python-can log files are read by ``forceskill.readers.canlog``.

Errors are ``FsError`` with codes 630-649 (host side of the CAN link), listed here.
"""

from __future__ import annotations

# The link's error codes live with every other host code in forceskill.errors (63x).
from forceskill.errors import (  # noqa: F401
    ERR_LINK_ARGS,
    ERR_LINK_BUS,
    ERR_LINK_LOG,
    ERR_LINK_NEGATIVE,
    ERR_LINK_NO_RESPONSE,
    ERR_LINK_STATE,
    ERR_LINK_TIMEOUT,
    ERR_LINK_VERIFY,
)
