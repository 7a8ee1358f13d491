"""The CAN link to a forceskill device, built on python-can, cantools, can-isotp and udsoncan.

``bus``: python-can bus options (like python-can's own CLI) and opening with one-line errors.
``dbc``: the DBC (``forceskill.dbc``, ids for node 0; node n adds n), E2E counter + CRC-8.
``device``: cyclic frames: presence, heartbeat, commands, status and telemetry.
``uds``: udsoncan client over can-isotp (SecurityAccess key, data identifiers, transfers).
``logs``: demonstration readers for python-can log files (.blf .asc .log .trc .csv).

Errors are ``FsError`` with codes 630-649 (host side of the CAN link), listed here.
"""
from __future__ import annotations

ERR_LINK_BUS = 630          # interface, channel, port or bus options unusable
ERR_LINK_NO_RESPONSE = 631  # the node sent nothing within the timeout
ERR_LINK_NEGATIVE = 632     # the device refused a request (UDS negative response)
ERR_LINK_VERIFY = 633       # read-back after upload differs
ERR_LINK_LOG = 634          # a CAN log without the device's telemetry
ERR_LINK_TIMEOUT = 635      # the device stopped answering during an operation
ERR_LINK_STATE = 636        # the device is not in the state the operation needs (e.g. FAULT)
ERR_LINK_ARGS = 637         # a bad option value (slot, sequence, scale)
