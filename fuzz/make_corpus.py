#!/usr/bin/env python3
"""Write the seed corpus of every fuzz harness into fuzz/corpus/<harness>/ (deterministic;
re-run after a format change). Skill images come from tests/vectors (written by the Python
package); storage records are built here with zlib's CRC-32, following docs/safety.md."""
import pathlib
import shutil
import struct
import zlib

HERE = pathlib.Path(__file__).resolve().parent
VEC = HERE.parent / "tests" / "vectors"
C = HERE / "corpus"


def out(harness, name, data):
    d = C / harness
    d.mkdir(parents=True, exist_ok=True)
    (d / name).write_bytes(bytes(data))


# skill_parse: small golden images (valid) and the rejected ones of tests/vectors/bad
for name in ["press_n10_lwr_hold.skill", "engrave_n10_ridge_release.skill",
             "press_n50_lwr_hold.skill"]:
    out("skill_parse", name, (VEC / name).read_bytes())
for p in sorted((VEC / "bad").glob("*.skill")):
    if p.stat().st_size <= 2000:
        out("skill_parse", "bad_" + p.name, p.read_bytes())

# nvm_record: records as nvm.c writes them (write unit 4)
MAGIC, VERSION, COMMIT = 0x524D564E, 1, 0x00C0FFEE


def record(slot, seq, payload, commit=True):
    hdr = struct.pack("<IHHII", MAGIC, VERSION, slot, seq, len(payload))
    crc = zlib.crc32(payload, zlib.crc32(hdr)) & 0xFFFFFFFF
    hdr += struct.pack("<I", crc) + b"\xff" * 12
    pad = (-len(payload)) % 4
    body = hdr + payload + b"\xff" * pad
    return body + (struct.pack("<I", COMMIT) if commit else b"\xff" * 4)


SECTOR = 512
small = (VEC / "press_n10_lwr_hold.skill").read_bytes()
out("nvm_record", "valid_small", record(0, 1, b"hello, slot"))
out("nvm_record", "valid_skill", record(0, 7, small))
out("nvm_record", "uncommitted", record(0, 2, b"interrupted", commit=False))
out("nvm_record", "empty_payload", record(0, 3, b""))
img = bytearray(b"\xff" * (4 * SECTOR))
a = record(0, 5, b"older copy A")
b = record(0, 6, b"newer copy B")
c = record(1, 1, small[:200])
img[0:len(a)] = a
img[SECTOR:SECTOR + len(b)] = b
img[2 * SECTOR:2 * SECTOR + len(c)] = c
out("nvm_record", "flash_two_slots", img)

# isotp: [bs, stmin] then steps: ctl byte (low 3 bits: 0/1 frame for us, 2 foreign, 3 read,
# 4 send, else poll; high 5 bits: time step), frame = dlc + bytes
def frame(ctl, data):
    return bytes([ctl, len(data)]) + bytes(data)


sf = b"\x00\x00" + frame(0x08, [0x02, 0x10, 0x03, 0xCC, 0xCC, 0xCC, 0xCC, 0xCC]) + b"\x03"
out("isotp", "single_frame", sf)
ff = [0x10, 0x14] + list(range(6))
seq = b"\x00\x00" + frame(0x08, ff)
for sn in range(1, 3):
    seq += frame(0x08, [0x20 | sn] + list(range(7)))
seq += b"\x03"
out("isotp", "multi_frame", seq)
tx = b"\x08\x01" + bytes([0x0C, 0x01, 0x00]) + frame(0x08, [0x30, 0x02, 0x00, 0, 0, 0, 0, 0]) + b"\x0d\x0d\x0d"
out("isotp", "send_with_fc", tx)

# uds: length-prefixed requests
def reqs(*rs):
    return b"".join(bytes([len(r)]) + bytes(r) for r in rs)


out("uds", "session_seed_key", reqs([0x10, 0x03], [0x27, 0x01], [0x27, 0x02] + [0x42] * 16))
out("uds", "read_did", reqs([0x22, 0xF1, 0x90], [0x3E, 0x00], [0x3E, 0x80]))
out("uds", "routine", reqs([0x10, 0x03], [0x31, 0x01, 0x02, 0x03], [0x31, 0x03, 0x02, 0x03]))
out("uds", "download", reqs([0x10, 0x02], [0x27, 0x01], [0x27, 0x02] + [0x42] * 16,
                              [0x34, 0x00, 0x44, 0, 0, 0, 1, 0, 0, 0, 0x10],
                              [0x36, 0x01] + [0xAB] * 16, [0x37]))
