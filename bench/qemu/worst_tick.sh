#!/usr/bin/env bash
# The functions that dominate the worst tick of each state of the Cortex-M image under qemu:
# runs bench/qemu_tick.sh with its per-function profile (QEMU_TICK_PROFILE) and prints, per
# state, the largest tick's instructions and its top functions (instructions executed with that
# symbol, callees apart), e.g.
#   worst_tick state=UPLOAD total=30839
#     12345  41.1%  skill_crc32_f32
# usage: bench/qemu/worst_tick.sh TARGET [--top N] [--focus REGEX] [qemu_tick.sh options...]
#   TARGET cortex-m4f | cortex-m3; --top N functions per state (default 8); --focus REGEX: also,
#   per state, the tick where the functions matching REGEX ran the most instructions and those
#   functions (worst_focus lines; e.g. the skill store and storage: '^(slots_|nvm_|skill_)');
#   the other options go to bench/qemu_tick.sh (--fw-bytes 4096, --skill FILE, ...). Its own
#   output is printed too.
set -euo pipefail
[ $# -ge 1 ] || { echo "usage: $0 cortex-m4f|cortex-m3 [--top N] [qemu_tick.sh options]" >&2; exit 2; }
TARGET=$1; shift
TOP=8
FOCUS=""
ARGS=()
while [ $# -gt 0 ]; do
  case $1 in
    --top) TOP=$2; shift 2 ;;
    --focus) FOCUS=$2; shift 2 ;;
    *) ARGS+=("$1"); shift ;;
  esac
done
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
WORK=$(mktemp -d "${TMPDIR:-/tmp}/worst_tick.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
status=0
QEMU_TICK_PROFILE="$WORK/prof" QEMU_TICK_FOCUS="$FOCUS" "$ROOT/bench/qemu_tick.sh" "$TARGET" "${ARGS[@]}" || status=$?
for f in "$WORK"/prof.max.* "$WORK"/prof.focus.*; do
  [ -e "$f" ] || continue
  kind=worst_tick; k=${f##*.max.}
  case $f in *.focus.*) kind=worst_focus; k=${f##*.focus.} ;; esac
  sort -rn "$f" | awk -v kind="$kind" -v k="$(echo "$k" | tr a-z A-Z)" -v top="$TOP" -v t="$TARGET" '
    { n[NR] = $1; s[NR] = $2; tot += $1 }
    END { printf "%s target=%s state=%s total=%d\n", kind, t, k, tot
          for (i = 1; i <= NR && i <= top; i++) printf "  %8d %5.1f%%  %s\n", n[i], 100 * n[i] / tot, s[i] }'
done
exit $status
