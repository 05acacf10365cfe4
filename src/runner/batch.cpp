#include "floornav/runner/batch.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string_view>
#include <thread>

#include "floornav/core/input_error.hpp"
#include "floornav/core/output_error.hpp"
#include "floornav/io/atomic_file.hpp"
#include "floornav/io/provenance.hpp"
#include "floornav/io/run_mcap.hpp"
#include "floornav/io/summary_json.hpp"
#include "floornav/render/trajectory_html.hpp"
#include "floornav/render/trajectory_svg.hpp"
#include "floornav/runner/run_outputs.hpp"
#include "floornav/runner/run_summary.hpp"
#include "floornav/runner/scenario_optimum.hpp"

namespace floornav {

namespace {

using Json = nlohmann::ordered_json;
/// A worker's last optimum raster: consecutive cases on the same world and robot radius (the
/// rows of a .scen file, a sweep over one map) search one raster instead of building it each.
struct OptimumCache {
  std::shared_ptr<const World> world;  ///< held, so that the key cannot be a reused address
  double radius{0.0};
  bool usable{false};    ///< the world's raster does not depend on the route
  OptimumRaster raster;  ///< its memory is reused for the next world
};

/// compute_optimum (run_summary.hpp) through the worker's cache: the same optimum (a length in
/// metres, or the reason there is none), nullopt where compute_optimum gives none.
std::optional<Optimum> cached_optimum(const Scenario& s, OptimumCache& cache) {
  const RobotTask* t = optimum_task(s);
  if (!t) return std::nullopt;
  const double r = t->robot.body_radius;
  if (cache.world != s.world || cache.radius != r) {
    cache.world = s.world;
    cache.radius = r;
    cache.usable = build_optimum_raster(*s.world, r, {}, cache.raster);
  }
  if (!cache.usable) return scenario_optimum(*s.world, r, t->start.position, t->goals);
  return scenario_optimum(cache.raster, t->start.position, t->goals);
}

/// A batch line: the case, where it came from, then the run's summary (run_summary, the keys of
/// summary.json) without the transition log.
Json case_line(const BatchCase& c, const Json& summary, bool timing) {
  Json line = Json::object();
  line["case"] = c.id;
  line["source"] = c.source;
  for (const auto& [k, v] : summary.items()) {
    if (k == "transitions" || k == "transitions_truncated") continue;
    line[k] = v;
  }
  if (!timing) line["wall_time"] = 0.0;
  return line;
}

RunContext context_of(const BatchCase& c, const BatchOptions& o) {
  RunContext ctx;
  ctx.overrides = o.overrides;
  ctx.optimal_length = c.optimal_length;
  ctx.optimal_time = c.optimal_time;
  ctx.swept = c.swept;
  return ctx;
}

/// "case-00042-rectangle": the pictures' file name stem (the name cut to letters, digits, - _ .).
std::string picture_stem(const BatchCase& c) {
  std::string name;
  for (char ch : c.scenario.name)
    name += (std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_' || ch == '.')
                ? ch
                : '_';
  if (name.size() > 80) name.resize(80);
  return fmt::format("case-{:05}-{}", c.id, name);
}

bool wants_picture(BatchPictures which, RunStatus status) {
  return which == BatchPictures::All ||
         (which == BatchPictures::Failed && status != RunStatus::Reached);
}

/// Runs one case; nullopt when the user's stop or `halt` was set while it ran (the case is
/// abandoned). With pictures asked for, the run records its trajectory and ranges as it goes
/// (recording moves nothing), so that a failure is drawn without running it again.
std::optional<Json> run_case(const BatchCase& c, const BatchOptions& o,
                             const std::atomic<bool>* halt, OptimumCache& optimum_cache) {
  Scenario sc = c.scenario;  // shares the world; copies only small data
  OutputSelection which;
  which.html = o.pictures != BatchPictures::None;
  which.mcap = o.mcap != BatchPictures::None;
  sc.sim.record_trajectory = which.html || which.mcap;
  if (sc.sim.record_trajectory) prepare_outputs(sc, which);
  const std::string stem = (o.pictures_dir / picture_stem(c)).string();
  const auto bag = [&](const auto& write) {
    ensure_directory(o.mcap_dir);  // made with the first bag: none, no folder
    write_file_atomically(o.mcap_dir / (picture_stem(c) + ".mcap"),
                          [&](const std::function<void(std::string_view)>& sink) { write(sink); });
  };
  RunContext ctx = context_of(c, o);
  if (sc.is_fleet()) {
    // A fleet: one thread per case, like every case (the batch is parallel across cases).
    auto f = run_fleet_timed(sc, 1, o.stop, halt);
    if (!f) return std::nullopt;
    if (wants_picture(o.pictures, f->status)) {
      ensure_directory(o.pictures_dir);
      write_file_atomically(stem + ".svg", render_fleet_svg(sc, *f));
      write_file_atomically(stem + ".html", render_fleet_html(sc, *f));
    }
    if (wants_picture(o.mcap, f->status))
      bag([&](const auto& sink) { write_fleet_mcap(sc, *f, sink); });
    // The fleet's line holds the fleet's summary without each robot's (there can be thousands).
    Json summary = fleet_run_summary(c.scenario, *f, ctx);
    summary.erase("robots");
    return case_line(c, summary, o.timing);
  }
  if (o.optimum && !c.optimal_length) ctx.optimum = cached_optimum(sc, optimum_cache);
  auto r = run_timed(sc, o.stop, halt);
  if (!r) return std::nullopt;
  if (wants_picture(o.pictures, r->status)) {
    ensure_directory(o.pictures_dir);  // made with the first picture: none, no folder
    write_file_atomically(stem + ".svg", render_trajectory_svg(sc, *r));
    write_file_atomically(stem + ".html", render_trajectory_html(sc, *r));
  }
  if (wants_picture(o.mcap, r->status))
    bag([&](const auto& sink) { write_run_mcap(sc, *r, sink); });
  return case_line(c, run_summary(c.scenario, *r, ctx), o.timing);
}

}  // namespace

std::string sweep_json_text(const SweepInfo& s, std::size_t shard_cases) {
  Json j = Json::object();
  j["sweep_id"] = s.id;
  j["shard"] = s.shard;
  j["shards"] = s.shards;
  j["cases"] = s.cases;
  j["shard_cases"] = shard_cases;
  j["floornav_version"] = floornav_version();
  return j.dump(2) + "\n";
}

namespace {

/// sweep.json of a folder, or nullopt when it has none. Its numbers are bounded before anything
/// is sized by them (a 90-byte file may claim 10^12 cases).
std::optional<Json> read_sweep(const std::filesystem::path& dir) {
  const auto path = dir / "sweep.json";
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::nullopt;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path.string(), "", "is not a file (a batch folder's sweep.json)");
  if (std::filesystem::file_size(path, ec) > (1u << 20))
    throw InputError(path.string(), "", "is larger than the 1 MiB a sweep.json may have");
  std::ifstream in(path);
  Json j = Json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("sweep_id") || !j["sweep_id"].is_string() ||
      !j.contains("shard") || !j["shard"].is_number_integer() || !j.contains("shards") ||
      !j["shards"].is_number_integer() || !j.contains("cases") || !j["cases"].is_number_unsigned())
    throw InputError(path.string(), "", "not a sweep.json written by floornav batch");
  const auto shards = j["shards"].get<std::int64_t>(), shard = j["shard"].get<std::int64_t>();
  if (shards < 1 || shards > kMaxShards)
    throw InputError(path.string(), "shards",
                     fmt::format("{} is not in [1, {}] (not a sweep.json written by floornav "
                                 "batch)",
                                 shards, kMaxShards));
  if (shard < 1 || shard > shards)
    throw InputError(path.string(), "shard",
                     fmt::format("{} is not in [1, shards = {}]", shard, shards));
  if (j["cases"].get<std::uint64_t>() > kMaxSweepCases)
    throw InputError(path.string(), "cases",
                     fmt::format("{} is more than the {} cases a sweep may have",
                                 j["cases"].get<std::uint64_t>(), kMaxSweepCases));
  return j;
}

/// Whether `j` is a finished case's line: its case number and the run's outcome (a line that has
/// the number but no result, written by hand or cut short, is not a finished case).
bool is_result_line(const Json& j) {
  if (!j.is_object() || !j.contains("case") || !j["case"].is_number_unsigned()) return false;
  const auto status = j.find("status");
  if (status == j.end() || !status->is_string()) return false;
  if (!parse_enum<RunStatus>(status->get<std::string>())) return false;
  const auto time = j.find("sim_time");
  return time != j.end() && time->is_number() && j.contains("source") && j["source"].is_string();
}

/// The lines of a results.jsonl, by case number. A line that is not a finished case (cut short
/// by an interrupted write, or without a result) is skipped when `resume` (that case runs again)
/// and an error otherwise (merge). A case given twice is an error either way: which of the two
/// is the result?
std::map<std::size_t, Json> read_results(const std::filesystem::path& path, bool resume) {
  std::map<std::size_t, Json> out;
  std::map<std::size_t, std::size_t> line_of;
  std::ifstream in(path);
  if (!in) {
    if (resume) return out;
    throw InputError(path.string(), "", "cannot be read (is this a batch output folder?)");
  }
  std::string text;
  for (std::size_t n = 1; std::getline(in, text); ++n) {
    if (text.empty()) continue;
    Json j = Json::parse(text, nullptr, false);
    if (j.is_discarded() || !is_result_line(j)) {
      if (resume) continue;
      throw InputError(path.string(), "line " + std::to_string(n),
                       "not a finished case's line (cut short, without a result, or not written "
                       "by floornav batch)");
    }
    // The case number first: the line itself is moved into the map only after it was read.
    const auto id = j["case"].get<std::size_t>();
    if (const auto [it, fresh] = line_of.emplace(id, n); !fresh)
      throw InputError(
          path.string(), "line " + std::to_string(n),
          fmt::format("case {} again (also on line {}): a case is in a results file "
                      "once{}",
                      id, it->second, resume ? "; leave out --resume to run the sweep again" : ""));
    out[id] = std::move(j);
  }
  return out;
}

/// The case number of a per-case output's file name (`case-NNNNN-<name>.<ext>`, as picture_stem
/// makes it: at least 5 digits), or nullopt for a file of another name.
std::optional<std::size_t> case_of_file_name(const std::string& name) {
  if (name.compare(0, 5, "case-") != 0) return std::nullopt;
  std::size_t end = 5, id = 0;
  for (; end < name.size() && end < 5 + 19 && name[end] >= '0' && name[end] <= '9'; ++end)
    id = 10 * id + static_cast<std::size_t>(name[end] - '0');
  if (end - 5 < 5 || end >= name.size() || name[end] != '-') return std::nullopt;
  return id;
}

/// Removes the per-case outputs (`case-NNNNN-<name>` with one of `extensions`) that an earlier
/// batch left in `dir` for the cases `stale(id)` names. Nothing else in the folder is touched.
void remove_stale_case_files(const std::filesystem::path& dir,
                             std::initializer_list<std::string_view> extensions,
                             const std::function<bool(std::size_t)>& is_stale) {
  std::error_code ec;
  std::vector<std::filesystem::path> stale;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::optional<std::size_t> id = case_of_file_name(it->path().filename().string());
    const std::string ext = it->path().extension().string();
    if (id && is_stale(*id) &&
        std::find(extensions.begin(), extensions.end(), ext) != extensions.end() &&
        it->is_regular_file(ec))
      stale.push_back(it->path());
  }
  for (const auto& p : stale) std::filesystem::remove(p, ec);
}

