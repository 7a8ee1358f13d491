"""The generated C and the DBC agree: for every message, random raw signal values packed by the
generated C equal cantools' encoding, and the C unpack/decode of random bytes equals cantools'
decoding (raw and physical). Run by ctest with the harness path: check_dbc.py HARNESS DBC."""

import random
import subprocess
import sys

import cantools

ROUNDS = 2000


def main(harness: str, dbc_path: str) -> int:
    db = cantools.database.load_file(dbc_path, strict=True)
    proc = subprocess.Popen([harness], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)

    def ask(line: str) -> str:
        proc.stdin.write(line + "\n")
        proc.stdin.flush()
        out = proc.stdout.readline().strip()
        assert out != "error", f"harness refused: {line}"
        return out

    proc.stdin.write("list\n")
    proc.stdin.flush()
    layout = {}
    for _ in db.messages:
        parts = proc.stdout.readline().split()
        layout[parts[0]] = (int(parts[1]), parts[2:])
    names = {m.name for m in db.messages}
    assert set(layout) == names, f"harness messages {sorted(layout)} != DBC {sorted(names)}"
    rng = random.Random(4)
    checked = 0
    for msg in db.messages:
        frame_id, signals = layout[msg.name]
        assert frame_id == msg.frame_id, f"{msg.name}: C id {frame_id:#x} != DBC {msg.frame_id:#x}"
        assert sorted(signals) == sorted(s.name for s in msg.signals), msg.name
        mux = next((s for s in msg.signals if s.is_multiplexer), None)
        mux_ids = sorted({i for s in msg.signals for i in (s.multiplexer_ids or [])} | {0, 1, 2, 4})
        for _ in range(ROUNDS):
            raw = {}
            sel = rng.choice(mux_ids) if mux is not None else None
            for s in msg.signals:
                lo = -(1 << (s.length - 1)) if s.is_signed else 0
                hi = (1 << (s.length - 1)) - 1 if s.is_signed else (1 << s.length) - 1
                raw[s.name] = rng.randint(lo, hi)
                if s.multiplexer_ids is not None and sel not in s.multiplexer_ids:
                    raw[s.name] = 0  # a signal of another multiplexer value: not in this frame
            if mux is not None:
                raw[mux.name] = sel
            used = {
                n: v for n, v in raw.items() if msg.get_signal_by_name(n).multiplexer_ids in (None, [sel])
            }
            expected = msg.encode(used, scaling=False, strict=False)
            got = ask("pack " + msg.name + " " + " ".join(str(raw[n]) for n in signals))
            assert bytes.fromhex(got) == expected, f"{msg.name} {raw}: C {got} != cantools {expected.hex()}"
            data = bytearray(rng.getrandbits(8) for _ in range(msg.length))
            if mux is not None:  # a multiplexer value the DBC defines (the mux is bits 0..3)
                data[0] = (data[0] & 0xF0) | sel
            data = bytes(data)
            out = ask(f"unpack {msg.name} {data.hex()}")
            raw_c, phys_c = out.split("|")
            raw_py = msg.decode(data, decode_choices=False, scaling=False)
            phys_py = msg.decode(data, decode_choices=False, scaling=True)
            for n, v in zip(signals, raw_c.split(), strict=False):
                if n not in raw_py:
                    continue
                assert int(v) == raw_py[n], f"{msg.name}.{n}: C raw {v} != cantools {raw_py[n]}"
            for n, v in zip(signals, phys_c.split(), strict=False):
                if n not in phys_py:
                    continue
                ref = float(phys_py[n])
                # decode functions compute in double; printed with 9 significant digits
                assert abs(float(v) - ref) <= 1e-8 * max(1.0, abs(ref)), (
                    f"{msg.name}.{n}: C phys {v} != cantools {ref}"
                )
            checked += 1
    proc.stdin.close()
    proc.wait()
    print(f"dbc: {len(db.messages)} messages, {checked} random pack/unpack pairs agree with cantools")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
