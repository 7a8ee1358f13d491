"""A firmware update as docs/update.md and docs/cli.md give it, on the simulator's device holding
a skill: `image build` of the binary the docs name (built by scripts/setup.sh) with its default
formats, `flash`, then `status` shows the version flashed; an image whose skill formats do not
cover the stored skills is refused (708) before anything is written."""

from __future__ import annotations

import re
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from forceskill import cli
from forceskill.link import uds as U
from forceskill.model import fwimage as fw
from helpers.canbus import REPO, SCENARIOS, Server

DOCS = (REPO / "docs" / "cli.md").read_text() + (REPO / "docs" / "update.md").read_text()
SKILL = REPO / "tests" / "vectors" / "press_n50_lwr_hold.skill"  # format v2, as `fit` writes it


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    rc = cli.main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


@pytest.fixture
def device() -> Iterator[Server]:
    s = Server(SCENARIOS / "pressing_task1_demo.toml")
    time.sleep(0.2)
    yield s
    s.stop()


def documented_binary() -> Path:
    m = re.search(r"forceskill image build (\S+) -o fw-1\.1\.0\.fwimg --version 1\.1\.0 --target host", DOCS)
    assert m, "docs name no binary for a host image"
    return REPO / m.group(1)


def test_the_documented_update_runs_and_status_shows_it(
    device: Server, capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    bus = device.bus_args()
    assert run(capsys, "upload", str(SKILL), "--slot", "1", "-q", *bus)[0] == 0
    binary = documented_binary()
    assert binary.is_file(), f"{binary} is not built by scripts/setup.sh"
    image = tmp_path / "fw-1.1.0.fwimg"
    rc, out, err = run(
        capsys, "image", "build", str(binary), "-o", str(image), "--version", "1.1.0", "--target", "host"
    )
    assert rc == 0, err
    assert "skill format      5 (migrates from 2)" in out  # the default covers every format fit writes
    rc, out, err = run(capsys, "flash", str(image), "-q", *bus)
    assert rc == 0, err
    assert "after reset: device: firmware 1.1.0 on host" in out and "new image confirmed" in out
    rc, out, err = run(capsys, "status", *bus)
    assert rc == 0, err
    assert out.splitlines()[1].startswith("firmware 1.1.0 (image in slot A, confirmed; build forceskill-fw ")
    assert "  slot 1: 1340 bytes" in out  # the skill survived the update


def test_an_image_that_cannot_read_the_stored_skills_is_refused_before_writing(
    device: Server, capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    bus = device.bus_args()
    assert run(capsys, "upload", str(SKILL), "--slot", "1", "-q", *bus)[0] == 0
    image = tmp_path / "fw.fwimg"
    rc, _, err = run(
        capsys, "image", "build", str(documented_binary()), "-o", str(image), "--version", "1.2.0",
        "--target", "host", "--skill-format", "4",
    )  # fmt: skip
    assert rc == 0, err
    rc, out, err = run(capsys, "flash", str(image), "-q", *bus)
    assert rc == 2 and "written" not in out
    assert err == (
        "forceskill: error: image 1.2.0 reads skill formats 4..4 but the device stores skills of formats "
        "2..5 (it would refuse the image, 708): build it with --skill-format 5:2; nothing written [708]\n"
    )
    # nothing was received: the update phase is idle, the device still runs its own build
    import can

    from forceskill.link.flash import DeviceStatus

    b = can.Bus(interface="socketcand", channel="can0", host="127.0.0.1", port=device.port)
    try:
        from forceskill.link.device import Device

        with Device(b, node=0) as dev, U.uds_client(dev) as client:
            st = DeviceStatus.decode(U.read_did(client, U.DID_FWU_STATUS, 0))
    finally:
        b.shutdown()
    assert st.phase == 0 and st.received_version == 0 and st.running_slot > 1


def test_docs_and_code_name_the_same_secret_variable() -> None:
    assert "$FORCESKILL_FW_SECRET" in DOCS and "$FORCESKILL_SECRET`, else the" not in DOCS
    assert "FORCESKILL_FW_SECRET" in Path(U.__file__).read_text()
    # the default skill formats the docs state are those image build uses
    assert f"skills `{fw.SKILL_FORMAT}:{fw.SKILL_FORMAT_OLDEST}`" in DOCS