/// How many of the case numbers 0..cases-1 are in shard k of n (every n-th from k - 1).
std::size_t shard_size(std::size_t cases, int k, int n) {
  const auto first = static_cast<std::size_t>(k - 1);
  return cases > first
             ? (cases - first + static_cast<std::size_t>(n) - 1) / static_cast<std::size_t>(n)
             : 0;
}

/// Whether case `id` is one of shard k of n of a sweep of `cases` cases.
bool in_shard(std::size_t id, std::size_t cases, int k, int n) {
  return id < cases && id % static_cast<std::size_t>(n) == static_cast<std::size_t>(k - 1);
}

/// "case 7, 10, 13 and 5 more".
std::string list_cases(const std::vector<std::size_t>& ids) {
  std::string out;
  const std::size_t shown = std::min<std::size_t>(ids.size(), 5);
  for (std::size_t i = 0; i < shown; ++i) out += (i ? ", " : "") + std::to_string(ids[i]);
  if (ids.size() > shown) out += fmt::format(" and {} more", ids.size() - shown);
  return out;
}

}  // namespace

nlohmann::ordered_json aggregate_results(const std::vector<nlohmann::ordered_json>& lines) {
  struct Totals {
    std::size_t n = 0, reached = 0, collision = 0, timeout = 0, stuck = 0;
    double time_sum = 0, path_sum = 0;
    std::optional<double> clearance_min;  // none until a line has a finite one
    std::size_t efficiency_n = 0, score_n = 0, optimum_n = 0;
    double efficiency_sum = 0, score_sum = 0, optimum_sum = 0;
    std::map<std::string, std::size_t> optimum_sources;
  };
  auto add = [](Totals& t, const Json& l) {
    ++t.n;
    const std::string s = l.value("status", "");
    if (s == "reached") {
      ++t.reached;
      t.time_sum += l.value("sim_time", 0.0);
      t.path_sum += l.value("path_length", 0.0);
    }
    t.collision += s == "collision";
    t.timeout += s == "timeout";
    t.stuck += s == "stuck";
    if (l.contains("path_efficiency") && l["path_efficiency"].is_number())
      ++t.efficiency_n, t.efficiency_sum += l["path_efficiency"].get<double>();
    if (l.contains("optimal_length") && l["optimal_length"].is_number()) {
      ++t.optimum_n, t.optimum_sum += l["optimal_length"].get<double>();
      ++t.optimum_sources[l.value("optimal_source", "unknown")];
    }
    if (l.contains("score") && l["score"].is_number())
      ++t.score_n, t.score_sum += l["score"].get<double>();
    if (l.contains("min_clearance") && l["min_clearance"].is_number()) {
      const double c = l["min_clearance"].get<double>();
      t.clearance_min = t.clearance_min ? std::min(*t.clearance_min, c) : c;
    }
  };
  auto render = [](const Totals& t) {
    Json j;
    const double n = t.n ? static_cast<double>(t.n) : 1.0;
    j["runs"] = t.n;
    j["reached"] = t.reached;
    j["success_rate"] = static_cast<double>(t.reached) / n;
    j["collision_rate"] = static_cast<double>(t.collision) / n;
    j["timeout_rate"] = static_cast<double>(t.timeout) / n;
    j["stuck_rate"] = static_cast<double>(t.stuck) / n;
    j["mean_time_reached"] =
        t.reached ? Json(t.time_sum / static_cast<double>(t.reached)) : Json(nullptr);
    j["mean_path_length_reached"] =
        t.reached ? Json(t.path_sum / static_cast<double>(t.reached)) : Json(nullptr);
    j["min_clearance"] = t.clearance_min ? Json(*t.clearance_min) : Json(nullptr);
    if (t.efficiency_n)
      j["mean_path_efficiency_reached"] = t.efficiency_sum / static_cast<double>(t.efficiency_n);
    if (t.optimum_n) {
      j["runs_with_optimum"] = t.optimum_n;
      j["mean_optimal_length"] = t.optimum_sum / static_cast<double>(t.optimum_n);
      j["optimal_sources"] = t.optimum_sources;
    }
    if (t.score_n) j["mean_score"] = t.score_sum / static_cast<double>(t.score_n);
    return j;
  };
  Totals all;
  std::map<std::string, Totals> by_kind;
  for (const auto& l : lines) {
    add(all, l);
    add(by_kind[l.value("controller", "unknown")], l);
  }
  Json out = render(all);
  Json kinds = Json::object();
  for (const auto& [k, t] : by_kind) kinds[k] = render(t);
  out["by_controller"] = kinds;
  return out;
}

