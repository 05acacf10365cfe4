#!/usr/bin/env bash
# The consumer test: floornav as a user gets it. Installs a build into a temporary prefix, then,
# in a directory outside the repository and against that prefix only:
#   1. checks the installed headers include nothing that is not installed (no src/ header);
#   2. builds the README's "Library" program with the README's CMake lines (both copied out of
#      README.md, so the README is what is tested), runs it on an installed chapter scenario and
#      checks the outcome; the program must be examples/01_go_to_goal.cpp word for word;
#   3. builds examples/ on their own (find_package) and runs their tests;
#   4. runs the installed floornav tool on an installed scenario (and, with OMPL, plans with
#      rrt_connect: the planner's module loaded from the prefix);
#   5. imports the installed Python package (when the build has it) from outside the repository,
#      with no PYTHONPATH into the build tree, and runs an installed scenario with it;
#   6. builds the libraries again without OMPL (FLOORNAV_WITH_OMPL=OFF; no tests, tool or Python)
#      and installs them into a second prefix: the README's program builds against it with OMPL
#      hidden from CMake, runs, and refuses a scenario asking for rrt_connect (exit 2); a program
#      asking for floornav's core component alone builds with yaml-cpp, tinyxml2, libpng, zstd
#      and nlohmann_json hidden; asking for the ompl component there fails, saying why.
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
configure() {  # configure SOURCE BINARY [CMAKE ARGS...]: against the prefix alone
  cmake -S "$1" -B "$2" "${generator[@]}" "${launcher[@]}" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF "${@:3}" >/dev/null
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
# The rrt_connect planner (a build with OMPL): the installed tool loads its module from the
# prefix, relative to itself (the prefix was moved: --prefix); a program built against the
# package has the module's directory on its run path.
if [ -f "$build/libfloornav_rrt_connect.so" ]; then
  [ -f "$prefix/lib/floornav/libfloornav_rrt_connect.so" ] ||
    fail "the install lacks lib/floornav/libfloornav_rrt_connect.so (the rrt_connect planner's module)"
  out=$(LD_DEBUG=files "$prefix/bin/floornav" run "$prefix/share/floornav/scenarios/fleet_crossing.yaml" \
    --set controller.planner.kind=rrt_connect --out "$work/rrt" --quiet 2>&1) ||
    fail "the installed floornav failed with rrt_connect: $(grep -v '^ *[0-9]*:' <<<"$out")"
  grep -q "file=$prefix/bin/../lib/floornav/libfloornav_rrt_connect.so " <<<"$out" ||
    fail "the installed floornav did not load the rrt_connect module from $prefix/lib/floornav"
  grep -q '"status": *"reached"' "$work/rrt/summary.json" ||
    fail "the installed floornav's fleet_crossing with rrt_connect did not reach every goal"
  readelf -d "$app/build/app" | grep -q "RUNPATH.*$prefix/lib/floornav" ||
    fail "the README program's run path lacks the rrt_connect module's $prefix/lib/floornav"
  # floornav::floornav brings floornav::ompl: the README program takes a scenario with rrt_connect.
  sed 's/^  kind: hybrid$/  kind: hybrid\n  planner: {kind: rrt_connect}/' \
    "$prefix/share/floornav/scenarios/circle_obstacle.yaml" >"$work/rrt_connect.yaml"
  out=$("$app/build/app" "$work/rrt_connect.yaml" 2>&1) ||
    fail "the README program refused a scenario with rrt_connect (floornav::floornav without floornav::ompl?): $out"
  echo "consumer test: the installed tool planned with rrt_connect, its module loaded from the prefix;" \
    "the README program takes rrt_connect"
fi

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

# 6. An install made without OMPL (only the libraries are built: the tool, tests, benchmarks,
# examples and Python are off).
nompl=$work/no-ompl
cmake -S "$repo" -B "$nompl/build" "${generator[@]}" "${launcher[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DFLOORNAV_WITH_OMPL=OFF -DFLOORNAV_BUILD_TOOL=OFF -DFLOORNAV_BUILD_TESTS=OFF \
  -DFLOORNAV_BUILD_BENCH=OFF -DFLOORNAV_BUILD_EXAMPLES=OFF -DFLOORNAV_BUILD_PYTHON=OFF >/dev/null
cmake --build "$nompl/build" >/dev/null
cmake --install "$nompl/build" --prefix "$nompl/prefix" >/dev/null
prefix=$nompl/prefix  # configure() builds against this install from here on
[ ! -e "$prefix/include/floornav/ompl" ] && [ ! -e "$prefix/include/floornav/ompl.hpp" ] ||
  fail "the install without OMPL has floornav/ompl headers"
! find "$prefix/lib" -name 'libfloornav_ompl*' | grep -q . ||
  fail "the install without OMPL has libfloornav_ompl"
echo "consumer test: install without OMPL:" \
  "$(find "$prefix/include" -name '*.hpp' | wc -l) installed headers"
# The README's program, with OMPL hidden from CMake: the package must not look for it.
# (--no-warn-unused-cli: a hiding variable that was never used is the point, not a mistake.)
configure "$app" "$nompl/app" --no-warn-unused-cli -DCMAKE_DISABLE_FIND_PACKAGE_ompl=ON
cmake --build "$nompl/app" >/dev/null
out=$("$nompl/app/app" "$prefix/share/floornav/scenarios/circle_obstacle.yaml")
[[ "$out" == "circle-obstacle: reached in "* ]] ||
  fail "the README program (no OMPL) did not reach the goal: $out"
# A scenario asking for rrt_connect: one clear error, exit status 2.
sed 's/^  kind: hybrid$/  kind: hybrid\n  planner: {kind: rrt_connect}/' \
  "$prefix/share/floornav/scenarios/circle_obstacle.yaml" >"$nompl/rrt_connect.yaml"
grep -q 'planner: {kind: rrt_connect}' "$nompl/rrt_connect.yaml" ||
  fail "circle_obstacle.yaml lost its line '  kind: hybrid' (the rrt_connect case is made from it)"
status=0
out=$("$nompl/app/app" "$nompl/rrt_connect.yaml" 2>&1) || status=$?
[ "$status" -eq 2 ] && [[ "$out" == *"controller.planner.kind: rrt_connect needs OMPL"* ]] ||
  fail "rrt_connect without OMPL: expected exit 2 and 'needs OMPL', got $status: $out"
echo "consumer test: without OMPL: README program: reached; rrt_connect refused (exit 2)"
# The core component alone needs none of the file formats' libraries.
mkdir -p "$nompl/core"
cat >"$nompl/core/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.21)
project(core_only LANGUAGES CXX)
find_package(floornav CONFIG REQUIRED COMPONENTS core)
if(TARGET floornav::io OR TARGET floornav::floornav)
  message(FATAL_ERROR "COMPONENTS core loaded more than the core")
endif()
add_executable(core_only main.cpp)
target_link_libraries(core_only PRIVATE floornav::core)
CMAKE
cat >"$nompl/core/main.cpp" <<'CPP'
#include <cstdio>
#include <floornav/core.hpp>
int main() {
  floornav::WorldDesc desc;
  desc.circles.push_back({floornav::Vec2(2.0, 0.0), 0.5});
  const floornav::World world(std::move(desc));
  std::printf("%.3f\n", world.clearance(floornav::Vec2(0.0, 0.0)));
}
CPP
configure "$nompl/core" "$nompl/core/build" --no-warn-unused-cli \
  -DCMAKE_DISABLE_FIND_PACKAGE_ompl=ON -DCMAKE_DISABLE_FIND_PACKAGE_yaml-cpp=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_tinyxml2=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_PNG=ON -DCMAKE_DISABLE_FIND_PACKAGE_zstd=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_nlohmann_json=ON
cmake --build "$nompl/core/build" >/dev/null
out=$("$nompl/core/build/core_only")
[ "$out" = "1.500" ] || fail "the core-only program printed '$out', not the clearance 1.500"
# Asking for floornav::ompl from this install: not found, and the message says why.
mkdir -p "$nompl/ompl"
cat >"$nompl/ompl/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.21)
project(wants_ompl LANGUAGES CXX)
find_package(floornav CONFIG REQUIRED COMPONENTS ompl)
CMAKE
if out=$(configure "$nompl/ompl" "$nompl/ompl/build" 2>&1); then
  fail "find_package(floornav COMPONENTS ompl) succeeded against an install without OMPL"
fi
[[ "$out" == *"installed without OMPL"* ]] || fail "COMPONENTS ompl failed without saying why: $out"
echo "consumer test: without OMPL: COMPONENTS core needs only Eigen and fmt;" \
  "COMPONENTS ompl is refused"
echo "consumer test: passed"
