"""The docs' shell examples run as printed: README.md and every docs/*.md.

The convention (stated at the top of docs/cli.md): a fenced block tagged ``console`` is a
transcript. Each line starting with ``$ `` is a command, run by bash; the lines up to the next
command or the block's end are what it prints (stdout and stderr together). A line ``...`` stands
for any number of lines, ``...`` inside a line for any text on that line. The commands run in
order, one scratch folder per document, where ``.venv``, ``build``, ``tests`` and ``hil_sim`` lead
to the checkout's (so the documented first steps, ``.venv/bin/python tests/helpers/recordings.py
.`` and ``hil_sim run hil_sim/scenarios/...``, make the inputs there) and ``forceskill`` and
``hil_sim`` are on PATH. ``-i socketcan -c can0`` stands for the reader's bus: it is replaced by
the options of a simulator this test starts for the document (``hil_sim serve`` on the pressing
scenario, socketcand), one for all its examples; a block preceded by ``<!-- bus: SCENARIO.toml -->``
talks to one on that scenario of ``hil_sim/scenarios`` (one simulator per scenario and document).

A shell example that is not a transcript (a block tagged ``sh``, ``bash`` or ``shell``, or an
untagged one holding a command) must say why on the line just above its fence:
``<!-- not run: REASON -->``, REASON one of ``NOT_RUN`` (below), optionally followed by ``:`` and
a detail. ``test_every_shell_example_runs_or_says_why`` fails on any other and prints the skipped
ones, so the set is auditable. Blocks that are no commands (formulas, printed output, diagrams)
are tagged ``text`` or left untagged.

Also: docs/safety.md's HIL fault table is what ``hil_sim faults --seed 1`` prints now
(``hil_sim/faults/update_safety_doc.py`` regenerates it)."""

from __future__ import annotations

import importlib.util
import os
import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import pytest

from helpers.canbus import Server
from helpers.paths import REPO, SCENARIOS, hil_sim_path

BUS = "-i socketcan -c can0"
#: What one command may take (a fit with a search on a long recording, a CAN run).
STEP_TIMEOUT_S = 120
#: Why a shell example is not run: a usage line with placeholders (FILE, N), a real CAN adapter or
#: board, the qemu guest (scripts/test_linux_can.sh runs it), more than STEP_TIMEOUT_S, or a
#: set-up step (installs packages or builds).
NOT_RUN = ("synopsis", "hardware", "vm", "long", "setup")
SHELL_TAGS = ("sh", "bash", "shell", "console")
DOCS = ["README.md", *sorted(str(p.relative_to(REPO)) for p in (REPO / "docs").glob("*.md"))]
_NOT_RUN_RE = re.compile(r"<!-- not run: (\w+)(?::[^>]*)? -->")
_BUS_RE = re.compile(r"<!-- bus: ([\w.-]+\.toml) -->")
#: The simulator's scenario behind a transcript's bus unless its block names another.
BUS_SCENARIO = "pressing_task1_demo.toml"
# An untagged block holds a command when a line starts with a prompt, a program the docs use, a
# path to one, or a variable assignment before one.
_COMMAND_RE = re.compile(
    r"^(\$ |(sudo|forceskill|hil_sim|cmake|ninja|make|python3?|pip|git|ip|candump|cansend|cangen|"
    r"qemu-system-\w+|for|export|cd|pkg-config)( |$)|\.{0,2}/|(\.venv|build|scripts|tools|bench|"
    r"tests|hil_sim)/\S|[A-Z_]+=\S+ )"
)


@dataclass
class Block:
    """A fenced block: its tag, first line (the fence's), lines (from its fence's indentation on:
    a block inside a list item) and the line above its fence."""

    tag: str
    line: int
    body: list[str]
    above: str


def blocks(text: str) -> list[Block]:
    out: list[Block] = []
    lines = text.splitlines()
    cur: Block | None = None
    fence = ""
    for no, line in enumerate(lines, 1):
        stripped = line.strip()
        if cur is None:
            if stripped.startswith("```"):
                fence = line[: len(line) - len(line.lstrip())]
                above = lines[no - 2].strip() if no > 1 else ""
                cur = Block(stripped[3:].strip(), no, [], above)
            continue
        if stripped.startswith("```"):
            out.append(cur)
            cur = None
            continue
        cur.body.append((line[len(fence) :] if line.startswith(fence) else line.lstrip()).rstrip())
    return out


def is_shell(b: Block) -> bool:
    """A shell example: tagged as one, or untagged with a command in it."""
    if b.tag in SHELL_TAGS:
        return True
    return b.tag == "" and any(_COMMAND_RE.match(ln.lstrip()) for ln in b.body)


def not_run_reason(b: Block) -> str | None:
    """The reason given above a block that is not run, or None."""
    m = _NOT_RUN_RE.fullmatch(b.above)
    return m.group(1) if m else None