nlohmann::ordered_json run_batch_case(const BatchCase& c, const BatchOptions& options) {
  OptimumCache cache;
  // Never abandoned: with no halt flag and the caller's own stop unset, a line always comes.
  BatchOptions o = options;
  o.stop = nullptr;
  return *run_case(c, o, nullptr, cache);
}

BatchOutcome run_batch(std::span<const BatchCase> cases, const BatchOptions& options) {
  std::map<std::size_t, std::size_t> index;  // case id -> position in `cases`
  CaseList list;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    index[cases[i].id] = i;
    list.ids.push_back(cases[i].id);
  }
  std::sort(list.ids.begin(), list.ids.end());
  list.make = [&](std::size_t id) { return cases[index.at(id)]; };
  return run_batch(list, options);
}

namespace {

/// What a folder being resumed already holds for this shard (nothing for a fresh batch).
struct ResumedLines {
  std::vector<std::optional<Json>> lines;  ///< by position in the case list: set when finished
  std::size_t count{0};                    ///< lines taken from the folder
  /// The sweep's case count as sweep.json will say: a resumed folder keeps a larger count it had
  /// (a resume with a smaller --limit runs fewer cases, but never drops lines already finished).
  std::size_t sweep_cases{0};
  /// Finished lines of this shard outside this call's cases (beyond --limit): kept as they are.
  std::map<std::size_t, Json> beyond;
};

/// Stage 1, resume: the lines kept from the folder. Only a folder of this very sweep and shard may
/// be resumed (InputError otherwise); its lines are kept as they are.
ResumedLines read_resumed_lines(const CaseList& cases, const BatchOptions& options) {
  const std::size_t n = cases.ids.size();
  ResumedLines r;
  r.lines.resize(n);
  r.sweep_cases = options.sweep.cases;
  if (!options.resume) return r;
  const auto results_path = options.out_dir / "results.jsonl";
  const auto old = read_sweep(options.out_dir);
  std::error_code ec;
  if (!old && std::filesystem::exists(results_path, ec))
    throw InputError(options.out_dir.string(), "",
                     "has a results.jsonl but no sweep.json, so which sweep its lines belong to "
                     "cannot be checked: give another --out, or leave out --resume to start "
                     "again");
  if (old) {
    if ((*old)["sweep_id"] != options.sweep.id || (*old)["shard"] != options.sweep.shard ||
        (*old)["shards"] != options.sweep.shards)
      throw InputError(
          (options.out_dir / "sweep.json").string(), "",
          fmt::format("holds shard {}/{} of sweep {}, not shard {}/{} of this sweep ({}): "
                      "give another --out, or leave out --resume to start again",
                      (*old)["shard"].get<int>(), (*old)["shards"].get<int>(),
                      (*old)["sweep_id"].get<std::string>(), options.sweep.shard,
                      options.sweep.shards, options.sweep.id));
    r.sweep_cases = std::max(r.sweep_cases, (*old)["cases"].get<std::size_t>());
  }
  std::map<std::size_t, std::size_t> position;  // case id -> index in `ids`
  for (std::size_t i = 0; i < n; ++i) position[cases.ids[i]] = i;
  for (auto& [id, line] : read_results(results_path, true)) {
    if (auto it = position.find(id); it != position.end()) {
      r.lines[it->second] = std::move(line);
      ++r.count;
    } else if (in_shard(id, r.sweep_cases, options.sweep.shard, options.sweep.shards)) {
      r.beyond.emplace(id, std::move(line));
    }
  }
  return r;
}

/// Stage 2, the folder: created only now, after every check (bad input leaves no folder behind),
/// cleared of stale per-case files, with this shard's sweep.json.
void prepare_folder(const CaseList& cases, const BatchOptions& options, const ResumedLines& r) {
  ensure_directory(options.out_dir);
  // Per-case pictures and bags are stale unless their case's line is kept (so all of them in a
  // fresh batch): a case that runs now writes its own, an unfinished case or a case of no sweep
  // must not show one. The cases of another shard (folders shared by shards) are not ours.
  std::set<std::size_t> kept;
  for (std::size_t i = 0; i < r.lines.size(); ++i)
    if (r.lines[i]) kept.insert(cases.ids[i]);
  for (const auto& line : r.beyond) kept.insert(line.first);
  const auto stale = [&](std::size_t id) {
    return !kept.count(id) &&
           (id >= r.sweep_cases ||
            in_shard(id, r.sweep_cases, options.sweep.shard, options.sweep.shards));
  };
  if (options.pictures != BatchPictures::None)
    remove_stale_case_files(options.pictures_dir, {".svg", ".html"}, stale);
  if (options.mcap != BatchPictures::None)
    remove_stale_case_files(options.mcap_dir, {".mcap"}, stale);
  SweepInfo written = options.sweep;
  written.cases = r.sweep_cases;
  write_file_atomically(
      options.out_dir / "sweep.json",
      sweep_json_text(written, shard_size(r.sweep_cases, written.shard, written.shards)));
}

/// Stage 3, the ordered writer: results.jsonl while the batch runs. The resumed lines are
/// rewritten first (atomically, so that the file never holds a case twice), then each fresh line
/// is appended in case order as soon as every line before it is finished. Every write and flush
/// is checked: after the first failure (a full disk) nothing more is written.
class OrderedWriter {
 public:
  OrderedWriter(std::filesystem::path path, const ResumedLines& resumed)
      : path_(std::move(path)), file_(nullptr, &std::fclose) {
    write_file_atomically(path_, [&](const std::function<void(std::string_view)>& sink) {
      for (const auto& l : resumed.lines)
        if (l) sink(l->dump() + "\n");
      for (const auto& [id, l] : resumed.beyond) sink(l.dump() + "\n");
    });
    file_.reset(std::fopen(path_.c_str(), "a"));
    if (!file_)
      throw OutputError(path_.string(), std::string("cannot write: ") + std::strerror(errno));
  }