out("uds", "upload", reqs([0x10, 0x02], [0x35, 0x00, 0x44, 0, 0, 0, 1, 0, 0, 0, 0x20],
                          [0x36, 0x01], [0x36, 0x02], [0x37], [0x11, 0x01]))

# frames: protected 8-byte frames and a short one
out("frames", "heartbeat", bytes([0x10, 0x81, 1, 2, 3, 4, 5, 6, 0x05, 0x00]))
out("frames", "command", bytes([0x00, 0x81, 0x02, 0x01, 0xE8, 0x03, 0xE8, 0x03, 0x01, 0x00]) * 2)
out("frames", "short", bytes([0x01, 0x02, 0x03]))

# app: operation sequences of fuzz_app.c (op byte, then its arguments; see the harness)
TICKS, RAW, CMD, HB, UDS, SEC, SKILL, FW, SENS, BUSOFF, POWER, FWUPDATE, RUN = range(13)
SESSION, ACMD, AHB, REPLAY = range(13, 17)  # the harness's host session and its frames


def app_cmd(mode, slot=1, goal=1000, time_scale=1000):
    return bytes([CMD, mode, slot, goal & 0xFF, goal >> 8, time_scale & 0xFF, time_scale >> 8])


def wait(ms):
    return bytes([TICKS, min(ms, 256) - 1]) * max(1, ms // 256)


upload = wait(1100) + bytes([SEC, 1]) + bytes([SKILL, 0, 0, 1, 200])      # slot 1, CRC kept
out("app", "upload_run", upload + bytes([HB, 0, RUN, 1, 0x03, 0xE8, 0x03, 0xE8])
    + (bytes([HB, 0]) + wait(20)) * 40)
out("app", "upload_run_over_limit", upload + bytes([HB, 0, RUN, 1, 0x4E, 0x20, 0x03, 0xE8]) + wait(50))
out("app", "upload_then_cmd_execute", upload + app_cmd(3) + (bytes([HB, 0]) + wait(20)) * 30
    + app_cmd(1) + wait(10))
out("app", "teach_silence_clear", app_cmd(2) + bytes([HB, 0]) + wait(300) + bytes([HB, 0])
    + app_cmd(4) + wait(20))
out("app", "mutated_upload", wait(1100) + bytes([SEC, 1, SKILL, 2, 2, 1, 50, 130, 0x40, 140, 0x7F]))
out("app", "cut_upload_erase", wait(1100) + bytes([SEC, 1, SKILL, 0, 0, 3, 100])
    + bytes([UDS, 4, 0x31, 0x01, 0xFF, 0x00, 0x01]) + wait(10))
out("app", "fw_download", wait(1100) + bytes([SEC, 3, FW, 0]) + b"FSFW" + bytes(300))
out("app", "wrong_keys_reset", wait(1100) + bytes([SEC, 5, TICKS, 255, SEC, 5, POWER, SEC, 5]) + wait(1100))
out("app", "sensors_nan", app_cmd(2) + bytes([HB, 0, SENS]) + struct.pack("<fff", float("nan"), 1.0, 2.0)
    + wait(100))
out("app", "bus_off_execute", upload + bytes([HB, 0, RUN, 1, 0x03, 0xE8, 0x03, 0xE8, BUSOFF]) + wait(100))
out("app", "fw_update_confirm_then_revert", bytes([FWUPDATE, 0]) + wait(256)
    + bytes([FWUPDATE, 2]) + wait(600) + bytes([UDS, 3, 0x31, 0x01, 0x0F, 0x02]))


def auth_cmd(mode, slot=1, goal=1000, time_scale=1000):
    return bytes([ACMD, mode, slot, goal & 0xFF, goal >> 8, time_scale & 0xFF, time_scale >> 8])


out("app", "authentic_teach_execute_replay", upload + bytes([SESSION, AHB, 0]) + auth_cmd(2)
    + (bytes([AHB, 0]) + wait(10)) * 5 + bytes([REPLAY]) + auth_cmd(1) + auth_cmd(5) + auth_cmd(3)
    + (bytes([AHB, 0]) + wait(10)) * 20 + bytes([REPLAY, REPLAY]) + app_cmd(3) + auth_cmd(1))
out("app", "forged_after_session", upload + bytes([SESSION]) + app_cmd(2) + app_cmd(5) + app_cmd(3)
    + bytes([HB, 0, REPLAY]) + wait(20) + bytes([POWER]) + auth_cmd(2) + wait(20))
print("corpus written to", C)
