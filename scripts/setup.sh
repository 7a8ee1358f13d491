#!/usr/bin/env bash
# Set up everything forceskill needs on a fresh Debian/Ubuntu machine: apt packages, a Python
# venv in .venv with the host package, and a Release build of firmware + simulator in build/.
# Idempotent: re-running only does what is missing. Used by demo.sh and test.sh.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"

APT_PACKAGES=(build-essential cmake ninja-build python3-venv python3-dev
  libcmocka-dev libsocketcan-dev
  gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm
  clang libclang-rt-14-dev clang-format cppcheck)

missing=()
for p in "${APT_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "== installing apt packages: ${missing[*]}"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi

PY="${PYTHON:-python3}"
if [ ! -x .venv/bin/python ]; then
  echo "== creating .venv"
  "$PY" -m venv .venv
fi
if ! .venv/bin/python -c "import forceskill" 2>/dev/null || [ host/pyproject.toml -nt .venv/.forceskill-installed ]; then
  echo "== installing the host package (pip install -e host[dev])"
  .venv/bin/pip install -q --upgrade pip
  .venv/bin/pip install -q -e "host[dev]"
  touch .venv/.forceskill-installed
fi

echo "== building (Release) in build/ (preset host-release)"
cmake --preset host-release >/dev/null
cmake --build --preset host-release -j "$(nproc)"