  /// Appends the fresh lines from the first one not written yet up to the first unfinished case.
  void append_ready(const std::vector<std::optional<Json>>& lines, const std::vector<bool>& fresh) {
    while (error_.empty() && written_upto_ < lines.size() && lines[written_upto_]) {
      if (fresh[written_upto_]) append(*lines[written_upto_]);
      ++written_upto_;
    }
  }

  /// Appends the fresh lines left (finished out of order before an interruption: kept too) and
  /// closes the file.
  void close(const std::vector<std::optional<Json>>& lines, const std::vector<bool>& fresh) {
    for (std::size_t i = written_upto_; i < lines.size() && error_.empty(); ++i)
      if (lines[i] && fresh[i]) append(*lines[i]);
    if (std::fclose(file_.release()) != 0 && error_.empty()) error_ = std::strerror(errno);
  }

  bool failed() const { return !error_.empty(); }

  /// The OutputError of the first failed write, if there was one.
  void throw_if_failed() const {
    if (failed())
      throw OutputError(path_.string(),
                        "cannot write: " + error_ + " (the batch stopped; --resume goes on)");
  }

 private:
  void append(const Json& l) {
    const std::string text = l.dump() + "\n";
    if (std::fputs(text.c_str(), file_.get()) < 0 || std::fflush(file_.get()) != 0)
      error_ = std::strerror(errno);
  }

