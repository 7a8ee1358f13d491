"""Bad input on the CAN link: one line naming the problem, exit status 2, no traceback; a device
that keeps its old skill when an upload is corrupted or interrupted."""

from __future__ import annotations

import socket
import struct
import subprocess
import sys
import time

import can
import pytest

from forceskill.commands._common import connect
from forceskill.errors import FsError
from forceskill.link import uds as U
from forceskill.model.fit import fit
from forceskill.model.synthetic import pressing
from helpers.canbus import SCENARIOS, Server


def run_cli(*argv: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "forceskill", *argv], capture_output=True, text=True, timeout=60
    )


def one_line_error(p: subprocess.CompletedProcess, *needles: str) -> None:
    assert p.returncode == 2, p.stderr
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in p.stderr, p.stderr
    for n in needles:
        assert n in lines[0], lines[0]


def free_port() -> int:
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


def test_wrong_port():
    port = free_port()
    p = run_cli("status", "-i", "socketcand", "-c", "can0", "--bus-kwargs", "host=127.0.0.1", f"port={port}")
    one_line_error(p, f"127.0.0.1:{port}", "socketcand")


def test_wrong_channel(server):
    p = run_cli(
        "status", "-i", "socketcand", "-c", "can9", "--bus-kwargs", "host=127.0.0.1", f"port={server.port}"
    )
    one_line_error(p, "'can9'")


def test_wrong_interface():
    p = run_cli("status", "-i", "nosuchbus", "-c", "can0")
    one_line_error(p, "nosuchbus")


def test_device_absent(server):
    t0 = time.monotonic()
    p = run_cli("status", *server.bus_args(node=5)[:-2], "--timeout", "1")
    one_line_error(p, "no response from node 5 on can0")
    assert time.monotonic() - t0 < 10


def _image(seed: int) -> bytes:
    return fit(pressing(seed=seed, duration_s=3.0), 100.0, n_kernels=20, surface_m=0.001).skill.to_bytes()


def test_corrupted_upload_keeps_old_skill(server):
    old, new = _image(1), bytearray(_image(2))
    new[200] ^= 0x01  # the image's CRC-32 no longer matches
    with connect(server.namespace()) as dev, U.uds_client(dev) as client:
        U.unlock(client, 0, 0x02)
        U.download(client, 0, 3, old)
        with pytest.raises(FsError) as e:
            U.download(client, 0, 3, bytes(new))
        assert "status 204" in e.value.message and "keeps its previous skill" in e.value.message
        assert U.upload(client, 0, 3, len(old)) == old
        d = U.slot_directory(client, 0)[2]
        assert d["valid"] and d["crc32"] == struct.unpack("<I", old[-4:])[0]


def test_interrupted_upload_keeps_old_skill(server):
    old, new = _image(3), _image(4)
    with connect(server.namespace()) as dev, U.uds_client(dev) as client:
        U.unlock(client, 0, 0x02)
        U.download(client, 0, 4, old)
        import udsoncan

        loc = udsoncan.MemoryLocation(address=4, memorysize=len(new), address_format=8, memorysize_format=16)
        client.request_download(loc)
        client.transfer_data(1, new[:500])  # then the host goes away mid-transfer
        client.change_session(0x01)  # (session change aborts the transfer)
        assert U.last_transfer_status(client, 0) == 0xFFFE
        U.unlock(client, 0, 0x02)
        assert U.upload(client, 0, 4, len(old)) == old
        with pytest.raises(FsError, match=r"requestSequenceError|RequestSequenceError|0x24"):
            U.call("exit", client.request_transfer_exit, 0)


def test_writes_need_security(server):
    import udsoncan

    with connect(server.namespace()) as dev, U.uds_client(dev) as client:
        client.change_session(0x02)
        loc = udsoncan.MemoryLocation(address=1, memorysize=200, address_format=8, memorysize_format=16)
        with pytest.raises(FsError, match="0x33"):
            U.call("download", lambda: client.request_download(loc), 0)
        client.change_session(0x01)
        with pytest.raises(FsError, match="0x7F"):
            U.call("write", lambda: client.write_data_by_identifier(U.DID_COMM, bytes([1, 0, 100])), 0)


