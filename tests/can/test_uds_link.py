"""UDS over ISO-TP through `hil_sim serve` at the sizes and moments that used to fail:
skill images of 2.5 and 4.9 KB (ISO-TP messages up to 4095 bytes, ~590 frames sent in one burst),
the first request on a freshly opened socketcand connection, and ECUReset's positive response
(ISO 14229-1: sent before the reset)."""

from __future__ import annotations

import struct
import time
import zlib

import can
import pytest
import udsoncan
from udsoncan.exceptions import NegativeResponseException

from forceskill import cli
from forceskill.commands._common import connect
from forceskill.link import uds as U
from forceskill.model.fit import fit
from forceskill.model.synthetic import pressing


@pytest.mark.parametrize("n_kernels,slot", [(100, 5), (200, 6)])
def test_upload_large_skill_read_back(server, tmp_path, capsys, n_kernels, slot):
    """`forceskill upload` of N = 100 (2,540 B: one 2.5 KB TransferData) and N = 200 (4,940 B:
    a 4,095-byte ISO-TP request, then the rest), read back with RequestUpload and compared."""
    image = fit(
        pressing(seed=5, duration_s=8.0), 100.0, n_kernels=n_kernels, surface_m=0.001
    ).skill.to_bytes()
    assert len(image) == 140 + 24 * n_kernels
    path = tmp_path / f"n{n_kernels}.skill"
    path.write_bytes(image)
    rc = cli.main(["upload", str(path), "--slot", str(slot), "-q", *server.bus_args()])
    out, err = capsys.readouterr()
    assert rc == 0, err
    assert f"N = {n_kernels}" in out and "verified by read-back" in out
    with connect(server.namespace()) as dev, U.uds_client(dev) as client:
        U.unlock(client, 0, 0x02)
        assert U.upload(client, 0, slot, len(image)) == image
        d = U.slot_directory(client, 0)[slot - 1]
        client.change_session(0x01)
    assert d["valid"] and d["length"] == len(image) and d["n_kernels"] == n_kernels
    assert d["crc32"] == struct.unpack("<I", image[-4:])[0] == zlib.crc32(image[:-4])


def _first_frame_answered(port: int) -> bool:
    """Open a fresh socketcand connection and send TesterPresent (ISO-TP single frame) as its
    very first frame, without waiting for any frame of the device; True if 7E 00 comes back."""
    bus = can.Bus(interface="socketcand", host="127.0.0.1", port=port, channel="can0")
    try:
        bus.send(
            can.Message(
                arbitration_id=U.UDS_REQUEST_BASE,
                is_extended_id=False,
                data=[0x02, 0x3E, 0x00, 0xCC, 0xCC, 0xCC, 0xCC, 0xCC],
            )
        )
        end = time.monotonic() + 3.0  # suited to a loaded CI machine; answered in ~ms
        while time.monotonic() < end:
            m = bus.recv(0.1)
            if m is not None and m.arbitration_id == U.UDS_RESPONSE_BASE:
                return bytes(m.data[:3]) == b"\x02\x7e\x00"
        return False
    finally:
        bus.shutdown()


def test_first_request_on_fresh_connection(server):
    """50 fresh connections, each sends one UDS TesterPresent as its first frame: all answered."""
    answered = [_first_frame_answered(server.port) for _ in range(50)]
    assert sum(answered) == 50, f"{answered.count(False)} of 50 first requests got no answer"


def test_ecu_reset_positive_response(server):
    """ECUReset (hard) gets its positive response 51 01, then the device restarts: it comes back
    in the default session (programming session and security gone) with its skills."""
    with connect(server.namespace()) as dev, U.uds_client(dev) as client:
        before = U.slot_directory(client, 0)
        U.unlock(client, 0, 0x02)
        r = client.ecu_reset(0x01)
        assert r.positive and r.service_data.reset_type_echo == 0x01
        # restarted: a request of the programming session is refused in the default one
        time.sleep(0.1)
        with pytest.raises(NegativeResponseException) as e:
            client.request_download(
                udsoncan.MemoryLocation(address=7, memorysize=200, address_format=8, memorysize_format=16)
            )
        assert e.value.response.code == 0x7F  # serviceNotSupportedInActiveSession
        assert U.slot_directory(client, 0) == before


def test_security_levels_over_the_bus(server, tmp_path):
    """udsoncan against the simulator: firmware confirm (0x0F02) is refused without level 3
    (0x33) in the default session and with level 1; level 3 (its own secret) does not open
    settings or skill slots (0x33); level 1 still does."""
    image = fit(pressing(seed=5, duration_s=3.0), 100.0, n_kernels=20, surface_m=0.001).skill.to_bytes()
    with connect(server.namespace()) as dev, U.uds_client(dev) as client:
        client.change_session(0x01)
        for session in (0x01, 0x02):
            if session == 0x02:
                U.unlock(client, 0, 0x02)
            with pytest.raises(NegativeResponseException) as e:
                client.start_routine(0x0F02)
            assert e.value.response.code == 0x33
        client.change_session(0x01)
        client.change_session(0x02)
        end = time.monotonic() + 15.0
        while True:
            try:
                client.unlock_security_access(U.SEC_LEVEL_FIRMWARE)
                break
            except NegativeResponseException as e:
                assert e.value.response.code == 0x37 and time.monotonic() < end
                time.sleep(0.2)
        with pytest.raises(NegativeResponseException) as e:
            client.start_routine(U.RID_ERASE_SLOT, bytes([3]))
        assert e.value.response.code == 0x33
        with pytest.raises(NegativeResponseException) as e:
            client.request_download(
                udsoncan.MemoryLocation(
                    address=3, memorysize=len(image), address_format=8, memorysize_format=16
                )
            )
        assert e.value.response.code == 0x33
        client.change_session(0x01)
        U.unlock(client, 0, 0x02)
        U.download(client, 0, 3, image)
        assert U.slot_directory(client, 0)[2]["valid"]
        client.change_session(0x01)