  std::filesystem::path path_;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file_;
  std::size_t written_upto_{0};  // fresh lines [0, written_upto_) are on disk
  std::string error_;
};

/// Stage 4, the pool: worker threads take the unfinished cases in order and run them, while the
/// calling thread writes the finished lines in order and reports progress. A worker's failure, a
/// failed write or the user's stop halts it: the workers abandon their cases.
class CasePool {
 public:
  CasePool(const CaseList& cases, const BatchOptions& options,
           std::vector<std::optional<Json>>& lines)
      : cases_(cases), options_(options), lines_(lines), fresh_(lines.size(), false) {
    for (std::size_t i = 0; i < lines.size(); ++i)
      if (!lines[i]) todo_.push_back(i);
    done_ = lines.size() - todo_.size();
  }

  /// Runs the cases until all are done or the pool halts, appending their lines to `writer`.
  /// Rethrows a worker's exception (after the writer's own error, which comes first).
  void run(OrderedWriter& writer) {
    const auto t0 = std::chrono::steady_clock::now();
    {
      Workers workers{{}, halt_};
      const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
      const int jobs = options_.jobs > 0 ? options_.jobs : static_cast<int>(hw);
      const int count = std::max(1, std::min<int>(jobs, static_cast<int>(todo_.size())));
      for (int k = 0; k < count && !todo_.empty(); ++k)
        workers.threads.emplace_back(&CasePool::work, this);
      for (bool over = false; !over;) over = write_ready(writer, t0);
      for (auto& t : workers.threads) t.join();
    }
    writer.close(lines_, fresh_);
    report(t0, true);
    writer.throw_if_failed();
    if (failure_) std::rethrow_exception(failure_);
  }

