#!/usr/bin/env bash
# The main job, end to end on the HIL simulator:
#  1. over CAN (python-can socketcand client only): demonstrate -> record .blf -> fit -> upload
#     (UDS) -> execute at goal 1x and 1.5x -> report         => report/can/can_report.md
#  2. every paper experiment (pressing, engraving, reuse with goal scaling), lockstep
#                                                              => report/paper/report.md
#   scripts/demo.sh [--target cortex-m4f|cortex-m3] [OUT]
# --target: step 1 runs against the product's Cortex-M image under qemu (hil_sim pil, python-can's
# slcan interface) instead of the simulator's host build; the image is built first.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
TARGET=host
if [ "${1:-}" = "--target" ]; then
  TARGET="${2:-}"; shift 2 || true
  case $TARGET in
    cortex-m4f|cortex-m3) ;;
    *) echo "demo.sh: --target must be cortex-m4f or cortex-m3" >&2; exit 2 ;;
  esac
fi
"$ROOT/scripts/setup.sh"
cd "$ROOT"
OUT="${1:-report}"
if [ "$TARGET" = host ]; then
  echo "== 1/2: the journey over CAN against the simulator"
else
  echo "== 1/2: the journey over CAN against the $TARGET image under qemu"
  cmake -S . -B "build/$TARGET" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$ROOT/cmake/arm-none-eabi.cmake" \
        -DFS_CORTEX_TARGET="$TARGET" -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE="$ROOT/.venv/bin/python" >/dev/null
  cmake --build "build/$TARGET" --target fs_pil | grep -E '^(size|heap|stack)' || true
fi
.venv/bin/forceskill journey -o "$OUT/can" --hil-sim build/hil_sim/hil_sim --target "$TARGET" \
  $([ "$TARGET" = host ] || echo "--host-timeout 500")
echo "== 2/2: the paper's experiments"
.venv/bin/forceskill report -o "$OUT/paper" --hil-sim build/hil_sim/hil_sim
echo "== done: $OUT/can/can_report.md and $OUT/paper/report.md (figures beside them)"
