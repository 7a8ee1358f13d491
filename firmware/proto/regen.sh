#!/bin/sh
# Regenerate the C pack/unpack code from the DBC (the single source of truth).
# Usage: firmware/proto/regen.sh [PYTHON_VENV_BIN]   (default: .venv/bin of the repo)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:-$here/../../.venv/bin}
"$bin/cantools" generate_c_source --database-name fs_dbc --use-round \
    -o "$here/generated" "$here/forceskill.dbc"