  std::size_t ran() const { return ran_; }

 private:
  /// Whatever leaves `run` (a writer that throws, an allocation that fails) leaves it with every
  /// worker stopped and joined: an exception never passes a joinable thread (which would end the
  /// process), and the caller's error message is the one printed.
  struct Workers {
    std::vector<std::thread> threads;
    std::atomic<bool>& halt;
    ~Workers() {
      halt.store(true);
      for (auto& t : threads)
        if (t.joinable()) t.join();
    }
  };

  bool user_stop() const { return options_.stop && options_.stop->load(); }

  /// A worker: takes the next case until none is left or the pool halts.
  void work() {
    OptimumCache optimum_cache;
    for (std::size_t i; take(i);) {
      std::optional<Json> line;
      try {
        const BatchCase c = cases_.make(cases_.ids[i]);
        line = run_case(c, options_, &halt_, optimum_cache);
      } catch (...) {
        std::lock_guard lock(mutex_);
        if (!failure_) failure_ = std::current_exception();
        halt_.store(true);
      }
      hand_in(i, std::move(line));
    }
  }

  bool take(std::size_t& i) {
    std::lock_guard lock(mutex_);
    if (next_job_ >= todo_.size() || halt_.load() || user_stop()) return false;
    i = todo_[next_job_++];
    return true;
  }

  /// A finished case's line (none when the case was abandoned or failed).
  void hand_in(std::size_t i, std::optional<Json> line) {
    {
      std::lock_guard lock(mutex_);
      if (line) {
        lines_[i] = std::move(line);
        fresh_[i] = true;
        ++done_;
        ++ran_;
      }
    }
    cv_.notify_one();
  }

  /// One round of the calling thread: waits for a line (at most 100 ms), appends what is ready in
  /// order and reports progress. True when every case is done, or when the pool halted and no
  /// case is left to start.
  bool write_ready(OrderedWriter& writer, std::chrono::steady_clock::time_point t0) {
    std::unique_lock lock(mutex_);
    cv_.wait_for(lock, std::chrono::milliseconds(100));
    if (user_stop()) halt_.store(true);
    writer.append_ready(lines_, fresh_);
    if (writer.failed()) halt_.store(true);
    const bool all_done = done_ == lines_.size();
    const bool idle = next_job_ >= todo_.size() || halt_.load();
    report(t0, false);
    return all_done || (idle && halt_.load());
  }

  void report(std::chrono::steady_clock::time_point t0, bool finished) const {
    if (!options_.progress) return;
    BatchProgress p;
    p.done = done_;
    p.total = lines_.size();
    p.elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    p.finished = finished;
    options_.progress(p);
  }

