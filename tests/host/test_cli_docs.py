"""docs/cli.md against the CLI itself: every sub-command (and `image` action) has a section
`## <command>` with an example `$ forceskill <command> ...`, and every option its --help lists is
named in that section (or in "CAN bus options" when the section links there)."""

from __future__ import annotations

import argparse
import re
from pathlib import Path

import pytest

from forceskill import cli

DOC = Path(__file__).resolve().parents[2] / "docs" / "cli.md"
BUS_SECTION = "CAN bus options"
BUS_LINK = "(#can-bus-options)"


def _sections() -> dict[str, str]:
    """Level-2 sections of docs/cli.md by heading text."""
    out: dict[str, str] = {}
    for part in re.split(r"^## ", DOC.read_text(), flags=re.M)[1:]:
        head, _, body = part.partition("\n")
        out[head.strip()] = body
    return out


def _subparsers(p: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    for a in p._actions:
        if isinstance(a, argparse._SubParsersAction):
            return dict(a.choices)
    return {}


def _commands() -> dict[str, argparse.ArgumentParser]:
    """Every runnable command: `fit`, ..., and `image build` for nested actions."""
    parser, missing = cli.build_parser()
    assert not missing, f"command modules failed to load: {missing}"
    out: dict[str, argparse.ArgumentParser] = {}
    for name, p in _subparsers(parser).items():
        nested = _subparsers(p)
        if nested:
            out.update({f"{name} {n}": q for n, q in nested.items()})
        else:
            out[name] = p
    return out


def _options(p: argparse.ArgumentParser) -> list[tuple[str, ...]]:
    """The options --help lists, each with all its spellings (help itself and hidden ones excluded)."""
    return [
        tuple(a.option_strings)
        for a in p._actions
        if a.option_strings and not isinstance(a, argparse._HelpAction) and a.help != argparse.SUPPRESS
    ]


COMMANDS = _commands()


def _section(command: str) -> str:
    secs = _sections()
    found = [body for head, body in secs.items() if head == command or head.startswith(command + ":")]
    assert found, f"docs/cli.md has no section '## {command}: ...'"
    body = found[0]
    if BUS_LINK in body:
        body += secs[BUS_SECTION]
    return body


def test_every_command_is_found() -> None:
    # the commands the product ships; a module failing to import must not hide one silently
    assert {
        "fit",
        "rollout",
        "show",
        "report",
        "record",
        "upload",
        "run",
        "status",
        "monitor",
        "journey",
        "flash",
        "image build",
        "image show",
    } <= set(COMMANDS)


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_command_has_an_example(command: str) -> None:
    assert re.search(rf"^\$ forceskill {re.escape(command)}(\s|$)", _section(command), flags=re.M), (
        f"docs/cli.md, section {command}: no example line '$ forceskill {command} ...'"
    )


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_every_option_is_documented(command: str) -> None:
    body = _section(command)
    undocumented = [
        o[-1]
        for o in _options(COMMANDS[command])
        if not any(re.search(rf"(?<![\w-]){re.escape(s)}(?![\w-])", body) for s in o)
    ]
    assert not undocumented, f"docs/cli.md, section {command}: options not described: {undocumented}"
