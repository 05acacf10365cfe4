// A batch folder's state, as merge and --resume read it: sweep.json, then a NUL byte, then
// results.jsonl, written into a shard folder. merge_batches joins it (partial shards allowed) and
// run_batch resumes it (no case to run: only what the folder holds is read, kept and
// aggregated). Either refuses it with an InputError or gives counts that add up and aggregates
// without a non-finite number. The sweep id `fuzz` (in the corpus) lets resume past the check.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "floornav/runner/batch.hpp"
#include "fuzz_support.hpp"

namespace {

using namespace floornav;

void check_numbers(const nlohmann::ordered_json& j) {
  if (j.is_number_float() && !std::isfinite(j.get<double>()))
    fuzz::finding("a non-finite number in an aggregate: " + j.dump());
  if (j.is_structured())
    for (const auto& v : j) check_numbers(v);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t nul = input.find('\0');
  const std::filesystem::path shard = fuzz::scratch_dir() / "shard";
  std::filesystem::create_directories(shard);
  const auto write_state = [&] {
    fuzz::write_scratch("shard/sweep.json", input.substr(0, nul));
    fuzz::write_scratch("shard/results.jsonl",
                        nul == std::string_view::npos ? std::string_view() : input.substr(nul + 1));
  };
  write_state();
  try {
    const std::filesystem::path dirs[] = {shard};
    const MergeOutcome m = merge_batches(dirs, fuzz::scratch_dir() / "merged", true);
    if (m.merged > m.total) fuzz::finding("merged more cases than the sweep has");
    check_numbers(m.aggregate);
  } catch (const InputError& e) {
    fuzz::check_message(e);
  }
  write_state();
  try {
    BatchOptions o;
    o.jobs = 1;
    o.out_dir = shard;
    o.resume = true;
    o.timing = false;
    o.optimum = false;
    o.sweep = {"fuzz", 1, 1, 4};
    const CaseList none{{}, [](std::size_t) -> BatchCase { fuzz::finding("a case was made"); }};
    const BatchOutcome b = run_batch(none, o);
    if (b.completed > b.total || b.ran != 0) fuzz::finding("resume counts that do not add up");
    check_numbers(b.aggregate);
  } catch (const InputError& e) {
    fuzz::check_message(e);
  }
  return 0;
}
