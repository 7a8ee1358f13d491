"""The user's files are safe: every command writes through forceskill.outputs (temporary file in the
target's folder, renamed on success, all outputs of a command or none), refuses an output that is
an input or a special file, follows symlinks and the umask; skills whose rollout is not finite or
peaks above the force limit are refused by fit/upload/run and flagged by show; rollouts are
bounded and streamed."""

from __future__ import annotations

import os
import stat
from pathlib import Path

import numpy as np
import pytest
from test_cli import VECTORS, run, write_demo

from forceskill import outputs
from forceskill.errors import FsError
from forceskill.model import dmp, synthetic
from forceskill.model.scales import MAX_ROLLOUT_STEPS
from forceskill.model.skill import Skill

SKILL = VECTORS / "press_n10_ridge_release.skill"


def fit_argv(demo: Path, out: Path, *extra: str) -> list[str]:
    return ["fit", str(demo), "--stiffness", "100", "-o", str(out), "--kernels", "20", *extra]


def snapshot(folder: Path) -> dict[str, bytes]:
    return {p.name: (p.read_bytes() if p.is_file() else b"<dir>") for p in sorted(folder.iterdir())}


@pytest.fixture()
def demo_csv(tmp_path: Path) -> Path:
    return write_demo(tmp_path / "demo.csv", synthetic.pressing(seed=2, duration_s=3.0))


def hostile(tmp_path: Path, factor: float) -> Path:
    """A valid image (CRC, ranges) whose weights are scaled by factor."""
    d = Skill.read(SKILL).to_json_dict()
    d["weights"] = [w * factor for w in d["weights"]]
    p = tmp_path / f"hostile_{factor:g}.skill"
    Skill.from_json_dict(d).write(p)
    return p


# ---- outputs -----------------------------------------------------------------------------------


