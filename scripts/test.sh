#!/usr/bin/env bash
# Every test: C unit tests under ASan+UBSan (Debug build), the static checks, the Cortex-M images
# under qemu (bench/qemu_tick.sh: the product image's tick counted per state, no heap/recursion,
# size and stack per entry point), then the Python, HIL and CAN tests against the Release build
# (tests/can/test_pil.py: the journey against the Cortex-M4F image built by the step before).
# Exit status is non-zero if anything fails.
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

echo "== Cortex-M images under qemu (M4F, M3): the product image's app_tick counted per state,"
echo "   DMP + control law within budget, no heap, no recursion, size, worst stack per entry point"
for target in cortex-m4f cortex-m3; do
  log="build/qemu_tick_$target.log"
  if ! bench/qemu_tick.sh "$target" >"$log" 2>&1; then
    cat "$log"; echo "qemu benchmark failed for $target (log: $log)" >&2; exit 1
  fi
  grep -E '^(size|heap|stack|tick_instructions|app_tick_instructions|budget|counter check)' "$log" || true
done

echo "== Python, HIL and CAN tests"
export FORCESKILL_HIL_SIM="$ROOT/build/hil_sim/hil_sim"
.venv/bin/python -m pytest -q tests
