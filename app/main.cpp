// floornav: the command line. Subcommands: run, batch, demo, presets.
// Exit status: 0 when the simulation(s) ran, 2 for bad input, 1 for an internal error.

#include <fmt/format.h>
#include <unistd.h>
#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "batch_sources.hpp"
#include "bench_command.hpp"
#include "demo_scenario.hpp"
#include "floornav/core/input_error.hpp"
#include "floornav/io/scenario_file.hpp"
#include "floornav/robot/robot_spec.hpp"
#include "floornav/runner/batch.hpp"
#include "floornav/runner/run_outputs.hpp"
#include "floornav/scenario/presets.hpp"

namespace fs = std::filesystem;
using namespace floornav;

namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) {
  g_stop.store(true);
}

std::string default_out_dir(const std::string& name) {
  return (fs::path("out") / name).string();
}

int run_one(Scenario scenario, const std::string& out, bool quiet, int threads, bool html) {
  const fs::path dir = out.empty() ? fs::path(default_out_dir(scenario.name)) : fs::path(out);
  OutputSelection which;
  which.html = html;
  prepare_outputs(scenario, which);
  if (scenario.is_fleet()) {
    const FleetResult f = run_fleet_timed(scenario, threads);
    write_fleet_outputs(dir, scenario, f, which);
    if (!quiet) fmt::print("{} -> {}\n", describe_fleet(f), dir.string());
    return 0;
  }
  const RunResult r = run_timed(scenario);
  write_run_outputs(dir, scenario, r, which);
  if (!quiet) fmt::print("{} -> {}\n", describe_run(r), dir.string());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"floornav: reactive navigation of wheeled mobile robots on factory floors"};
  app.set_version_flag("--version", std::string("floornav ") + FLOORNAV_VERSION);
  app.require_subcommand(1);

  // run
  std::string run_file, run_out;
  std::vector<std::string> run_sets;
  bool run_quiet = false, run_no_html = false;
  auto* run = app.add_subcommand("run",
                                 "Simulate one scenario; writes summary.json, "
                                 "trajectory.csv, trajectory.svg and trajectory.html");
  run->add_option("scenario", run_file, "scenario YAML file")->required();
  run->add_option("--out", run_out, "output folder (default: out/<scenario name>)");
  run->add_option("--set", run_sets, "override a scenario key: --set controller.kind=blended")
      ->take_all();
  run->add_flag("-q,--quiet", run_quiet, "print nothing on success");
  run->add_flag("--no-html", run_no_html, "do not write trajectory.html (the replay)");
  int run_threads = 0;
  run->add_option("--threads", run_threads,
                  "threads stepping a fleet's robots (default: all cores; same result for any)")
      ->check(CLI::Range(1, 1024));

  // batch
  std::vector<std::string> batch_files, batch_sets;
  std::string batch_out = "out/batch", batch_scen;
  int batch_jobs = 0;
  double batch_cell = 0.0;
  long batch_limit = -1;
  bool batch_no_timing = false, batch_resume = false, batch_no_optimum = false;
  std::string batch_worlds, batch_barn_paths, batch_shard;
  std::vector<std::string> batch_pictures;
  auto* batch = app.add_subcommand("batch",
                                   "Run many scenarios in parallel; writes "
                                   "results.jsonl and aggregate.json");
  batch->add_option("scenarios", batch_files, "scenario YAML files (or one template with --scen)")
      ->required();
  batch->add_option("--jobs,-j", batch_jobs, "worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  batch->add_option("--out", batch_out, "output folder (default: out/batch)");
  batch->add_option("--set", batch_sets, "override a key in every scenario")->take_all();
  batch->add_option("--scen", batch_scen, "MovingAI .scen file: one case per row, on its map");
  batch->add_option("--cell-size", batch_cell, "metres per grid cell for --scen (default 1)")
      ->check(CLI::PositiveNumber);
  batch->add_option("--limit", batch_limit, "run only the first N cases")
      ->check(CLI::NonNegativeNumber);
  batch->add_flag("--no-timing", batch_no_timing,
                  "write wall_time as 0 so that repeated runs give identical files");
  batch->add_flag("--resume", batch_resume, "keep the cases already in results.jsonl");
  batch->add_flag("--no-optimum", batch_no_optimum,
                  "skip the grid A* optimal path length (and path_efficiency) where no .scen "
                  "file gives the optimum");
  batch->add_option("--worlds", batch_worlds,
                    "folder of Gazebo .world/.sdf files: one case per world, on the template");
  batch->add_option("--barn-paths", batch_barn_paths,
                    "with --worlds: BARN path_N.npy folder, adds optimal_time and the BARN score");
  batch->add_option("--shard", batch_shard,
                    "K/N: run only shard K of N (every N-th case); join shards with merge");

  batch
      ->add_option(
          "--pictures", batch_pictures,
          "failed|all DIR: an SVG and an HTML replay of each failed (or every) case in DIR")
      ->expected(2);

  // merge
  std::vector<std::string> merge_dirs;
  std::string merge_out = "out/merged";
  auto* merge = app.add_subcommand("merge", "Join the results of sharded batches");
  merge->add_option("dirs", merge_dirs, "batch output folders")->required();
  merge->add_option("--out", merge_out, "output folder (default: out/merged)");

  // demo
  std::string demo_out;
  auto* demo = app.add_subcommand("demo", "Run the built-in factory floor demo (no files needed)");
  demo->add_option("--out", demo_out, "output folder (default: out/factory-delivery)");
  bool demo_no_html = false;
  demo->add_flag("--no-html", demo_no_html, "do not write trajectory.html (the replay)");

  // bench
  BenchOptions bench_opt;
  auto* bench = app.add_subcommand("bench", "Measure simulation speed on the standard cases");
  bench->add_flag("--json", bench_opt.json, "one JSON object instead of the table");
  bench->add_option("--seconds", bench_opt.seconds_per_case, "timed seconds per case (default 1)")
      ->check(CLI::PositiveNumber);
  bench->add_option("--filter", bench_opt.filter, "only cases whose name contains this");

  // presets
  auto* presets = app.add_subcommand("presets", "List the robot presets");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  try {
    if (*run) {
      const Scenario s = load_scenario_file(run_file, run_sets);
      return run_one(s, run_out, run_quiet, run_threads, !run_no_html);
    }
    if (*demo) {
      const Scenario s = load_scenario_text(app::kDemoScenarioYaml, "factory-delivery.yaml");
      return run_one(s, demo_out, false, 0, !demo_no_html);
    }
    if (*bench) return run_bench(bench_opt);
    if (*presets) {
      for (auto name : robot_preset_names()) {
        const RobotPreset p = *find_robot_preset(name);
        fmt::print(
            "{:<18} R {:.4f} m, L {:.4f} m, body radius {:.3f} m, max {:.2f} m/s, {} "
            "range sensors {:.2f}-{:.2f} m\n",
            name, p.robot.drive.wheel_radius, p.robot.drive.track_width, p.robot.body_radius,
            max_forward_speed(p.robot.drive), p.robot.sensors.size(),
            p.robot.sensors.front().min_range, p.robot.sensors.front().max_range);
      }
      return 0;
    }
    if (*batch) {
      std::vector<BatchCase> cases;
      if (!batch_worlds.empty()) {
        if (batch_files.size() != 1)
          throw InputError("", "--worlds", "give exactly one template scenario with --worlds");
        cases = make_world_cases(batch_files[0], batch_worlds, batch_barn_paths, batch_sets);
      } else if (!batch_scen.empty()) {
        if (batch_files.size() != 1)
          throw InputError("", "--scen", "give exactly one template scenario with --scen");
        cases = make_scen_cases(batch_files[0], batch_scen, batch_cell > 0 ? batch_cell : 1.0,
                                batch_sets);
      } else {
        for (const auto& f : batch_files)
          cases.push_back({load_scenario_file(f, batch_sets), f, cases.size(), {}, {}});
      }
      if (batch_limit >= 0 && static_cast<std::size_t>(batch_limit) < cases.size())
        cases.resize(static_cast<std::size_t>(batch_limit));
      if (!batch_shard.empty()) {
        int k = 0, n = 0;
        char slash = 0;
        std::istringstream ss(batch_shard);
        if (!(ss >> k >> slash >> n) || slash != '/' || n < 1 || k < 1 || k > n || !ss.eof())
          throw InputError("", "--shard",
                           "expected K/N with 1 <= K <= N, got '" + batch_shard + "'");
        cases = select_shard(std::move(cases), k, n);
      }
      std::signal(SIGINT, on_signal);
      std::signal(SIGTERM, on_signal);
      BatchOptions opt;
      opt.jobs = batch_jobs;
      opt.out_dir = batch_out;
      opt.progress = isatty(STDERR_FILENO) != 0;
      opt.timing = !batch_no_timing;
      opt.resume = batch_resume;
      opt.optimum = !batch_no_optimum;
      opt.stop = &g_stop;
      if (!batch_pictures.empty()) {
        if (batch_pictures[0] == "failed")
          opt.pictures = BatchPictures::Failed;
        else if (batch_pictures[0] == "all")
          opt.pictures = BatchPictures::All;
        else
          throw InputError("", "--pictures",
                           "expected failed or all, got '" + batch_pictures[0] + "'");
        opt.pictures_dir = batch_pictures[1];
      }
      const BatchOutcome o = run_batch(cases, opt);
      const auto& a = o.aggregate;
      fmt::print(
          "{} of {} cases{}: success {:.1f}%, collision {:.1f}%, timeout {:.1f}%, stuck "
          "{:.1f}% -> {}\n",
          o.completed, o.total, o.interrupted ? " (interrupted; --resume completes it)" : "",
          100.0 * a["success_rate"].get<double>(), 100.0 * a["collision_rate"].get<double>(),
          100.0 * a["timeout_rate"].get<double>(), 100.0 * a["stuck_rate"].get<double>(),
          batch_out);
      return o.interrupted ? 130 : 0;
    }
    if (*merge) {
      std::vector<fs::path> dirs(merge_dirs.begin(), merge_dirs.end());
      const auto a = merge_batches(dirs, merge_out);
      fmt::print("{} cases merged: success {:.1f}% -> {}\n", a["runs"].get<std::size_t>(),
                 100.0 * a["success_rate"].get<double>(), merge_out);
      return 0;
    }
  } catch (const InputError& e) {
    fmt::print(stderr, "floornav: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "floornav: internal error: {}\n", e.what());
    return 1;
  }
  return 0;
}
