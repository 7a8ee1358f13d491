"""Firmware update over the simulator's socketcand bus with udsoncan (HIL), through the
app integration of docs/update.md section 8 in hil_sim.

`forceskill flash` against `hil_sim serve`: full update in 4,093-byte blocks (the device's
maximum), ECUReset answered before the restart, the first request of each connection answered,
revert when the new image fails its self-test, each refusal with its own NRC, skills kept byte
for byte across updates."""

from __future__ import annotations

import argparse
import os
import subprocess
from pathlib import Path

import pytest

from forceskill import cli
from forceskill.errors import FsError
from forceskill.link import flash as fl
from forceskill.model import fwimage as fw
from helpers.canbus import socketcand_args

REPO = Path(__file__).resolve().parents[2]
SKILL = REPO / "tests" / "vectors" / "engrave_n10_lwr_hold.skill"


def hil_sim() -> Path:
    p = Path(os.environ.get("FORCESKILL_HIL_SIM", str(REPO / "build" / "hil_sim" / "hil_sim")))
    assert p.is_file(), f"hil_sim not built at {p} (set FORCESKILL_HIL_SIM)"
    return p


@pytest.fixture(scope="module")
def sim():
    proc = subprocess.Popen(
        [str(hil_sim()), "serve", "--port", "0", "--host-timeout", "500"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    line = proc.stdout.readline()
    assert "listening on 127.0.0.1:" in line, line
    port = int(line.split("127.0.0.1:")[1].split()[0])
    yield [*socketcand_args(port), "--timeout", "3"]
    proc.terminate()
    proc.communicate(timeout=10)


def image(tmp: Path, name: str, version: str, payload: bytes, key: bytes = fw.DEV_KEY) -> str:
    p = tmp / f"{name}.fwimg"
    p.write_bytes(fw.build_image(payload, version, "host", key, build_id=name))
    return str(p)


def flash(capsys, path: str, bus: list[str], *extra: str) -> tuple[int, str, str]:
    # the device's maximum block: 4,093 bytes per TransferData (4,095-byte ISO-TP requests)
    rc = cli.main(["flash", path, *bus, "-q", *extra])
    out = capsys.readouterr()
    return rc, out.out, out.err


def slot1(capsys, bus) -> str:
    assert cli.main(["status", *bus]) == 0
    return next(ln for ln in capsys.readouterr().out.splitlines() if ln.strip().startswith("slot 1:"))


def test_update_revert_refusals_and_skills_kept(sim, tmp_path, capsys):
    payload = os.urandom(50000)
    assert cli.main(["upload", str(SKILL), "--slot", "1", "-q", *sim]) == 0
    capsys.readouterr()
    before = slot1(capsys, sim)
    assert "empty" not in before

    rc, out, err = flash(capsys, image(tmp_path, "v1", "1.0.0", payload), sim)
    assert rc == 0, err
    assert "after reset: device: firmware 1.0.0 on host, slot A" in out
    rc, out, err = flash(capsys, image(tmp_path, "v11", "1.1.0", payload[::-1]), sim)
    assert rc == 0, err
    assert "after reset: device: firmware 1.1.0 on host, slot B" in out
    assert slot1(capsys, sim) == before  # the skill survived both updates

    # a build whose self-test fails: booted once, not confirmed, reverted
    bad = b"FSHOST-SELFTEST-FAIL" + payload[:20000]
    rc, out, err = flash(capsys, image(tmp_path, "bad", "1.2.0", bad), sim)
    assert rc == 2 and "device reverted to 1.1.0" in err and "[638]" in err, err

    # refusals, each with its own code, straight to the device
    ns = argparse.Namespace(
        interface="socketcand",
        channel="can0",
        bus_kwargs={"host": "127.0.0.1", "port": int(sim[6].split("=")[1])},
        node=0,
        timeout=3.0,
    )
    from forceskill.link.uds import device_secret

    cases = [
        (fw.build_image(payload, "1.3.0", "host", bytes(32)), 0xF4),
        (fw.build_image(payload, "1.3.0", "cortex-m4f", fw.DEV_KEY), 0xF1),
        (fw.build_image(payload, "1.3.0", "host", fw.DEV_KEY)[:-1000], 0xF2),
        (fw.build_image(payload, "0.9.0", "host", fw.DEV_KEY), 0xF5),
    ]
    for img, nrc in cases:
        with fl.Link(ns, device_secret(3)) as client:
            assert fl.read_status(client).version == "1.1.0"  # the first request is answered
            with pytest.raises(FsError) as e:
                fl.flash_image(client, img)
            assert f"NRC 0x{nrc:02X}" in str(e.value), str(e.value)
            st = fl.read_status(client)
            assert st.version == "1.1.0" and not st.on_test
    assert slot1(capsys, sim) == before


def test_keyless_confirm_across_reset_cannot_keep_failing_image(sim, tmp_path, capsys):
    """Another node without a key repeats RoutineControl 0x0F02 (confirm firmware) every 2 ms
    from just before the ECUReset until well after it: the failing test image still reverts."""
    import threading
    import time

    import can

    from forceskill.link.uds import device_secret

    port = int(sim[6].split("=")[1])
    # an active image to revert to (the test above leaves 1.1.0; run alone, the device has none,
    # and the bootloader then adopts the only image that verifies: the reverted one, "recovered")
    ns = argparse.Namespace(
        interface="socketcand",
        channel="can0",
        bus_kwargs={"host": "127.0.0.1", "port": port},
        node=0,
        timeout=3.0,
    )
    with fl.Link(ns, device_secret(3)) as client:
        has_active = fl.read_status(client).running_slot != 0xFF
    if not has_active:
        rc, _, err = flash(capsys, image(tmp_path, "good", "1.0.0", os.urandom(20000)), sim)
        assert rc == 0, err
    payload = os.urandom(30000)
    with fl.Link(ns, device_secret(3)) as client:
        running = fl.read_status(client)
        img = fw.build_image(b"FSHOST-SELFTEST-FAIL" + payload, "9.0.0", "host", fw.DEV_KEY)
        fl.flash_image(client, img)
        stop = threading.Event()
        sent = [0]

        def hostile() -> None:
            with can.Bus(interface="socketcand", host="127.0.0.1", port=port, channel="can0") as bus:
                msg = can.Message(
                    arbitration_id=0x600,
                    is_extended_id=False,
                    data=[0x04, 0x31, 0x01, 0x0F, 0x02, 0xCC, 0xCC, 0xCC],
                )
                while not stop.is_set():
                    bus.send(msg)
                    sent[0] += 1
                    stop.wait(0.002)

        t = threading.Thread(target=hostile, daemon=True)
        t.start()
        try:
            time.sleep(0.2)
            try:
                client.ecu_reset(1)
            except Exception:  # the hostile node's answers share the response id
                pass
            time.sleep(1.0)
        finally:
            stop.set()
            t.join(timeout=5)
        assert sent[0] > 100
        time.sleep(0.3)
        st = fl.read_status(client)
    assert st.running_version == running.running_version and not st.on_test, st.describe()
    assert st.path in (3, 4), st.describe()  # reverted
