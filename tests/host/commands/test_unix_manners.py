"""The command as a Unix tool: a reader that closes the pipe early (``| head -1``) ends the command
quietly, and a device command without any bus configured names how to choose one."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from forceskill import cli
from forceskill.model import synthetic
from forceskill.model.demo import write_csv

EXE = [sys.executable, "-m", "forceskill"]


def closed_reader(argv: list[str], env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    """Run the CLI with its standard output a pipe whose reader has already gone."""
    r, w = os.pipe()
    os.close(r)
    try:
        return subprocess.run(
            [*EXE, *argv], stdout=w, stderr=subprocess.PIPE, text=True, timeout=120, env=env
        )
    finally:
        os.close(w)


def head_1(argv: list[str], env: dict[str, str] | None = None) -> tuple[str, int, str]:
    """`forceskill ARGV | head -1`: head's output, the command's exit status and its stderr."""
    p = subprocess.Popen([*EXE, *argv], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    assert p.stdout is not None and p.stderr is not None
    first = p.stdout.readline()
    p.stdout.close()
    err = p.stderr.read()
    return first, p.wait(timeout=120), err


@pytest.fixture(scope="module")
def press_skill(tmp_path_factory: pytest.TempPathFactory) -> Path:
    d = tmp_path_factory.mktemp("pipe")
    demo = synthetic.pressing(seed=2, duration_s=3.0)
    write_csv(d / "demo.csv", {"t": demo.t_s, "x": demo.pos_m, "f_contact": demo.force_N})
    assert cli.main(["fit", str(d / "demo.csv"), "-k", "100", "-o", str(d / "p.skill")]) == 0
    return d / "p.skill"


@pytest.mark.parametrize(
    "argv",
    [
        ["rollout", "{skill}", "-o", "-", "--steps", "200000"],
        ["show", "{skill}"],
        ["show", "{skill}", "--json"],
        ["--help"],
    ],
    ids=["rollout-stdout", "show", "show-json", "help"],
)
def test_a_closed_pipe_ends_quietly(argv: list[str], press_skill: Path) -> None:
    args = [a.replace("{skill}", str(press_skill)) for a in argv]
    r = closed_reader(args)
    assert r.stderr == "", r.stderr
    assert r.returncode in (0, cli.EXIT_PIPE_CLOSED)
    first, rc, err = head_1(args)
    assert first.strip() and err == "" and rc in (0, cli.EXIT_PIPE_CLOSED), (first, rc, err)


def test_a_long_stream_cut_by_head_exits_as_sigpipe_would(press_skill: Path) -> None:
    first, rc, err = head_1(["rollout", str(press_skill), "-o", "-", "--steps", "2000000"])
    assert first == "t,f_hat\n"
    assert err == "" and rc == 141


def test_no_bus_configured_names_how_to_choose_one(tmp_path: Path) -> None:
    env = {k: v for k, v in os.environ.items() if not k.startswith("CAN_")}
    env["HOME"] = str(tmp_path)  # no ~/.canrc
    for argv in (["status"], ["status", "--clear"], ["record", "-o", str(tmp_path / "x.blf")]):
        r = subprocess.run([*EXE, *argv], capture_output=True, text=True, env=env, timeout=120)
        assert r.returncode == 2 and r.stdout == ""
        assert r.stderr.count("\n") == 1, r.stderr
        assert "Unknown interface" not in r.stderr and "None" not in r.stderr
        assert "python-can's configuration (~/.canrc or $CAN_INTERFACE" in r.stderr
        assert "-i/--interface NAME -c/--channel CH" in r.stderr and r.stderr.endswith("[630]\n")
    # python-can's configuration is honoured first: the interface it names is the one tried
    (tmp_path / ".canrc").write_text("[default]\ninterface = nosuchbus\nchannel = x\n")
    r = subprocess.run([*EXE, "status"], capture_output=True, text=True, env=env, timeout=120)
    assert r.returncode == 2 and r.stderr == "forceskill: error: unknown CAN interface 'nosuchbus' [630]\n"
    env["CAN_INTERFACE"] = "otherbus"
    r = subprocess.run([*EXE, "status"], capture_output=True, text=True, env=env, timeout=120)
    assert r.returncode == 2 and "'otherbus'" in r.stderr
