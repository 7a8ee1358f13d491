#!/usr/bin/env bash
# Every test: C unit tests under ASan+UBSan (Debug build), then the Python, HIL and CAN tests
# against the Release build. Exit status is non-zero if anything fails.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$ROOT/scripts/setup.sh"
cd "$ROOT"

echo "== C tests (Debug: ASan + UBSan)"
cmake -S . -B build-debug -G Ninja -DCMAKE_BUILD_TYPE=Debug -DPython3_EXECUTABLE="$ROOT/.venv/bin/python" >/dev/null
cmake --build build-debug -j "$(nproc)"
ctest --test-dir build-debug --output-on-failure -j "$(nproc)"

echo "== static checks (cppcheck; MISRA addon findings counted, not fatal)"
tools/static_check.sh build-debug/static

echo "== Python, HIL and CAN tests"
export FORCESKILL_HIL_SIM="$ROOT/build/hil_sim/hil_sim"
.venv/bin/python -m pytest -q tests
