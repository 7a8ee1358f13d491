#!/usr/bin/env bash
# Every test: one tick implementation (scripts/check_one_tick.sh), C unit tests under ASan+UBSan (Debug build, preset host-debug), the static checks, the Cortex-M images
# under qemu (bench/qemu_tick.sh: budgets, qemu vs host, no heap/recursion, stack per entry point),
# then the Python, HIL and CAN tests against the Release build, and a subset again in .venv-min
# (every dependency at its lowest allowed version, scripts/min_venv.sh). Exit status is non-zero if
# anything fails.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$ROOT/scripts/setup.sh"
cd "$ROOT"

echo "== generated files agree with their sources (codes.toml -> headers, codes.py, docs/codes.md;"
echo "   public headers -> the _f32 rename headers)"
.venv/bin/python tools/gen_codes.py --check
.venv/bin/python tools/gen_f32_names.py --check
echo "== comments and docs cite no SPEC or issue numbers"
tools/check_no_tracker_refs.sh
echo "== one implementation of the control tick (scripts/check_one_tick.sh)"
scripts/check_one_tick.sh
echo "== layers: no upward or sideways include or host import, no cycle (tools/check_layers.py)"
.venv/bin/python tools/check_layers.py
echo "== Python: ruff (lint, format) on host/forceskill, tests/, tools/ and bench/, mypy (strict) on"
echo "   host/forceskill (configuration: host/pyproject.toml)"
.venv/bin/ruff check --config host/pyproject.toml host/forceskill tests tools bench
.venv/bin/ruff format --config host/pyproject.toml --check host/forceskill tests tools bench
(cd host && ../.venv/bin/mypy)

echo "== C tests (Debug: ASan + UBSan; preset host-debug, build/host-debug)"
cmake --preset host-debug >/dev/null
cmake --build --preset host-debug -j "$(nproc)"
ctest --preset host-debug -j "$(nproc)"

echo "== the firmware libraries as a consumer sees them: cmake --install, find_package, add_subdirectory, pkg-config"
tests/consumer/run.sh build/consumer

echo "== static checks (cppcheck; MISRA addon findings counted, not fatal)"
tools/static_check.sh build/host-debug/static

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

echo "== clang-format: firmware/ and hil_sim/ match .clang-format (generated code excluded)"
tools/check_format.sh
echo "== the host package at the lowest dependency versions pyproject.toml allows (.venv-min):"
echo "   host CLI tests and the CAN journey"
scripts/min_venv.sh
