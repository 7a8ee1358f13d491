#!/usr/bin/env bash
# The main job, end to end on the HIL simulator:
#  1. over CAN (python-can socketcand client only): demonstrate -> record .blf -> fit -> upload
#     (UDS) -> execute at goal 1x and 1.5x -> report         => report/can/can_report.md
#  2. every paper experiment (pressing, engraving, reuse with goal scaling), lockstep
#                                                              => report/paper/report.md
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$ROOT/scripts/setup.sh"
cd "$ROOT"
OUT="${1:-report}"
echo "== 1/2: the journey over CAN against the simulator"
.venv/bin/forceskill journey -o "$OUT/can" --hil-sim build/hil_sim/hil_sim
echo "== 2/2: the paper's experiments"
.venv/bin/forceskill report -o "$OUT/paper" --hil-sim build/hil_sim/hil_sim
echo "== done: $OUT/can/can_report.md and $OUT/paper/report.md (figures beside them)"
