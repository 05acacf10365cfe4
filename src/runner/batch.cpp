#include "floornav/runner/batch.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <thread>

#include "floornav/core/input_error.hpp"
#include "floornav/io/atomic_file.hpp"
#include "floornav/io/summary_json.hpp"
#include "floornav/render/trajectory_html.hpp"
#include "floornav/render/trajectory_svg.hpp"
#include "floornav/runner/run_outputs.hpp"
#include "floornav/world/shortest_path.hpp"

namespace floornav {

namespace {

/// The grid optimum of a case's scenario: a length in metres, or the reason there is none.
Optimum case_optimum(const Scenario& s) {
  if (!s.world) return {};
  const RobotTask& t = s.robot();
  return scenario_optimum(*s.world, t.robot.body_radius, t.start.position, t.goals);
}

nlohmann::ordered_json result_line(const BatchCase& c, const RunResult& r, bool timing,
                                   const std::optional<Optimum>& optimum) {
  nlohmann::ordered_json line;
  line["case"] = c.id;
  line["source"] = c.source;
  line["controller"] = c.scenario.robot().controller.kind;
  line["robot"] = c.scenario.robot().robot.preset;
  const nlohmann::ordered_json summary = summary_to_json(r);
  for (const auto& [k, v] : summary.items()) line[k] = v;
  if (!timing) line["wall_time"] = 0.0;
  line.erase("transitions");  // the per-case detail stays out of a batch's lines
  line.erase("transitions_truncated");
  std::optional<double> optimal = c.optimal_length;
  if (optimum && optimum->status == OptimumStatus::Found) optimal = optimum->length;
  if (c.optimal_length || optimum) {
    line["optimal_length"] = optimal ? nlohmann::ordered_json(*optimal) : nullptr;
    line["path_efficiency"] = optimal && r.reached_goal && r.path_length > 0
                                  ? nlohmann::ordered_json(*optimal / r.path_length)
                                  : nlohmann::ordered_json(nullptr);
    line["optimal_source"] = c.optimal_length ? "scen" : "grid_astar";
  }
  if (optimum) {
    if (optimum->status == OptimumStatus::Found)
      line["optimal_octile_length"] = optimum->octile_length;
    else
      line["optimal_status"] = std::string(to_string(optimum->status));
    line["optimal_cell_size"] = optimum->cell_size;
  }
  if (c.optimal_time) {
    line["optimal_time"] = *c.optimal_time;
    line["score"] = barn_score(r.reached_goal && !r.collided, r.sim_time, *c.optimal_time);
  }
  return line;
}

// A fleet case's line: the fleet's summary without each robot's (which can be thousands).
nlohmann::ordered_json fleet_result_line(const BatchCase& c, const FleetResult& f, bool timing) {
  nlohmann::ordered_json line;
  line["case"] = c.id;
  line["source"] = c.source;
  line["controller"] = c.scenario.robot().controller.kind;
  line["robot"] = c.scenario.robot().robot.preset;
  nlohmann::ordered_json summary = fleet_summary_to_json(f);
  summary.erase("robots");
  for (auto& [k, v] : summary.items()) line[k] = std::move(v);
  if (!timing) line["wall_time"] = 0.0;
  return line;
}

// Reads a results.jsonl left by an earlier (interrupted) run: case index -> line.
std::map<std::size_t, nlohmann::ordered_json> read_existing(const std::filesystem::path& path) {
  std::map<std::size_t, nlohmann::ordered_json> out;
  std::ifstream in(path);
  std::string text;
  for (std::size_t n = 1; std::getline(in, text); ++n) {
    if (text.empty()) continue;
    try {
      auto j = nlohmann::ordered_json::parse(text);
      out[j.at("case").get<std::size_t>()] = std::move(j);
    } catch (const std::exception&) {
      // A line cut short by the interruption: that case simply runs again.
    }
  }
  return out;
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

void draw_progress(std::size_t done, std::size_t total, double elapsed) {
  const double rate = elapsed > 0 ? static_cast<double>(done) / elapsed : 0.0;
  const double eta = rate > 0 ? static_cast<double>(total - done) / rate : 0.0;
  constexpr int kWidth = 30;
  const int filled = total ? static_cast<int>(kWidth * done / total) : kWidth;
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(kWidth, '.');
  std::fprintf(stderr, "\r[%s] %zu/%zu  %.1f runs/s  ETA %.0f s ", bar.c_str(), done, total, rate,
               eta);
  std::fflush(stderr);
}

}  // namespace

nlohmann::ordered_json aggregate_results(const std::vector<nlohmann::ordered_json>& lines) {
  struct Totals {
    std::size_t n = 0, reached = 0, collision = 0, timeout = 0, stuck = 0;
    double time_sum = 0, path_sum = 0, clearance_min = 1e300;
    std::size_t efficiency_n = 0, score_n = 0, optimum_n = 0;
    double efficiency_sum = 0, score_sum = 0, optimum_sum = 0;
    std::map<std::string, std::size_t> optimum_sources;
  };
  auto add = [](Totals& t, const nlohmann::ordered_json& l) {
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
    if (l.contains("min_clearance") && l["min_clearance"].is_number())
      t.clearance_min = std::min(t.clearance_min, l["min_clearance"].get<double>());
  };
  auto render = [](const Totals& t) {
    nlohmann::ordered_json j;
    const double n = t.n ? static_cast<double>(t.n) : 1.0;
    j["runs"] = t.n;
    j["reached"] = t.reached;
    j["success_rate"] = static_cast<double>(t.reached) / n;
    j["collision_rate"] = static_cast<double>(t.collision) / n;
    j["timeout_rate"] = static_cast<double>(t.timeout) / n;
    j["stuck_rate"] = static_cast<double>(t.stuck) / n;
    j["mean_time_reached"] =
        t.reached ? nlohmann::ordered_json(t.time_sum / static_cast<double>(t.reached)) : nullptr;
    j["mean_path_length_reached"] =
        t.reached ? nlohmann::ordered_json(t.path_sum / static_cast<double>(t.reached)) : nullptr;
    j["min_clearance"] = t.n ? nlohmann::ordered_json(t.clearance_min) : nullptr;
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
  nlohmann::ordered_json out = render(all);
  nlohmann::ordered_json kinds = nlohmann::ordered_json::object();
  for (const auto& [k, t] : by_kind) kinds[k] = render(t);
  out["by_controller"] = kinds;
  return out;
}

nlohmann::ordered_json run_batch_case(const BatchCase& c, const BatchOptions& options) {
  Scenario sc = c.scenario;  // shares the world; copies only small data
  const bool pictures = options.pictures != BatchPictures::None;
  sc.sim.record_trajectory = pictures;
  if (pictures) prepare_outputs(sc);
  const std::filesystem::path stem = options.pictures_dir / picture_stem(c);
  if (sc.is_fleet()) {
    // A fleet: one thread per case, like every case (the batch is parallel across cases).
    const FleetResult f = run_fleet_timed(sc, 1);
    if (wants_picture(options.pictures, f.status)) {
      write_file_atomically(stem.string() + ".svg", render_fleet_svg(sc, f));
      write_file_atomically(stem.string() + ".html", render_fleet_html(sc, f));
    }
    return fleet_result_line(c, f, options.timing);
  }
  std::optional<Optimum> optimum;
  if (options.optimum && !c.optimal_length) optimum = case_optimum(sc);
  const RunResult r = run_timed(sc);
  if (wants_picture(options.pictures, r.status)) {
    write_file_atomically(stem.string() + ".svg", render_trajectory_svg(sc, r));
    write_file_atomically(stem.string() + ".html", render_trajectory_html(sc, r));
  }
  return result_line(c, r, options.timing, optimum);
}

BatchOutcome run_batch(std::span<const BatchCase> cases, const BatchOptions& options) {
  ensure_directory(options.out_dir);
  if (options.pictures != BatchPictures::None) ensure_directory(options.pictures_dir);
  const auto results_path = options.out_dir / "results.jsonl";
  const std::size_t n = cases.size();
  std::vector<std::optional<nlohmann::ordered_json>> lines(n);
  if (options.resume) {
    std::map<std::size_t, std::size_t> position;  // case id -> index in `cases`
    for (std::size_t i = 0; i < n; ++i) position[cases[i].id] = i;
    for (auto& [id, line] : read_existing(results_path))
      if (auto it = position.find(id); it != position.end()) lines[it->second] = std::move(line);
  }

  std::vector<std::size_t> todo;
  for (std::size_t i = 0; i < n; ++i)
    if (!lines[i]) todo.push_back(i);

  // Lines are appended in case order; a finished case waits until all before it are written.
  // The file is rewritten (atomically) at the end, so resumed files end up identical too.
  std::FILE* out = std::fopen(results_path.c_str(), options.resume ? "a" : "w");
  if (!out) throw InputError(results_path.string(), "", "cannot open for writing");

  std::mutex mutex;
  std::condition_variable cv;
  std::size_t next_job = 0, done = n - todo.size();
  std::vector<bool> fresh(n, false);
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  const int jobs = options.jobs > 0 ? options.jobs : static_cast<int>(hw);
  auto stopped = [&] { return options.stop && options.stop->load(); };

  auto worker = [&] {
    while (true) {
      std::size_t i;
      {
        std::lock_guard lock(mutex);
        if (next_job >= todo.size() || stopped()) return;
        i = todo[next_job++];
      }
      nlohmann::ordered_json line = run_batch_case(cases[i], options);
      {
        std::lock_guard lock(mutex);
        lines[i] = std::move(line);
        fresh[i] = true;
        ++done;
      }
      cv.notify_one();
    }
  };

  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::thread> threads;
  const int workers = std::max(1, std::min<int>(jobs, static_cast<int>(todo.size())));
  for (int k = 0; k < workers && !todo.empty(); ++k) threads.emplace_back(worker);

  // Writer loop: append finished lines in order while workers run.
  std::size_t written_upto = 0;  // fresh lines [0, written_upto) are on disk
  while (true) {
    std::unique_lock lock(mutex);
    cv.wait_for(lock, std::chrono::milliseconds(100));
    while (written_upto < n && lines[written_upto]) {
      if (fresh[written_upto]) {
        const std::string text = lines[written_upto]->dump() + "\n";
        if (std::fputs(text.c_str(), out) < 0) {
          std::fclose(out);
          throw InputError(results_path.string(), "", "write failed (disk full?)");
        }
      }
      ++written_upto;
    }
    std::fflush(out);
    const bool all_done = done == n;
    const bool workers_idle = next_job >= todo.size() || stopped();
    if (options.progress)
      draw_progress(done, n,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    if (all_done || (workers_idle && stopped())) break;
  }
  for (auto& t : threads) t.join();
  // Lines finished out of order before an interruption are kept too.
  for (std::size_t i = written_upto; i < n; ++i)
    if (lines[i] && fresh[i]) std::fputs((lines[i]->dump() + "\n").c_str(), out);
  std::fclose(out);
  if (options.progress) std::fprintf(stderr, "\n");

  BatchOutcome outcome;
  outcome.total = n;
  std::vector<nlohmann::ordered_json> finished;
  for (auto& l : lines)
    if (l) finished.push_back(*l);
  outcome.completed = finished.size();
  outcome.interrupted = outcome.completed < n;
  outcome.aggregate = aggregate_results(finished);
  outcome.aggregate["complete"] = !outcome.interrupted;
  if (!outcome.interrupted) {
    // Canonical form: every line in case order, whatever order resumed runs appended them in.
    std::string all;
    for (auto& l : finished) all += l.dump() + "\n";
    write_file_atomically(results_path, all);
  }
  write_file_atomically(options.out_dir / "aggregate.json", outcome.aggregate.dump(2) + "\n");
  return outcome;
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

nlohmann::ordered_json merge_batches(std::span<const std::filesystem::path> dirs,
                                     const std::filesystem::path& out_dir) {
  std::map<std::size_t, nlohmann::ordered_json> all;
  for (const auto& d : dirs) {
    const auto path = d / "results.jsonl";
    std::ifstream in(path);
    if (!in) throw InputError(path.string(), "", "cannot open for reading");
    std::string text;
    for (std::size_t n = 1; std::getline(in, text); ++n) {
      if (text.empty()) continue;
      nlohmann::ordered_json j;
      try {
        j = nlohmann::ordered_json::parse(text);
      } catch (const std::exception&) {
        throw InputError(path.string(), "line " + std::to_string(n), "not a JSON line");
      }
      if (!j.contains("case") || !j["case"].is_number_unsigned())
        throw InputError(path.string(), "line " + std::to_string(n), "no case number");
      const auto id = j["case"].get<std::size_t>();
      if (auto it = all.find(id); it != all.end() && it->second != j)
        throw InputError(path.string(), "line " + std::to_string(n),
                         "case " + std::to_string(id) + " differs from another shard's");
      all[id] = std::move(j);
    }
  }
  ensure_directory(out_dir);
  std::string text;
  std::vector<nlohmann::ordered_json> lines;
  for (auto& [id, j] : all) {
    text += j.dump() + "\n";
    lines.push_back(j);
  }
  write_file_atomically(out_dir / "results.jsonl", text);
  nlohmann::ordered_json aggregate = aggregate_results(lines);
  aggregate["complete"] = true;  // as far as the shards given go
  write_file_atomically(out_dir / "aggregate.json", aggregate.dump(2) + "\n");
  return aggregate;
}

}  // namespace floornav
