#!/usr/bin/env bash
# The consumer test: floornav as a user gets it. Installs a build into a temporary prefix, then,
# in a directory outside the repository and against that prefix only:
#   1. checks the installed headers include nothing that is not installed (no src/ header);
#   2. builds the README's "Library" program with the README's CMake lines (both copied out of
#      README.md, so the README is what is tested), runs it on an installed chapter scenario and
#      checks the outcome; the program must be examples/01_go_to_goal.cpp word for word;
#   3. builds examples/ on their own (find_package) and runs their tests;
#   4. runs the installed floornav tool on an installed scenario;
#   5. imports the installed Python package (when the build has it) from outside the repository,
#      with no PYTHONPATH into the build tree, and runs an installed scenario with it.
# Usage: scripts/consumer_test.sh [BUILD_DIR]   (default: build; it must be built already)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$repo/build}" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
configure() {  # configure SOURCE BINARY: against the prefix alone
  cmake -S "$1" -B "$2" "${generator[@]}" "${launcher[@]}" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF >/dev/null
}
fail() {
  echo "consumer test: $*" >&2
  exit 1
}

cmake --install "$build" --prefix "$prefix" >/dev/null
echo "consumer test: installed into $prefix"

# 1. Every quoted include of an installed header names an installed header; nothing installed
# points back into the source or build tree.
while IFS= read -r header; do
  while IFS= read -r included; do
    [ -f "$prefix/include/$included" ] ||
      fail "${header#"$prefix"/} includes \"$included\", which is not installed"
  done < <(sed -n -e 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([^"]*\)".*/\1/p' \
    -e 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*<\(floornav\/[^>]*\)>.*/\1/p' "$header")
done < <(find "$prefix/include" -name '*.hpp')
if grep -rIl -e "$repo" -e "$build" "$prefix/include" "$prefix/lib/cmake" >/dev/null; then
  fail "installed files name the source or build tree: $(grep -rIl -e "$repo" -e "$build" \
    "$prefix/include" "$prefix/lib/cmake" | tr '\n' ' ')"
fi
# Every module header is named by an umbrella header (floornav/core.hpp, io.hpp, render.hpp,
# runner.hpp; floornav.hpp includes them all), so `#include <floornav/floornav.hpp>` is everything.
while IFS= read -r header; do
  grep -qx "#include \"${header#"$prefix/include/"}\"" "$prefix"/include/floornav/*.hpp ||
    fail "${header#"$prefix/include/"} is in no umbrella header (include/floornav/*.hpp)"
done < <(find "$prefix/include/floornav" -mindepth 2 -name '*.hpp')
echo "consumer test: $(find "$prefix/include" -name '*.hpp' | wc -l) installed headers include only installed headers; the umbrellas name every one"

# 2. The README's program and CMake lines, built outside the repository.
app=$work/app
mkdir -p "$app"
# The fenced block that follows the line `<!-- consumer-test: NAME ... -->`.
readme_block() {
  awk -v name="$1" '
    index($0, "<!-- consumer-test: " name) == 1 { armed = 1; next }
    armed && !inside && /^```/ { inside = 1; next }
    inside && /^```/ { exit }
    inside { print }' "$repo/README.md"
}
readme_block main.cpp >"$app/main.cpp"
readme_block CMakeLists.txt >"$app/CMakeLists.txt"
[ -s "$app/main.cpp" ] && [ -s "$app/CMakeLists.txt" ] || fail "README.md lost its consumer-test blocks"
diff -u "$repo/examples/01_go_to_goal.cpp" "$app/main.cpp" ||
  fail "the README's program differs from examples/01_go_to_goal.cpp: keep them identical"
configure "$app" "$app/build"
cmake --build "$app/build" >/dev/null
out=$("$app/build/app" "$prefix/share/floornav/scenarios/circle_obstacle.yaml")
echo "consumer test: README program: $out"
[[ "$out" == "circle-obstacle: reached in "* ]] || fail "the README program did not reach the goal"

# 3. The examples on their own, against the installed package and scenarios.
cp -r "$repo/examples" "$work/examples"
configure "$work/examples" "$work/examples/build"
cmake --build "$work/examples/build" >/dev/null
ctest --test-dir "$work/examples/build" --output-on-failure >"$work/examples.log" ||
  { cat "$work/examples.log"; fail "an example failed against the installed package"; }
echo "consumer test: examples: $(grep -o '[0-9]*% tests passed.*' "$work/examples.log")"

# 4. The installed tool.
out=$("$prefix/bin/floornav" run "$prefix/share/floornav/scenarios/week7_pocket.yaml" \
  --out "$work/run" --quiet 2>&1) || fail "the installed floornav failed: $out"
[ -f "$work/run/summary.json" ] || fail "the installed floornav wrote no summary.json"
grep -q '"status": *"reached"' "$work/run/summary.json" ||
  fail "the installed floornav did not reach the goal of week7_pocket.yaml"
# 5. The installed Python package (built when pybind11 and Debian's Python were found).
pkg=$(find "$prefix/lib" -path '*-packages/floornav/__init__.py' 2>/dev/null | head -n 1)
if [ -n "$pkg" ]; then
  out=$(cd "$work" && PYTHONPATH=$(dirname "$(dirname "$pkg")") /usr/bin/python3 -c '
import sys, floornav
assert floornav.__file__.startswith(sys.argv[1]), floornav.__file__
r = floornav.run(floornav.load_scenario(sys.argv[2]))
print(floornav.__version__, r.summary["status"])' "$prefix" "$prefix/share/floornav/scenarios/circle_obstacle.yaml" 2>&1) ||
    fail "the installed Python package failed: $out"
  [[ "$out" == *" reached" ]] || fail "the installed Python package did not reach the goal: $out"
  echo "consumer test: installed Python package floornav $out"
else
  echo "consumer test: no Python package in this build (skipped)"
fi
echo "consumer test: passed"