@dataclass
class Step:
    cmd: str
    expected: list[str]
    where: str
    scenario: str = BUS_SCENARIO  # of the simulator behind BUS


def transcript(text: str, name: str) -> list[Step]:
    """The ``console`` blocks' commands and their printed lines, in document order."""
    steps: list[Step] = []
    for b in blocks(text):
        if b.tag != "console":
            continue
        first = len(steps)
        bus = _BUS_RE.fullmatch(b.above)
        scenario = bus.group(1) if bus else BUS_SCENARIO
        for i, body in enumerate(b.body):
            if body.startswith("$ "):
                steps.append(Step(body[2:], [], f"{name}:{b.line + 1 + i}", scenario))
            elif len(steps) > first:
                steps[-1].expected.append(body)
    return steps


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
    steps = transcript("```console\n$ a\n```\n<!-- bus: other.toml -->\n```console\n$ b\n```\n", "t")
    assert [(s.cmd, s.scenario) for s in steps] == [("a", BUS_SCENARIO), ("b", "other.toml")]
    text = "a\n<!-- not run: vm -->\n```sh\nsudo ip link\n```\n```\nf = k*x\n```\n```\nninja -C build\n```\n"
    bs = blocks(text)
    assert [(b.tag, is_shell(b), not_run_reason(b)) for b in bs] == [
        ("sh", True, "vm"),
        ("", False, None),
        ("", True, None),
    ]


def _workspace(tmp: Path) -> Path:
    for name in (".venv", "build", "tests", "hil_sim"):
        (tmp / name).symlink_to(REPO / name)
    (tmp / "docs" / "hil").mkdir(parents=True)  # plots the examples write stay here
    return tmp


def _run(steps: list[Step], ws: Path) -> list[str]:
    env = dict(os.environ)
    env["PATH"] = os.pathsep.join([str(Path(sys.executable).parent), str(hil_sim_path().parent), env["PATH"]])
    env["PYTHONUNBUFFERED"] = "1"  # stdout and stderr in the order printed
    env["FORCESKILL_HIL_SIM"] = str(hil_sim_path())
    failures = []
    servers: dict[str, Server] = {}  # a simulator per scenario, started by its first bus example
    try:
        for st in steps:
            cmd = st.cmd
            if BUS in cmd:
                if st.scenario not in servers:
                    servers[st.scenario] = Server(SCENARIOS / st.scenario)
                cmd = cmd.replace(BUS, " ".join(servers[st.scenario].bus_args()))
            try:
                r = subprocess.run(
                    ["bash", "-c", cmd],
                    cwd=ws,
                    env=env,
                    stdout=subprocess.PIPE,
                    stderr=subprocess.STDOUT,
                    text=True,
                    timeout=STEP_TIMEOUT_S,
                )
            except subprocess.TimeoutExpired:
                failures.append(f"{st.where}: $ {st.cmd}\n  took more than {STEP_TIMEOUT_S} s")
                continue
            refused = any("error:" in ln and ln.rstrip().endswith("]") for ln in st.expected)
            ok_status = (r.returncode != 0) if refused else (r.returncode == 0)
            if not (ok_status and matches(st.expected, r.stdout)):
                failures.append(
                    f"{st.where}: $ {st.cmd}\n  exit status {r.returncode}\n  documented:\n"
                    + "".join(f"    {ln}\n" for ln in st.expected)
                    + "  printed:\n"
                    + "".join(f"    {ln}\n" for ln in r.stdout.splitlines())
                )
    finally:
        for server in servers.values():
            server.stop()
    return failures


#: The documents with transcripts (the others' shell blocks each say why they are not run:
#: test_every_shell_example_runs_or_says_why).
DOCS_WITH_TRANSCRIPTS = [d for d in DOCS if transcript((REPO / d).read_text(), d)]


@pytest.mark.parametrize("doc", DOCS_WITH_TRANSCRIPTS)
def test_the_examples_print_what_the_docs_show(doc: str, tmp_path: Path) -> None:
    steps = transcript((REPO / doc).read_text(), doc)
    failures = _run(steps, _workspace(tmp_path))
    assert not failures, "\n".join(failures)


def test_every_shell_example_runs_or_says_why() -> None:
    skipped, bad = [], []
    for doc in DOCS:
        for b in blocks((REPO / doc).read_text()):
            if not is_shell(b) or b.tag == "console":
                continue
            reason = not_run_reason(b)
            where = f"{doc}:{b.line} ({b.body[0] if b.body else ''})"
            if reason in NOT_RUN:
                skipped.append(f"{reason:9} {where}")
            else:
                bad.append(f"{where}: {b.above!r} above the fence")
    print(f"shell examples not run ({len(skipped)}):", *sorted(skipped), sep="\n  ")
    assert not bad, (
        "shell examples neither a console transcript nor preceded by <!-- not run: REASON --> "
        f"(REASON one of {', '.join(NOT_RUN)}):\n  " + "\n  ".join(bad)
    )


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
