#pragma once
// `floornav bench`: how fast the simulator steps on a standard set of cases (the same generated
// floors and robots as the Google Benchmark binary, see bench_cases.hpp), with the machine it ran
// on, as a table or as one JSON object. docs/PERFORMANCE.md explains the cases and the figures.

#include <string>

namespace floornav {

struct BenchOptions {
  bool json{false};              ///< print one JSON object instead of the table
  double seconds_per_case{1.0};  ///< s of timed work per case (after a short warm-up)
  std::string filter;            ///< run only the cases whose name contains this ("": all)
  std::string scenario_dir;      ///< "": ./scenarios, else the source tree's scenarios/
  std::string maps_dir;          ///< "": data/maps in the working directory or the tree
};

/// Runs the cases single-threaded and prints the results to stdout. Returns the exit status: 0,
/// or 2 when `filter` matches no case or `seconds_per_case` is not positive (message on stderr).
int run_bench(const BenchOptions& options);

}  // namespace floornav
