"""Bus options exactly as python-can's own command line tools take them (``can.cli``:
``-i/--interface``, ``-c/--channel``, ``-b/--bitrate``, ``--bus-kwargs key=value ...``), with
python-can's configuration files and environment (``can.util.load_config``) supplying what is
not given. Opening the bus turns every failure into one ``FsError`` line naming the culprit."""

from __future__ import annotations

import argparse
import logging
import socket
from typing import Any

import can
import can.cli

from ..errors import FsError
from . import ERR_LINK_ARGS, ERR_LINK_BUS

DEFAULT_TIMEOUT_S = 2.0
#: The longest telemetry period --telemetry-period accepts: the gap a run's figures are measured
#: across (commands.run's MAX_TELEMETRY_GAP_MS).
MAX_TELEMETRY_PERIOD_MS = 100

# python-can's socketcand reader warns whenever a TCP read ends inside a frame (normal streaming),
# and logs a lost connection with its traceback: the commands report link failures as one line
logging.getLogger("can.interfaces.socketcand.socketcand").setLevel(logging.CRITICAL)


def error_summary(e: BaseException) -> str:
    """One line for a bus failure: the exception's first line without the traceback that some
    python-can interfaces put into the message itself."""
    first = (str(e).splitlines() or [""])[0].split("Traceback (most recent call last)")[0].strip()
    return first or type(e).__name__


def add_bus_args(parser: argparse.ArgumentParser) -> None:
    """python-can's bus options plus the device's node id and the response timeout."""
    can.cli.add_bus_arguments(parser)
    g = parser.add_argument_group("device")
    g.add_argument(
        "--node",
        type=int,
        default=0,
        metavar="N",
        help="device node id 0..15 (CAN ids = base + N; default 0)",
    )
    g.add_argument(
        "--timeout",
        type=float,
        default=DEFAULT_TIMEOUT_S,
        metavar="S",
        help=f"seconds to wait for the device before giving up ({DEFAULT_TIMEOUT_S:g})",
    )
    g.add_argument(
        "--request-timeout",
        type=float,
        default=None,
        metavar="S",
        help="seconds each UDS request waits for its answer (default: the command's own, 2-5 s, "
        "below the device's 5 s session timeout so that a lost request is sent again in time; "
        "longer for a host whose threads stall for seconds, e.g. a qemu guest without KVM)",
    )
    g.add_argument(
        "--telemetry-period",
        type=int,
        default=1,
        metavar="MS",
        help="telemetry period asked of the device in TEACH/EXECUTE by record and run, 1.."
        f"{MAX_TELEMETRY_PERIOD_MS} ms (default 1: every tick; more for a host that cannot "
        "follow 2,000 frames/s; run interpolates the ticks between, counting as lost only samples due)",
    )


def bus_config(ns: argparse.Namespace) -> dict[str, Any]:
    """The keyword arguments for can.Bus: command line over python-can's config files/env."""
    given: dict[str, Any] = {}
    for key in ("interface", "channel", "bitrate", "fd", "data_bitrate", "timing"):
        if getattr(ns, key, None) is not None:  # an option not given leaves python-can's value
            given[key] = getattr(ns, key)
    given.update(getattr(ns, "bus_kwargs", {}) or {})
    try:
        cfg = can.util.load_config(config=dict(given))
    except can.CanInterfaceNotImplementedError:
        if "interface" not in given and not _configured_interface():
            raise FsError(ERR_LINK_BUS, NO_INTERFACE) from None
        raise FsError(ERR_LINK_BUS, f"unknown CAN interface {_configured_interface()!r}") from None
    except Exception as e:  # load_config raises on an unusable config file
        raise FsError(ERR_LINK_BUS, f"CAN configuration unusable: {error_summary(e)}") from None
    cfg.update(given)
    if not cfg.get("interface"):
        raise FsError(ERR_LINK_BUS, NO_INTERFACE)
    return cfg


#: The refusal of a command that talks to a device when nothing names the CAN interface.
NO_INTERFACE = (
    "no CAN interface: set one in python-can's configuration (~/.canrc or $CAN_INTERFACE and "
    "$CAN_CHANNEL) or give -i/--interface NAME -c/--channel CH (e.g. -i socketcand -c can0 "
    "--bus-kwargs host=127.0.0.1 port=29536 for hil_sim serve)"
)


