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
A transcript preceded by ``<!-- run by: tests/PATH.py -->`` is run and compared by that test, one
that runs the command anyway with checks of its own (``forceskill journey``: tests/can/test_band.py);
``test_a_transcript_run_by_another_test_is_asked_for_there`` checks that the file asks for it.

A shell example that is not a transcript (a block tagged ``sh``, ``bash`` or ``shell``, or an
untagged one holding a command) must say why on the line just above its fence:
``<!-- not run: REASON -->``, REASON one of ``NOT_RUN`` (helpers.doc_examples), optionally followed by ``:`` and
a detail. ``test_every_shell_example_runs_or_says_why`` fails on any other and prints the skipped
ones, so the set is auditable. Blocks that are no commands (formulas, printed output, diagrams)
are tagged ``text`` or left untagged.

Also: docs/safety.md's HIL fault table is what ``hil_sim faults --seed 1`` prints now
(``hil_sim/faults/update_safety_doc.py`` regenerates it)."""

from __future__ import annotations

import importlib.util
import subprocess
from pathlib import Path

import pytest

from helpers.doc_examples import (
    BUS_SCENARIO,
    NOT_RUN,
    blocks,
    is_shell,
    matches,
    not_run_reason,
    run,
    run_by,
    transcript,
    workspace,
)
from helpers.paths import REPO, hil_sim_path

DOCS = ["README.md", *sorted(str(p.relative_to(REPO)) for p in (REPO / "docs").glob("*.md"))]


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
    text = "```console\n$ a\n```\n<!-- run by: tests/x/test_y.py -->\n```console\n$ b\nout\n```\n"
    assert [s.cmd for s in transcript(text, "t")] == ["a"]
    assert [(s.cmd, s.expected) for s in transcript(text, "t", "tests/x/test_y.py")] == [("b", ["out"])]
    text = "a\n<!-- not run: vm -->\n```sh\nsudo ip link\n```\n```\nf = k*x\n```\n```\nninja -C build\n```\n"
    bs = blocks(text)
    assert [(b.tag, is_shell(b), not_run_reason(b)) for b in bs] == [
        ("sh", True, "vm"),
        ("", False, None),
        ("", True, None),
    ]


#: The documents with transcripts (the others' shell blocks each say why they are not run:
#: test_every_shell_example_runs_or_says_why).
DOCS_WITH_TRANSCRIPTS = [d for d in DOCS if transcript((REPO / d).read_text(), d)]


@pytest.mark.parametrize("doc", DOCS_WITH_TRANSCRIPTS)
def test_the_examples_print_what_the_docs_show(doc: str, tmp_path: Path) -> None:
    steps = transcript((REPO / doc).read_text(), doc)
    failures = run(steps, workspace(tmp_path))
    assert not failures, "\n".join(failures)


def test_a_transcript_run_by_another_test_is_asked_for_there() -> None:
    """Each ``<!-- run by: FILE -->`` transcript's command is asked for in FILE by
    ``documented_step(DOC, ...)`` (helpers.doc_examples), which fails unless it finds it."""
    named = 0
    for doc in DOCS:
        for b in blocks((REPO / doc).read_text()):
            by = run_by(b)
            if b.tag != "console" or by is None:
                continue
            named += 1
            test = REPO / by
            assert test.is_file(), f"{doc}:{b.line}: {b.above} names no file"
            assert f'documented_step("{doc}"' in test.read_text(), (
                f"{doc}:{b.line}: {by} does not ask for this transcript (documented_step)"
            )
    assert named >= 1  # the journey's


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
