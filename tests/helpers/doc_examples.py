"""The docs' shell examples as data: their fenced blocks, the ``console`` transcripts' commands
and printed lines, the matching of what a command printed against what a document shows, and the
running of a transcript's commands (tests/docs/test_docs_examples.py states the conventions).

A transcript preceded by ``<!-- run by: tests/PATH.py -->`` is run by that test (one that runs the
command anyway, with checks of its own: ``documented_step`` gives it the command and its printed
lines); the docs test checks that the named file asks for it and runs every other transcript."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

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
_NOT_RUN_RE = re.compile(r"<!-- not run: (\w+)(?::[^>]*)? -->")
_BUS_RE = re.compile(r"<!-- bus: ([\w.-]+\.toml) -->")
RUN_BY_RE = re.compile(r"<!-- run by: (tests/[\w/.-]+\.py) -->")
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


def run_by(b: Block) -> str | None:
    """The test file named above a transcript that another test runs, or None."""
    m = RUN_BY_RE.fullmatch(b.above)
    return m.group(1) if m else None


def transcript(text: str, name: str, by: str | None = None) -> list[Step]:
    """The ``console`` blocks' commands and their printed lines, in document order: those the docs
    test runs (by None), or those ``<!-- run by: BY -->`` names."""
    steps: list[Step] = []
    for b in blocks(text):
        if b.tag != "console" or run_by(b) != by:
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


def workspace(tmp: Path) -> Path:
    """A scratch folder laid out as the docs' examples expect (the checkout's .venv, build, tests
    and hil_sim linked in)."""
    for name in (".venv", "build", "tests", "hil_sim"):
        (tmp / name).symlink_to(REPO / name)
    (tmp / "docs" / "hil").mkdir(parents=True)  # plots the examples write stay here
    return tmp


def run(steps: list[Step], ws: Path, timeout_s: float = STEP_TIMEOUT_S) -> list[str]:
    """Run the steps in order in ws; one failure text per step that printed other than documented
    (or ended with the other exit status, or took more than timeout_s)."""
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
                    timeout=timeout_s,
                )
            except subprocess.TimeoutExpired:
                failures.append(f"{st.where}: $ {st.cmd}\n  took more than {timeout_s} s")
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


def documented_step(doc: str, prefix: str, by: str) -> Step:
    """The command of doc's transcripts run by the test file ``by`` that starts with prefix."""
    steps = [s for s in transcript((REPO / doc).read_text(), doc, by) if s.cmd.startswith(prefix)]
    assert len(steps) == 1, f"{doc}: {len(steps)} transcripts of `{prefix}` marked <!-- run by: {by} -->"
    return steps[0]