def _configured_interface() -> str | None:
    """The interface python-can's environment or configuration files name, if any."""
    try:
        found = can.util.load_environment_config().get("interface") or can.util.load_file_config().get(
            "interface"
        )
    except Exception:  # an unreadable file is reported by load_config's own error
        return None
    return str(found) if found else None


def describe(cfg: dict[str, Any]) -> str:
    """Short name of the bus for messages: 'can0' or 'can0 (socketcand 127.0.0.1:29536)'."""
    ch = cfg.get("channel")
    if cfg.get("interface") == "socketcand":
        return f"{ch} (socketcand {cfg.get('host')}:{cfg.get('port')})"
    return f"{ch} ({cfg.get('interface')})"


def _precheck_socketcand(cfg: dict[str, Any]) -> None:
    host = cfg.get("host")
    port = cfg.get("port")
    if host is None or port is None:
        raise FsError(ERR_LINK_BUS, "the socketcand interface needs --bus-kwargs host=ADDR port=PORT")
    try:
        port_i = int(port)
    except (TypeError, ValueError):
        raise FsError(ERR_LINK_BUS, f"socketcand port is not a number: {port!r}") from None
    cfg["port"] = port_i
    # python-can retries a refused connection for 10 s; check once, quickly, to name the problem
    try:
        with socket.create_connection((str(host), port_i), timeout=2.0):
            pass
    except OSError as e:
        raise FsError(
            ERR_LINK_BUS, f"cannot connect to socketcand at {host}:{port_i}: {e.strerror or e}"
        ) from None


def _open_with_retry(cfg: dict[str, Any]) -> can.BusABC:
    """can.Bus(**cfg); a socketcand handshake that read the "< ok >" together with the first frame
    (python-can expects it alone: a client that was slow to read) is simply tried again."""
    for attempt in range(3):
        try:
            return can.Bus(**cfg)
        except can.CanError as e:
            if cfg.get("interface") != "socketcand" or "got: '< ok >" not in str(e) or attempt == 2:
                raise
    raise AssertionError("unreachable")


def open_bus(ns: argparse.Namespace) -> tuple[can.BusABC, dict[str, Any]]:
    """Open the bus the options describe; FsError(630) with one line on any failure."""
    node = getattr(ns, "node", 0)
    if not 0 <= node <= 15:
        raise FsError(ERR_LINK_ARGS, f"--node must be 0..15: {node}")
    req = getattr(ns, "request_timeout", None)
    if req is not None and not 0.0 < req <= 600.0:
        raise FsError(ERR_LINK_ARGS, f"--request-timeout must be in (0, 600] s: {req:g}")
    period = getattr(ns, "telemetry_period", 1)
    if not 1 <= period <= MAX_TELEMETRY_PERIOD_MS:
        raise FsError(ERR_LINK_ARGS, f"--telemetry-period must be 1..{MAX_TELEMETRY_PERIOD_MS} ms: {period}")
    cfg = bus_config(ns)
    iface = cfg["interface"]
    if iface not in can.VALID_INTERFACES:
        raise FsError(ERR_LINK_BUS, f"unknown CAN interface {iface!r}")
    if iface == "socketcand":
        _precheck_socketcand(cfg)
        if not cfg.get("channel"):
            cfg["channel"] = "can0"
    try:
        bus = _open_with_retry(cfg)
    except can.CanInterfaceNotImplementedError as e:
        raise FsError(ERR_LINK_BUS, f"CAN interface {iface!r} not available here: {e}") from None
    except (can.CanError, OSError, ValueError, TypeError, ImportError) as e:
        msg = str(e).splitlines()[0] if str(e) else type(e).__name__
        if iface == "socketcand" and "Expected '< ok >'" in msg:
            msg = f"channel {cfg.get('channel')!r} not served by socketcand at {cfg.get('host')}:{cfg.get('port')}"
            raise FsError(ERR_LINK_BUS, msg) from None
        raise FsError(
            ERR_LINK_BUS, f"cannot open CAN interface {iface!r} channel {cfg.get('channel')!r}: {msg}"
        ) from None
    return bus, cfg
