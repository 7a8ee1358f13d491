#!/usr/bin/env bash
# The firmware libraries as a consumer sees them: configure the tree with the simulator, tests
# and benchmarks off, build, `cmake --install` into a prefix; then build tests/consumer three
# ways (find_package, add_subdirectory, pkg-config) and run each on a golden skill image.
# usage: tests/consumer/run.sh [OUT=build/consumer]
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
OUT="$(realpath -m "${1:-$ROOT/build/consumer}")"
HERE="$ROOT/tests/consumer"
SKILL="$ROOT/tests/vectors/press_n50_lwr_hold.skill"
rm -rf "$OUT"
gen=(); command -v ninja >/dev/null && gen=(-G Ninja)

cmake -S "$ROOT" -B "$OUT/forceskill" "${gen[@]}" -DCMAKE_BUILD_TYPE=Release \
      -DFORCESKILL_BUILD_SIM=OFF -DFORCESKILL_BUILD_TESTS=OFF -DFORCESKILL_BUILD_BENCH=OFF \
      -DCMAKE_INSTALL_PREFIX="$OUT/prefix" >/dev/null
cmake --build "$OUT/forceskill" --target fs_core fs_core_f32 fs_fixed fs_proto >/dev/null
cmake --install "$OUT/forceskill" >/dev/null
echo "installed: $(find "$OUT/prefix" -type f | wc -l) files in $OUT/prefix"

cmake -S "$HERE" -B "$OUT/find" "${gen[@]}" -DCMAKE_PREFIX_PATH="$OUT/prefix" >/dev/null
cmake --build "$OUT/find" >/dev/null
echo -n "find_package:    "; "$OUT/find/consumer" "$SKILL"

cmake -S "$HERE" -B "$OUT/subdir" "${gen[@]}" -DFORCESKILL_SOURCE_DIR="$ROOT" >/dev/null
cmake --build "$OUT/subdir" --target consumer >/dev/null
echo -n "add_subdirectory: "; "$OUT/subdir/consumer" "$SKILL"
if [ -n "${gen[*]}" ]; then
  echo "add_subdirectory: $(ninja -C "$OUT/subdir" -t targets all | grep -c -E '^[^ ]+: (C_STATIC_LIBRARY|C_EXECUTABLE)_LINKER') libraries and programs in the consumer's tree (no simulator, tests or benchmarks)"
fi

mkdir -p "$OUT/pkgconfig"
export PKG_CONFIG_PATH="$OUT/prefix/lib/pkgconfig"
# shellcheck disable=SC2046
cc -std=c11 -Wall -Wextra -Werror "$HERE/main.c" $(pkg-config --cflags --libs forceskill) \
   -o "$OUT/pkgconfig/consumer"
echo -n "pkg-config:      "; "$OUT/pkgconfig/consumer" "$SKILL"
