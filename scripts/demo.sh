#!/usr/bin/env bash
# The main job, end to end on the HIL simulator: demonstrate -> log -> fit -> execute -> report.
# Output: report/report.md, report/summary.json and the figures in report/.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$ROOT/scripts/setup.sh"
cd "$ROOT"
OUT="${1:-report}"
.venv/bin/forceskill report -o "$OUT" --hil-sim build/hil_sim/hil_sim
echo "== report written to $OUT/report.md"
