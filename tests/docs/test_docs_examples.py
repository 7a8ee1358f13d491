"""The docs' shell examples run as printed: README.md's "Using it" and docs/cli.md.

The convention (stated at the top of docs/cli.md): a fenced block tagged ``console`` is a
transcript. Each line starting with ``$ `` is a command, run by bash; the lines up to the next
command or the block's end are what it prints (stdout and stderr together). A line ``...`` stands
for any number of lines, ``...`` inside a line for any text on that line. Blocks tagged ``sh`` or
without a tag are not run. The commands run in order, one scratch folder per document, where
``.venv``, ``build``, ``tests`` and ``hil_sim`` lead to the checkout's (so the documented first
steps, ``.venv/bin/python tests/helpers/recordings.py .`` and ``hil_sim run
hil_sim/scenarios/...``, make the inputs there) and ``forceskill`` and ``hil_sim`` are on PATH.
``-i socketcan -c can0`` stands for the reader's bus: it is replaced by the options of a
simulator this test starts (``hil_sim serve`` on the pressing scenario, socketcand).

Also: docs/safety.md's HIL fault table is what ``hil_sim faults --seed 1`` prints now
(``hil_sim/faults/update_safety_doc.py`` regenerates it)."""

from __future__ import annotations

import importlib.util
import os
import re
import subprocess
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest

from helpers.canbus import Server
from helpers.paths import REPO, SCENARIOS, hil_sim_path

BUS = "-i socketcan -c can0"
#: What one command may take (a fit with a search on a long recording, a CAN run).
STEP_TIMEOUT_S = 120


@dataclass
class Step:
    cmd: str
    expected: list[str]
    where: str


def transcript(text: str, name: str) -> list[Step]:
    """The ``console`` blocks' commands and their printed lines, in document order (a block's
    lines taken from its fence's indentation on: a block inside a list item)."""
    steps: list[Step] = []
    fence: str | None = None  # the open block's fence indentation ("" at the margin)
    run = False
    for no, line in enumerate(text.splitlines(), 1):
        stripped = line.strip()
        if fence is None:
            if stripped.startswith("```"):
                fence, run = line[: len(line) - len(line.lstrip())], stripped == "```console"
            continue
        if stripped.startswith("```"):
            fence = None
            continue
        if not run:
            continue
        body = (line[len(fence) :] if line.startswith(fence) else line.lstrip()).rstrip()
        if body.startswith("$ "):
            steps.append(Step(body[2:], [], f"{name}:{no}"))
        elif steps:
            steps[-1].expected.append(body)
    return steps


def section(text: str, heading: str) -> str:
    """The level-2 section ``## heading`` of a Markdown text."""
    m = re.search(rf"^## {re.escape(heading)}\n(.*?)(?=^## |\Z)", text, flags=re.M | re.S)
    assert m, f"no section '## {heading}'"
    return m.group(1)


def matches(expected: list[str], actual: str) -> bool:
    """``actual`` printed as ``expected`` shows it (``...`` lines and ``...`` in a line as wildcards)."""
    pat = ""
    for line in expected:
        if line == "...":
            pat += r"(?:[^\n]*\n)*?"
        else:
            pat += ".*".join(re.escape(p) for p in line.split("...")) + r"[ \t]*\n"
    got = "\n".join(ln.rstrip() for ln in actual.rstrip("\n").splitlines())
    return re.fullmatch(pat, got + "\n" if got else "") is not None


def test_matching_conventions() -> None:
    assert matches(["a", "...", "d"], "a\nb\nc\nd\n")
    assert matches(["a", "...", "d"], "a\nd")
    assert matches(["x = ... s"], "x = 1.5 s")
    assert not matches(["x = ... s"], "x = 1.5 ms\n")
    assert not matches(["a"], "a\nb")
    assert matches([], "")
    steps = transcript("```sh\n$ no\n```\n```console\n$ one\nout\n...\n$ two\n```\n", "t")
    assert [(s.cmd, s.expected) for s in steps] == [("one", ["out", "..."]), ("two", [])]


def _workspace(tmp: Path) -> Path:
    for name in (".venv", "build", "tests", "hil_sim"):
        (tmp / name).symlink_to(REPO / name)
    (tmp / "docs" / "hil").mkdir(parents=True)  # plots the examples write stay here
    return tmp


@pytest.fixture(scope="module")
def server() -> Iterator[list[Server]]:
    """A simulator, started by the first example that names the bus."""
    started: list[Server] = []
    yield started
    for s in started:
        s.stop()


def _run(steps: list[Step], ws: Path, server: list[Server]) -> list[str]:
    env = dict(os.environ)
    env["PATH"] = os.pathsep.join([str(Path(sys.executable).parent), str(hil_sim_path().parent), env["PATH"]])
    env["PYTHONUNBUFFERED"] = "1"  # stdout and stderr in the order printed
    env["FORCESKILL_HIL_SIM"] = str(hil_sim_path())
    failures = []
    for st in steps:
        cmd = st.cmd
        if BUS in cmd:
            if not server:
                server.append(Server(SCENARIOS / "pressing_task1_demo.toml"))
            cmd = cmd.replace(BUS, " ".join(server[0].bus_args()))
        r = subprocess.run(
            ["bash", "-c", cmd],
            cwd=ws,
            env=env,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            timeout=STEP_TIMEOUT_S,
        )
        refused = any("error:" in ln and ln.rstrip().endswith("]") for ln in st.expected)
        ok_status = (r.returncode != 0) if refused else (r.returncode == 0)
        if not (ok_status and matches(st.expected, r.stdout)):
            failures.append(
                f"{st.where}: $ {st.cmd}\n  exit status {r.returncode}\n  documented:\n"
                + "".join(f"    {ln}\n" for ln in st.expected)
                + "  printed:\n"
                + "".join(f"    {ln}\n" for ln in r.stdout.splitlines())
            )
    return failures


@pytest.mark.parametrize("doc", ["README.md", "docs/cli.md"])
def test_the_examples_print_what_the_docs_show(doc: str, tmp_path: Path, server: list[Server]) -> None:
    text = (REPO / doc).read_text()
    if doc == "README.md":
        text = section(text, "Using it")
    steps = transcript(text, doc)
    assert steps, f"{doc}: no console examples"
    failures = _run(steps, _workspace(tmp_path), server)
    assert not failures, "\n".join(failures)


def test_the_safety_fault_table_is_what_hil_sim_prints(tmp_path: Path) -> None:
    spec = importlib.util.spec_from_file_location(
        "update_safety_doc", REPO / "hil_sim/faults/update_safety_doc.py"
    )
    assert spec and spec.loader
    upd = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(upd)
    out = tmp_path / "table.md"
    subprocess.run(
        [str(hil_sim_path()), "faults", "--seed", "1", "-o", str(out)], check=True, capture_output=True
    )
    doc = upd.DOC.read_text()
    assert upd.replace_section(doc, upd.section(out.read_text(), "hil_sim faults --seed 1")) == doc, (
        "docs/safety.md's fault table differs from hil_sim faults --seed 1: "
        "run hil_sim/faults/update_safety_doc.py build/hil_sim/hil_sim"
    )