  const CaseList& cases_;
  const BatchOptions& options_;
  std::vector<std::optional<Json>>& lines_;  // by position in the case list
  std::vector<bool> fresh_;                  // lines run by this call (not resumed)
  std::vector<std::size_t> todo_;            // positions of the unfinished cases
  std::mutex mutex_;
  std::condition_variable cv_;
  std::size_t next_job_{0}, done_{0}, ran_{0};
  std::atomic<bool> halt_{false};  // the user's stop, or a failure: workers abandon their cases
  std::exception_ptr failure_;
};

/// Stage 5, aggregation: the outcome and aggregate.json; results.jsonl in canonical form (every
/// line in case order, whatever order resumed runs appended them in) when nothing was interrupted.
BatchOutcome aggregate_batch(const BatchOptions& options, ResumedLines& r, std::size_t ran) {
  const std::size_t n = r.lines.size();
  BatchOutcome outcome;
  outcome.total = n;
  outcome.resumed = r.count;
  outcome.ran = ran;
  std::vector<Json> finished;
  for (auto& l : r.lines)
    if (l) finished.push_back(*l);
  outcome.completed = finished.size();
  outcome.interrupted = outcome.completed < n;
  // Lines kept from beyond this call's cases come after its own (their numbers are larger).
  for (auto& [id, l] : r.beyond) finished.push_back(std::move(l));
  outcome.aggregate = aggregate_results(finished);
  outcome.aggregate["sweep_id"] = options.sweep.id;
  outcome.aggregate["complete"] =
      !outcome.interrupted &&
      finished.size() >= shard_size(r.sweep_cases, options.sweep.shard, options.sweep.shards);
  if (!outcome.interrupted) {
    write_file_atomically(options.out_dir / "results.jsonl",
                          [&](const std::function<void(std::string_view)>& sink) {
                            for (const Json& l : finished) sink(l.dump() + "\n");
                          });
  }
  write_file_atomically(options.out_dir / "aggregate.json", outcome.aggregate.dump(2) + "\n");
  return outcome;
}

}  // namespace

BatchOutcome run_batch(const CaseList& cases, const BatchOptions& options) {
  ResumedLines resumed = read_resumed_lines(cases, options);
  prepare_folder(cases, options, resumed);
  OrderedWriter writer(options.out_dir / "results.jsonl", resumed);
  CasePool pool(cases, options, resumed.lines);
  pool.run(writer);
  return aggregate_batch(options, resumed, pool.ran());
}

double barn_score(bool success, double time, double optimal_time) {
  if (!success || !(optimal_time > 0.0)) return 0.0;
  return optimal_time / std::clamp(time, 2.0 * optimal_time, 8.0 * optimal_time);
}

std::vector<BatchCase> select_shard(std::vector<BatchCase> cases, int k, int n) {
  std::vector<BatchCase> out;
  for (std::size_t i = 0; i < cases.size(); ++i)
    if (static_cast<int>(i % static_cast<std::size_t>(n)) == k - 1)
      out.push_back(std::move(cases[i]));
  return out;
}

std::vector<std::size_t> shard_ids(std::size_t count, int k, int n) {
  std::vector<std::size_t> out;
  for (std::size_t i = static_cast<std::size_t>(k - 1); i < count; i += static_cast<std::size_t>(n))
    out.push_back(i);
  return out;
}

