#!/usr/bin/env bash
# The host package against the lowest dependency versions host/pyproject.toml allows: a second venv
# (.venv-min) with every ">=X" bound installed as "==X" (scripts/min_versions.py), then the host
# CLI tests, the CMAC and firmware-crypto comparisons and one CAN journey test run there.
# Idempotent: the venv is rebuilt only when pyproject.toml changes. Used by scripts/test.sh.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
PY="${PYTHON:-python3}"
VENV=.venv-min
if [ ! -x "$VENV/bin/python" ] || [ host/pyproject.toml -nt "$VENV/.installed" ]; then
  rm -f "$VENV/.installed"
  pins="$("$PY" scripts/min_versions.py)"   # a separate statement: set -e stops on its failure
  echo "== $VENV with the lowest allowed versions:" $pins
  if [ ! -x "$VENV/bin/python" ]; then
    "$PY" -m venv "$VENV"
    "$VENV/bin/pip" install -q --upgrade pip
  fi
  # shellcheck disable=SC2046
  "$VENV/bin/pip" install -q --only-binary numpy,matplotlib $pins "pytest>=7"
  "$VENV/bin/pip" install -q --no-deps -e host
  touch "$VENV/.installed"
fi
"$VENV/bin/python" - <<'PY'
import importlib.metadata as md
import subprocess, sys
pins = subprocess.run([sys.executable, "scripts/min_versions.py"], capture_output=True, text=True,
                      check=True).stdout.split()
bad = [p for p in pins if md.version(p.split("==")[0]) != p.split("==")[1]
       and md.version(p.split("==")[0]) != p.split("==")[1] + ".0"]
print("installed:", ", ".join(f"{p.split('==')[0]} {md.version(p.split('==')[0])}" for p in pins))
sys.exit(f"not the lowest versions: {bad}" if bad else 0)
PY
export FORCESKILL_HIL_SIM="$ROOT/build/hil_sim/hil_sim"
"$VENV/bin/python" -m pytest -q tests/host/commands/test_cli.py tests/host/test_outputs.py \
  tests/host/wire/test_aes_cmac.py tests/host/wire/test_firmware_crypto.py \
  "tests/can/test_journey.py::test_record_fit_upload_run" "tests/can/test_journey.py::test_tracking_figures_1x_and_1_5x"
