"""The float32 libraries export only _f32 symbols (so they link beside the double ones): nm over
each library; every defined global symbol must end in _f32.
usage: check_f32_symbols.py NM LIBRARY..."""

import subprocess
import sys


def main(nm: str, libs: list[str]) -> int:
    bad = []
    n = 0
    for lib in libs:
        out = subprocess.run(
            [nm, "-g", "--defined-only", lib], check=True, capture_output=True, text=True
        ).stdout
        for line in out.splitlines():
            parts = line.split()
            if len(parts) == 3 and parts[1] in "TDBRC":
                n += 1
                if not parts[2].endswith("_f32"):
                    bad.append(f"{lib}: {parts[2]}")
    for b in bad:
        print(f"not renamed (add it to a header tools/gen_f32_names.py reads): {b}")
    print(f"{n} exported symbols, {len(bad)} without _f32")
    return 1 if bad or n == 0 else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2:]))