namespace {

/// A batch folder given to merge, with its sweep.json.
struct ShardFolder {
  std::filesystem::path dir;
  Json sweep;
};

/// Merge stage 1: every folder exists and has a sweep.json.
std::vector<ShardFolder> read_shard_folders(std::span<const std::filesystem::path> dirs) {
  std::vector<ShardFolder> shards;
  for (const auto& d : dirs) {
    std::error_code ec;
    if (!std::filesystem::is_directory(d, ec))
      throw InputError(d.string(), "",
                       std::filesystem::exists(d, ec) ? "is not a directory (a batch --out folder)"
                                                      : "does not exist");
    auto s = read_sweep(d);
    if (!s)
      throw InputError(d.string(), "",
                       "has no sweep.json: not a folder written by floornav batch (or by a version "
                       "before sweeps were checked); its shards cannot be checked");
    shards.push_back({d, std::move(*s)});
  }
  return shards;
}

/// The shards of one sweep, by shard number.
struct SweepShards {
  std::string id;
  int n{1};              ///< shards of the sweep
  std::size_t total{0};  ///< cases of the sweep
  std::map<int, std::filesystem::path> by_shard;
};

/// Merge stage 2: one sweep, one shard count, each shard once.
SweepShards check_one_sweep(const std::vector<ShardFolder>& shards) {
  const Json& first = shards.front().sweep;
  SweepShards out;
  out.id = first["sweep_id"];
  out.n = first["shards"];
  out.total = first["cases"];
  const int n = out.n;
  for (const ShardFolder& s : shards) {
    if (s.sweep["sweep_id"] != out.id || s.sweep["cases"] != out.total)
      throw InputError(
          s.dir.string(), "",
          fmt::format("is sweep {} ({} cases), but {} is sweep {} ({} cases): mixed "
                      "sweeps cannot be merged",
                      s.sweep["sweep_id"].get<std::string>(), s.sweep["cases"].get<std::size_t>(),
                      shards.front().dir.string(), out.id, out.total));
    if (s.sweep["shards"] != n)
      throw InputError(s.dir.string(), "",
                       fmt::format("is shard {}/{}, but {} is a shard of {}: the same sweep split "
                                   "two ways cannot be merged",
                                   s.sweep["shard"].get<int>(), s.sweep["shards"].get<int>(),
                                   shards.front().dir.string(), n));
    const int k = s.sweep["shard"];
    if (k < 1 || k > n)
      throw InputError((s.dir / "sweep.json").string(), "", fmt::format("shard {}/{}?", k, n));
    if (auto [it, fresh] = out.by_shard.emplace(k, s.dir); !fresh)
      throw InputError(s.dir.string(), "",
                       fmt::format("is shard {}/{} again (so is {}): give each shard once", k, n,
                                   it->second.string()));
  }
  return out;
}

/// Merge stage 3: the shards not given; an error unless `allow_partial`.
std::vector<int> missing_shards(const SweepShards& s, bool allow_partial) {
  std::vector<int> missing_ones;
  for (int k = 1; k <= s.n; ++k)
    if (!s.by_shard.count(k)) missing_ones.push_back(k);
  if (missing_ones.empty() || allow_partial) return missing_ones;
  std::string missing;
  for (std::size_t i = 0; i < missing_ones.size(); ++i)
    missing += (i ? ", " : "") + fmt::format("{}/{}", missing_ones[i], s.n);
  throw InputError("", "merge",
                   fmt::format("shard{} {} of sweep {} {} missing: give every shard's folder "
                               "(or --allow-partial to merge what there is, marked incomplete)",
                               missing_ones.size() == 1 ? "" : "s", missing, s.id,
                               missing_ones.size() == 1 ? "is" : "are"));
}

/// Merge stage 4: the lines of shard k, which holds exactly its own cases, and all of them unless
/// `allow_partial`. Checked by arithmetic on the case numbers, never by listing a shard's cases:
/// sweep.json's count is bounded (kMaxSweepCases) but still far more than needs to be held.
std::map<std::size_t, Json> read_shard_lines(const std::filesystem::path& dir, int k,
                                             const SweepShards& s, bool allow_partial) {
  const int n = s.n;
  const std::size_t total = s.total;
  auto lines = read_results(dir / "results.jsonl", false);
  for (const auto& [case_id, line] : lines)
    if (!in_shard(case_id, total, k, n))
      throw InputError((dir / "results.jsonl").string(), "",
                       fmt::format("holds case {}, which is not a case of shard {}/{} of {} cases",
                                   case_id, k, n, total));
  const std::size_t expected = shard_size(total, k, n);
  if (lines.size() < expected && !allow_partial) {
    std::vector<std::size_t> missing;  // the first few, for the message
    for (std::size_t i = static_cast<std::size_t>(k - 1); i < total && missing.size() < 5;
         i += static_cast<std::size_t>(n))
      if (!lines.count(i)) missing.push_back(i);
    const std::size_t more = expected - lines.size() - missing.size();
    throw InputError(dir.string(), "",
                     fmt::format("shard {}/{} is incomplete: {} of its {} cases are missing "
                                 "(case {}{}); finish it with --resume, or --allow-partial",
                                 k, n, expected - lines.size(), expected, list_cases(missing),
                                 more ? fmt::format(" and {} more", more) : std::string()));
  }
  return lines;
}

}  // namespace

MergeOutcome merge_batches(std::span<const std::filesystem::path> dirs,
                           const std::filesystem::path& out_dir, bool allow_partial) {
  if (dirs.empty()) throw InputError("", "merge", "no batch folders given");
  const SweepShards sweep = check_one_sweep(read_shard_folders(dirs));
  MergeOutcome outcome;
  outcome.total = sweep.total;
  outcome.missing_shards = missing_shards(sweep, allow_partial);
  std::map<std::size_t, Json> all;
  for (const auto& [k, dir] : sweep.by_shard) {
    auto lines = read_shard_lines(dir, k, sweep, allow_partial);
    all.merge(lines);
  }
  std::vector<Json> lines;
  lines.reserve(all.size());
  for (auto& [case_id, j] : all) lines.push_back(std::move(j));
  outcome.merged = lines.size();
  outcome.complete = outcome.merged == sweep.total;
  outcome.aggregate = aggregate_results(lines);
  outcome.aggregate["sweep_id"] = sweep.id;
  outcome.aggregate["complete"] = outcome.complete;
  if (!outcome.complete) outcome.aggregate["missing_cases"] = sweep.total - outcome.merged;
  // The merged folder is the whole sweep as one batch (shard 1 of 1): merged files equal one
  // big run's. All three appear together.
  OutputFolder folder(out_dir);
  folder.write("results.jsonl", [&](const std::function<void(std::string_view)>& sink) {
    for (const Json& l : lines) sink(l.dump() + "\n");
  });
  folder.write("aggregate.json", outcome.aggregate.dump(2) + "\n");
  SweepInfo merged{sweep.id, 1, 1, sweep.total};
  folder.write("sweep.json", sweep_json_text(merged, outcome.merged));
  folder.commit();
  return outcome;
}

}  // namespace floornav