def test_fit_refuses_to_overwrite_its_demonstration(
    demo_csv: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    before = snapshot(demo_csv.parent)
    rc, _, err = run(fit_argv(demo_csv, demo_csv), capsys)
    assert rc == 2 and "[660]" in err and err.count("\n") == 1
    assert snapshot(demo_csv.parent) == before
    link = demo_csv.parent / "alias.csv"
    link.symlink_to(demo_csv)
    before = snapshot(demo_csv.parent)
    for argv in (
        fit_argv(link, demo_csv),
        fit_argv(demo_csv, link),  # the input through a link
        fit_argv(demo_csv, demo_csv.parent / "s.skill", "--plot", str(link)),
    ):
        rc, _, err = run(argv, capsys)
        assert rc == 2 and "[660]" in err, err
    assert snapshot(demo_csv.parent) == before


def test_failed_fit_keeps_every_existing_file(
    demo_csv: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    for name, data in (("s.skill", b"old skill"), ("s.skill.json", b"old twin"), ("p.png", b"old plot")):
        (tmp_path / name).write_bytes(data)
    before = snapshot(tmp_path)
    rc, _, err = run(
        fit_argv(demo_csv, tmp_path / "s.skill", "--plot", str(tmp_path / "p.png"), "--kernels", "1"), capsys
    )
    assert rc == 2 and "[610]" in err
    assert snapshot(tmp_path) == before
    # the JSON twin cannot be written: neither the skill nor the plot changes
    (tmp_path / "s.skill.json").unlink()
    (tmp_path / "s.skill.json").mkdir()
    before = snapshot(tmp_path)
    rc, _, err = run(fit_argv(demo_csv, tmp_path / "s.skill", "--plot", str(tmp_path / "p.png")), capsys)
    assert rc == 2 and "[661]" in err and "directory" in err
    assert snapshot(tmp_path) == before


def test_commit_is_all_or_nothing(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    a, b = tmp_path / "a.bin", tmp_path / "b.bin"
    a.write_bytes(b"old a")
    real_replace = os.replace
    calls = {"n": 0}

    def failing_second(src: str, dst: str) -> None:
        calls["n"] += 1
        if calls["n"] == 2:
            raise OSError(28, "No space left on device")
        real_replace(src, dst)

    with outputs.Outputs() as outs:
        outs.write_bytes(a, b"new a")
        outs.write_bytes(b, b"new b")
        monkeypatch.setattr(outputs.os, "replace", failing_second)
        with pytest.raises(FsError) as e:
            outs.commit()
    monkeypatch.undo()
    assert e.value.code == 620 and "nothing was changed" in e.value.message
    assert a.read_bytes() == b"old a" and not b.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.bin"]  # no temporary files left


@pytest.mark.parametrize("mask,mode", [(0o022, 0o644), (0o002, 0o664), (0o077, 0o600)])
def test_new_outputs_follow_the_umask(
    tmp_path: Path, mask: int, mode: int, capsys: pytest.CaptureFixture[str]
) -> None:
    old = os.umask(mask)
    try:
        rc, _, err = run(["rollout", str(SKILL), "-o", str(tmp_path / "r.csv"), "--steps", "5"], capsys)
    finally:
        os.umask(old)
    assert rc == 0, err
    assert stat.S_IMODE((tmp_path / "r.csv").stat().st_mode) == mode


def test_replaced_output_keeps_its_mode_and_a_symlink_stays(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    target = tmp_path / "target.csv"
    target.write_text("old\n")
    target.chmod(0o640)
    link = tmp_path / "link.csv"
    link.symlink_to("target.csv")
    rc, _, err = run(["rollout", str(SKILL), "-o", str(link), "--steps", "5"], capsys)
    assert rc == 0, err
    assert link.is_symlink() and os.readlink(link) == "target.csv"
    assert target.read_text().startswith("t,f_hat\n") and stat.S_IMODE(target.stat().st_mode) == 0o640


def test_special_files_are_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    for target in (str(fifo), "/dev/null", "/dev/stdout", str(tmp_path)):
        rc, _, err = run(["rollout", str(SKILL), "-o", target, "--steps", "5"], capsys)
        assert rc == 2 and "[661]" in err, (target, err)
    assert stat.S_ISFIFO(fifo.stat().st_mode)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fifo"]


def test_dash_writes_csv_to_stdout(capsys: pytest.CaptureFixture[str]) -> None:
    rc, out, err = run(["rollout", str(SKILL), "-o", "-", "--steps", "3"], capsys)
    assert rc == 0, err
    _, f = dmp.rollout(Skill.read(SKILL), n_steps=3)
    lines = out.splitlines()
    assert lines[0] == "t,f_hat" and len(lines) == 5
    assert [float(x.split(",")[1]) for x in lines[1:]] == f.tolist()
    assert "wrote -: 4 rows" in err


# ---- inputs: bounded, one line ---------------------------------------------------------------


def test_rollout_is_bounded(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "r.csv"
    for argv, code in (
        (["--steps", "1000000000"], "[663]"),
        (["--time-scale", "1e6"], "[109]"),
        (["--goal-scale", "1e6"], "[109]"),
        (["--goal-scale", "-1"], "[109]"),
        (["--time-scale", "nan"], "[109]"),
    ):
        rc, _, err = run(["rollout", str(SKILL), "-o", str(out), *argv], capsys)
        assert rc == 2 and code in err and err.count("\n") == 1, (argv, err)
    assert not out.exists()
    assert MAX_ROLLOUT_STEPS == 10_000_000


def test_rollout_blocks_are_the_rollout() -> None:
    sk = Skill.read(SKILL)
    t, f = dmp.rollout(sk, goal_scale=1.5, time_scale=1.3)
    blocks = list(dmp.rollout_blocks(sk, goal_scale=1.5, time_scale=1.3, block=97))
    assert len(blocks) == -(-t.size // 97)
    np.testing.assert_array_equal(np.concatenate([b[0] for b in blocks]), t)
    np.testing.assert_array_equal(np.concatenate([b[1] for b in blocks]), f)


# ---- the force limit ---------------------------------------------------------------------------


def test_show_flags_and_upload_refuses_a_hostile_skill(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    huge = hostile(tmp_path, 1e30)
    rc, out, err = run(["show", str(huge)], capsys)
    assert rc == 0 and "REFUSED" in out and ("not finite" in out or "above the force limit" in out)
    big = hostile(tmp_path, 20.0)
    rc, out, err = run(["show", str(big)], capsys)
    assert rc == 0 and "REFUSED" in out and "above the force limit 50 N" in out
    rc, out, err = run(["show", str(SKILL)], capsys)
    assert rc == 0 and "REFUSED" not in out and "goal scale up to" in out
    # upload refuses before anything is sent: the bus options point at nothing
    for p in (huge, big):
        rc, _, err = run(
            [
                "upload",
                str(p),
                "--slot",
                "1",
                "-i",
                "socketcand",
                "--bus-kwargs",
                "host=127.0.0.1",
                "port=9",
                "--timeout",
                "0.1",
            ],
            capsys,
        )
        assert rc == 2 and "[662]" in err and err.count("\n") == 1, err


def test_fit_refuses_a_skill_above_the_force_limit(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    d = synthetic.pressing(seed=2, duration_s=3.0)
    strong = write_demo(tmp_path / "strong.csv", d.__class__(d.t_s, d.pos_m, 20.0 * d.force_N, d.source))
    out = tmp_path / "s.skill"
    rc, _, err = run(fit_argv(strong, out), capsys)
    assert rc == 2 and "[662]" in err and "above the force limit 50 N" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["strong.csv"]
    rc, stdout, err = run(fit_argv(strong, out, "--force-limit", "200"), capsys)
    assert rc == 0, err
    assert "wrote" in stdout and out.is_file()


def test_run_checks_its_scales_with_the_rollout_validator_before_connecting(
    capsys: pytest.CaptureFixture[str],
) -> None:
    bus = ["-i", "socketcand", "--bus-kwargs", "host=127.0.0.1", "port=9", "--timeout", "0.1"]
    for argv in (
        ["--goal-scale", "70"],
        ["--goal-scale", "-0.5"],
        ["--time-scale", "0"],
        ["--time-scale", "inf"],
    ):
        rc, _, err = run(["run", "--slot", "1", *argv, *bus], capsys)
        assert rc == 2 and "[109]" in err, (argv, err)
        with pytest.raises(FsError) as e:
            dmp.rollout(
                Skill.read(SKILL),
                goal_scale=float(argv[1]) if "goal" in argv[0] else 1.0,
                time_scale=float(argv[1]) if "time" in argv[0] else 1.0,
            )
        assert e.value.code == 109
