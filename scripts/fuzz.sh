#!/usr/bin/env bash
# Fuzzes every parser of user input (fuzz/): configures a clang build with libFuzzer, ASan and
# UBSan in build-fuzz/, builds the targets, runs each for SECONDS (default 30) from its seed
# corpus in fuzz/corpus/<target>/, and prints the executions and findings per target.
# The `python` target is the Python driver (fuzz/fuzz_python.py: Hypothesis, Debian's python3)
# of the scenario text and --set overrides through the Python package of the Release build
# (build/python, or FLOORNAV_PYTHON_BUILD): build that first (scripts/quickstart.sh).
#
#   scripts/fuzz.sh [SECONDS] [TARGET ...]     targets: scenario ros_map movingai_map
#                                              movingai_scen sdf_world course_world
#                                              hunav_agents batch_state python
#
# New inputs that reach new code collect in build-fuzz/fuzz-corpus/<target>/ (the next run starts
# from them); findings (crash-*, leak-*, timeout-*, oom-*) in build-fuzz/fuzz-findings/<target>/,
# each reproduced by `build-fuzz/fuzz/fuzz_<target> FILE`. Exit status 1 when anything was found.
# Environment: FLOORNAV_FUZZ_BUILD (build folder), FLOORNAV_FUZZ_JOBS (build jobs, default 2).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
seconds="${1:-30}"
[ $# -gt 0 ] && shift
targets=("$@")
[ ${#targets[@]} -gt 0 ] ||
  targets=(scenario ros_map movingai_map movingai_scen sdf_world course_world hunav_agents
    batch_state python)
libfuzzer_targets=()
for t in "${targets[@]}"; do
  [ "$t" = python ] || libfuzzer_targets+=("$t")
done
python_build="${FLOORNAV_PYTHON_BUILD:-$root/build/python}"
build="${FLOORNAV_FUZZ_BUILD:-$root/build-fuzz}"
jobs="${FLOORNAV_FUZZ_JOBS:-2}"

if ! command -v clang++ > /dev/null; then
  echo "fuzz.sh: needs clang++ with libFuzzer: apt-get install -y clang libclang-rt-14-dev" >&2
  exit 2
fi
if ! grep -q 'add_subdirectory(fuzz)' "$root/CMakeLists.txt"; then
  echo "fuzz.sh: the top-level CMakeLists.txt does not add fuzz/ when FLOORNAV_FUZZ is ON" >&2
  exit 2
fi

mkdir -p "$build"
if [ ${#libfuzzer_targets[@]} -gt 0 ]; then
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_COMPILER=clang++ -DFLOORNAV_FUZZ=ON -DFLOORNAV_BUILD_TESTS=OFF \
    -DFLOORNAV_BUILD_BENCH=OFF > "$build/configure.log" 2>&1 ||
    { cat "$build/configure.log" >&2; exit 2; }
  cmake --build "$build" -j "$jobs" --target "${libfuzzer_targets[@]/#/fuzz_}"
fi

dict_of() {
  case "$1" in
    scenario | ros_map | batch_state) echo "$root/fuzz/dict/$1.dict" ;;
    hunav_agents) echo "$root/fuzz/dict/hunav.dict" ;;
    movingai_*) echo "$root/fuzz/dict/movingai.dict" ;;
    *) echo "$root/fuzz/dict/xml.dict" ;;
  esac
}

status=0
summary=()
for t in "${targets[@]}"; do
  work="$build/fuzz-corpus/$t"
  findings="$build/fuzz-findings/$t"
  log="$build/fuzz-$t.log"
  mkdir -p "$work" "$findings"
  touch "$build/fuzz-$t.start"
  echo "== fuzz_$t for ${seconds} s (log: $log)"
  if [ "$t" = python ]; then
    # Hypothesis from fixed seeds (0, 1, ...) until SECONDS have passed; findings, shrunk, are
    # written to the findings folder (60 s on one input is a hang: faulthandler ends it).
    if [ -d "$python_build/floornav" ]; then
      PYTHONPATH="$python_build" MPLBACKEND=Agg timeout $((${seconds%.*} + 300)) \
        /usr/bin/python3 "$root/fuzz/fuzz_python.py" "$seconds" "$findings" > "$log" 2>&1 || true
    else
      echo "no Python package in $python_build (build it: scripts/quickstart.sh)" > "$log"
    fi
  else
    # -timeout: an input that takes 10 s is a hang, a finding like a crash. libFuzzer stops at
    # the first finding; its exit status is not ours to judge, the findings folder is.
    "$build/fuzz/fuzz_$t" "$work" "$root/fuzz/corpus/$t" -dict="$(dict_of "$t")" \
      -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
      -artifact_prefix="$findings/" > "$log" 2>&1 || true
  fi
  execs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)"
  [ -n "$execs" ] || execs="$(grep -o '^#[0-9]*' "$log" | tail -n 1 | tr -d '#' || true)"
  if [ -z "$execs" ]; then  # the fuzzer never ran (a missing dictionary, a bad flag): a failure
    status=1
    echo "   fuzz_$t did not run:" && head -n 5 "$log" | sed 's/^/   /'
  fi
  found="$(find "$findings" -type f -newer "$build/fuzz-$t.start" | wc -l)"
  corpus="$(find "$work" -type f | wc -l)"
  summary+=("$(printf '%-14s %12s %9s %8s' "$t" "${execs:-0}" "$corpus" "$found")")
  if [ "$found" -gt 0 ]; then
    status=1
    find "$findings" -type f -newer "$build/fuzz-$t.start" | sed "s|^|   finding: |"
  fi
done

printf '\n%-14s %12s %9s %8s\n' target executions corpus findings
printf '%s\n' "${summary[@]}"
exit "$status"
