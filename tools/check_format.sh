#!/usr/bin/env bash
# clang-format check of the C sources in firmware/ and hil_sim/ (style: .clang-format), except
# generated code (firmware/proto/generated/ and every file marked "do not edit": the headers
# tools/gen_codes.py and tools/gen_f32_names.py write).
# usage: tools/check_format.sh          check (exit 1 and clang-format's findings on a difference)
#        tools/check_format.sh --fix    reformat those files in place
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
CF="${CLANG_FORMAT:-clang-format}"
mapfile -t files < <(git ls-files --cached --others --exclude-standard -- \
                         'firmware/*.c' 'firmware/*.h' 'hil_sim/*.c' 'hil_sim/*.h' |
                     grep -v '^firmware/proto/generated/' |
                     xargs grep -L 'do not edit' || true)
if [ "${1:-}" = "--fix" ]; then
    "$CF" -i "${files[@]}"
    echo "formatted ${#files[@]} files"
    exit 0
fi
"$CF" --dry-run --Werror "${files[@]}"
echo "clang-format: ${#files[@]} files match .clang-format"
