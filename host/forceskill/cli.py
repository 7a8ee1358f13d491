"""The ``forceskill`` command: builds the parser from the command modules and dispatches.

Each module named in ``COMMAND_MODULES`` (one per command, in ``forceskill.commands``) exposes
``register(subparsers)`` and adds its sub-command with ``set_defaults(func=handler)``,
``handler(args) -> int``. Modules are imported lazily when the parser is built, only the one a
command line needs (``LAZY_COMMANDS``); one that is missing or fails to import does not break the
others.

Bad input never gives a traceback: one line ``forceskill: error: ...`` on stderr, exit status 2,
and no output file (outputs are written to a temporary file and renamed on success).
"""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Sequence
from typing import NoReturn

from .errors import ERR_IO, ERR_UNEXPECTED, FsError, stdout_closed

#: Sub-command modules, one per command (``image`` shares the flash module): a module added here
#: (e.g. a plugin's "package.module") exposes ``register(subparsers)``.
COMMAND_MODULES: list[str] = [
    "forceskill.commands.fit",
    "forceskill.commands.rollout",
    "forceskill.commands.show",
    "forceskill.commands.report",
    "forceskill.commands.record",
    "forceskill.commands.upload",
    "forceskill.commands.run",
    "forceskill.commands.status",
    "forceskill.commands.monitor",
    "forceskill.commands.journey",
    "forceskill.commands.flash",
]
#: Commands of those modules with their one-line help: a command line naming one of them imports
#: only its module; ``forceskill --help`` lists them without importing any (numpy, python-can,
#: cantools, udsoncan and matplotlib stay unloaded). A module not in this table is imported for the help.
LAZY_COMMANDS: dict[str, tuple[str, str]] = {
    "fit": ("forceskill.commands.fit", "learn a force skill from one demonstration or the mean of several"),
    "rollout": ("forceskill.commands.rollout", "evaluate a skill offline (the firmware's DMP in numpy)"),
    "show": ("forceskill.commands.show", "summarise a skill image"),
    "report": ("forceskill.commands.report", "run every paper experiment on the HIL simulator"),
    "record": ("forceskill.commands.record", "record a demonstration (device in TEACH) to a CAN log"),
    "upload": ("forceskill.commands.upload", "upload a skill into a device slot (UDS over ISO-TP)"),
    "run": ("forceskill.commands.run", "execute a skill or a sequence on the device and report tracking"),
    "status": ("forceskill.commands.status", "show a device's state, versions and skill slots"),
    "monitor": ("forceskill.commands.monitor", "live values of a device (--plot for a live plot)"),
    "journey": (
        "forceskill.commands.journey",
        "record -> fit -> upload -> run 1x/1.5x over CAN on the simulator",
    ),
    "flash": (
        "forceskill.commands.flash",
        "flash a signed firmware image over CAN (UDS), test-boot it, read back",
    ),
    "image": ("forceskill.commands.flash", "build or inspect a signed firmware image"),
}

EXIT_BAD_INPUT = 2


class _Parser(argparse.ArgumentParser):
    """argparse with a one-line error (no usage dump), exit status 2."""

    def error(self, message: str) -> NoReturn:
        sys.stderr.write(f"forceskill: error: {message}\n")
        sys.exit(EXIT_BAD_INPUT)


# ---- parser and entry point -------------------------------------------------------------------


def _modules_for(argv: Sequence[str] | None) -> tuple[list[str], list[str]]:
    """(modules to import, commands to list from LAZY_COMMANDS without importing) for ``argv``."""
    if argv is None:
        return list(COMMAND_MODULES), []
    cmd = next((a for a in argv if not a.startswith("-")), None)
    if cmd in LAZY_COMMANDS and LAZY_COMMANDS[cmd][0] in COMMAND_MODULES:
        return [LAZY_COMMANDS[cmd][0]], []
    if cmd is None:  # help, version or nothing: list the known commands, import the others
        lazy = {m for m, _ in LAZY_COMMANDS.values()}
        return (
            [m for m in COMMAND_MODULES if m not in lazy],
            [c for c, (m, _) in LAZY_COMMANDS.items() if m in COMMAND_MODULES],
        )
    return list(COMMAND_MODULES), []


def build_parser(argv: Sequence[str] | None = None) -> tuple[argparse.ArgumentParser, list[str]]:
    """The parser for ``argv`` (every command when None), and the command modules that failed to load."""
    from . import __version__

    parser = _Parser(
        prog="forceskill",
        description="Learn force skills from demonstration and run them on a force controller over CAN.",
    )
    parser.add_argument("--version", action="version", version=f"forceskill {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    modules, listed = _modules_for(argv)
    for name in listed:
        sub.add_parser(name, help=LAZY_COMMANDS[name][1])
    missing: list[str] = []
    for name in modules:
        try:
            mod = importlib.import_module(name)
            mod.register(sub)
        except Exception as e:  # an optional command must not break the others
            missing.append(f"{name} ({type(e).__name__}: {e})")
    return parser, missing


#: Exit status after the reader of standard output went away: a process ended by SIGPIPE's.
EXIT_PIPE_CLOSED = 128 + 13


def _pipe_closed() -> int:
    """End quietly when the reader of standard output has gone (``forceskill status | head -1``):
    what is left unprinted goes to /dev/null instead of an error at the interpreter's exit."""
    import os

    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError):
        pass
    return EXIT_PIPE_CLOSED


def main(argv: Sequence[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    parser, missing = build_parser(argv)
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        if missing:
            sys.stderr.write("forceskill: unavailable commands: " + "; ".join(missing) + "\n")
        return EXIT_BAD_INPUT
    try:
        rc = int(args.func(args) or 0)
        sys.stdout.flush()  # a closed pipe is found here, not in the interpreter's exit
        return rc
    except BrokenPipeError as e:
        if stdout_closed():
            return _pipe_closed()
        sys.stderr.write(f"forceskill: error: {e.strerror or e} [{ERR_IO}]\n")
        return EXIT_BAD_INPUT
    except FsError as e:
        sys.stderr.write(f"forceskill: error: {e.message} [{e.code}]\n")
        return EXIT_BAD_INPUT
    except OSError as e:
        where = f": {e.filename}" if e.filename else ""
        sys.stderr.write(f"forceskill: error: {e.strerror or e}{where} [{ERR_IO}]\n")
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        sys.stderr.write("forceskill: interrupted\n")
        return 130
    except Exception as e:  # a failure no check foresaw (a library's own error): still one line
        first = (str(e).splitlines() or [""])[0]
        sys.stderr.write(f"forceskill: error: unexpected {type(e).__name__}: {first} [{ERR_UNEXPECTED}]\n")
        return EXIT_BAD_INPUT


if __name__ == "__main__":
    sys.exit(main())
