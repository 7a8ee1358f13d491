#!/usr/bin/env bash
# Comments and docs speak of the code itself: fail on a reference to a numbered section of the
# specification or a numbered tracker entry (the pattern below) anywhere in the tree's sources and docs.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
if git grep --untracked -n -I -E '\bSPEC ?[0-9]|\bSPEC section|\b[Ii]ssue ?#?[0-9]' -- . ':!tools/check_no_tracker_refs.sh'; then
    echo "check_no_tracker_refs: the lines above cite the specification or an issue by number;" \
         "say what the code does instead" >&2
    exit 1
fi
echo "no references to SPEC or issue numbers"
