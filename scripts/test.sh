#!/usr/bin/env bash
# Every test: C unit tests under ASan+UBSan (Debug build), the static checks, the Cortex-M images
# under qemu (bench/qemu_tick.sh: budgets, qemu vs host, no heap/recursion, stack per entry point),
# then the Python, HIL and CAN tests against the Release build, and a subset again in .venv-min
# (every dependency at its lowest allowed version, scripts/min_venv.sh). Exit status is non-zero if
# anything fails.
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

echo "== Cortex-M images under qemu (M4F float, M3 fixed): instructions per tick within budget,"
echo "   qemu output vs the host build, no heap, no recursion, worst stack per entry point"
for target in cortex-m4f cortex-m3; do
  log="build/qemu_tick_$target.log"
  if ! bench/qemu_tick.sh "$target" >"$log" 2>&1; then
    cat "$log"; echo "qemu benchmark failed for $target (log: $log)" >&2; exit 1
  fi
  grep -E '^(size|heap|stack|tick_instructions|budget|qemu_vs|loop|counter check)' "$log" || true
done

echo "== Python, HIL and CAN tests"
export FORCESKILL_HIL_SIM="$ROOT/build/hil_sim/hil_sim"
.venv/bin/python -m pytest -q tests

echo "== the host package at the lowest dependency versions pyproject.toml allows (.venv-min):"
echo "   host CLI tests and the CAN journey"
scripts/min_venv.sh