def test_bad_sequence_option(server):
    p = run_cli("run", "--sequence", "1:8s,x", *server.bus_args())
    one_line_error(p, "'x'")


def test_python_can_config_defaults(server, tmp_path):
    """Without -i/-c, python-can's own configuration (~/.canrc, or $CAN_INTERFACE/$CAN_CONFIG)
    supplies the bus, as for python-can's tools."""
    import os

    (tmp_path / ".canrc").write_text(
        f"[default]\ninterface = socketcand\nchannel = can0\nhost = 127.0.0.1\nport = {server.port}\n"
    )
    env = {k: v for k, v in os.environ.items() if not k.startswith("CAN_")}
    env["HOME"] = str(tmp_path)
    p = subprocess.run(
        [sys.executable, "-m", "forceskill", "status"], capture_output=True, text=True, timeout=60, env=env
    )
    assert p.returncode == 0 and "node 0 on can0 (socketcand 127.0.0.1:" in p.stdout, p.stderr
    env["HOME"] = str(tmp_path / "nowhere")
    env.update(
        {
            "CAN_INTERFACE": "socketcand",
            "CAN_CHANNEL": "can0",
            "CAN_CONFIG": f'{{"host": "127.0.0.1", "port": {server.port}}}',
        }
    )
    p = subprocess.run(
        [sys.executable, "-m", "forceskill", "status"], capture_output=True, text=True, timeout=60, env=env
    )
    assert p.returncode == 0 and "IDLE" in p.stdout, p.stderr


def test_record_refuses_unknown_log_formats_by_name(tmp_path):
    port = free_port()  # nothing listens: the format is refused before connecting
    import importlib.util

    cases = [("x.xyz", ".xyz"), ("x", "without suffix")]
    if importlib.util.find_spec("asammdf") is None:  # python-can writes .mf4 only with asammdf
        cases.append(("x.mf4", ".mf4"))
    for name, needle in cases:
        p = run_cli(
            "record",
            "-o",
            str(tmp_path / name),
            "-i",
            "socketcand",
            "--bus-kwargs",
            "host=127.0.0.1",
            f"port={port}",
            "--timeout",
            "0.2",
        )
        one_line_error(p, "[664]", needle)
    assert list(tmp_path.iterdir()) == []


def test_record_keeps_the_old_log_until_it_has_connected(tmp_path):
    old = tmp_path / "old.blf"
    old.write_bytes(b"an earlier recording")
    p = run_cli(
        "record",
        "-o",
        str(old),
        "-i",
        "socketcand",
        "--bus-kwargs",
        "host=127.0.0.1",
        f"port={free_port()}",
        "--timeout",
        "0.2",
    )
    one_line_error(p, "[630]")
    assert old.read_bytes() == b"an earlier recording"
    assert sorted(x.name for x in tmp_path.iterdir()) == ["old.blf"]


def test_record_keeps_what_it_recorded_when_the_link_drops(tmp_path):
    srv = Server(SCENARIOS / "pressing_task1_demo.toml")
    try:
        time.sleep(0.2)
        proc = subprocess.Popen(
            [
                sys.executable,
                "-m",
                "forceskill",
                "record",
                "-o",
                str(tmp_path / "d.blf"),
                "--duration",
                "30",
                *srv.bus_args(),
            ],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        assert "recording node 0" in proc.stdout.readline()
        time.sleep(1.5)
        srv.proc.kill()  # the link drops mid-recording
        srv.proc.wait()
        _, err = proc.communicate(timeout=30)
    finally:
        srv.stop()
    assert proc.returncode == 2 and len(err.strip().splitlines()) == 1 and "Traceback" not in err, err
    assert "kept what was recorded" in err
    msgs = list(can.LogReader(str(tmp_path / "d.blf")))
    assert len(msgs) > 1000  # ~1.5 s of 1 kHz telemetry
    assert sorted(x.name for x in tmp_path.iterdir()) == ["d.blf"]
