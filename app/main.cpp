// floornav: the command line. Subcommands: run, batch, sweep, merge, demo, bench, presets.
// Exit status: 0 when the simulation(s) ran, 2 for bad input (one line on stderr), 1 for an
// internal error, 130 when a batch was interrupted (its finished lines are kept).

#include <fmt/format.h>
#include <unistd.h>
#include <CLI/CLI.hpp>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "batch_sources.hpp"
#include "bench_command.hpp"
#include "demo_scenario.hpp"
#include "floornav/core/input_error.hpp"
#include "floornav/core/output_error.hpp"
#include "floornav/core/utf8.hpp"
#include "floornav/io/atomic_file.hpp"
#include "floornav/io/provenance.hpp"
#include "floornav/io/scenario_file.hpp"
#include "floornav/io/scenario_writer.hpp"
#include "floornav/robot/robot_spec.hpp"
#include "floornav/runner/batch.hpp"
#include "floornav/runner/run_outputs.hpp"
#include "floornav/runner/run_summary.hpp"
#include "floornav/scenario/presets.hpp"
#include "progress_bar.hpp"
#include "sweep_id.hpp"

namespace fs = std::filesystem;
using namespace floornav;

namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) {
  g_stop.store(true);
}

/// The `--record` list: command, heading, clearance, goal, ranges, or all.
RecordOptions parse_record(const std::string& list) {
  RecordOptions r;
  std::stringstream ss(list);
  for (std::string item; std::getline(ss, item, ',');) {
    if (item == "command")
      r.command = true;
    else if (item == "heading")
      r.heading = true;
    else if (item == "clearance")
      r.clearance = true;
    else if (item == "goal")
      r.goal = true;
    else if (item == "ranges")
      r.ranges = true;
    else if (item == "all")
      r = {true, true, true, true, true};
    else
      throw InputError("", "--record " + list,
                       fmt::format("unknown column group '{}' (expected command, heading, "
                                   "clearance, goal, ranges or all, separated by commas)",
                                   item.substr(0, 40)));
  }
  return r;
}

/// Outputs appear whole: SIGINT and SIGTERM wait while they are written and moved into place.
class SignalsHeld {
 public:
  SignalsHeld() {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    sigaddset(&set, SIGHUP);
    sigprocmask(SIG_BLOCK, &set, &old_);
  }
  ~SignalsHeld() { sigprocmask(SIG_SETMASK, &old_, nullptr); }
  SignalsHeld(const SignalsHeld&) = delete;
  SignalsHeld& operator=(const SignalsHeld&) = delete;

 private:
  sigset_t old_;
};

struct RunRequest {
  std::string file;  ///< names the scenario in warnings
  std::string out;
  std::vector<std::string> sets;
  bool quiet{false};
  int threads{0};
  std::string config_out;
  std::string record;
  bool optimum{true};
  bool html{true};   ///< trajectory.html, the replay
  bool mcap{false};  ///< run.mcap, the ROS 2 bag
};

int run_one(Scenario scenario, const RunRequest& rq) {
  const fs::path dir =
      rq.out.empty() ? fs::path("out") / safe_file_name(scenario.name) : fs::path(rq.out);
  if (!rq.record.empty()) scenario.sim.record = parse_record(rq.record);
  OutputSelection which;
  which.html = rq.html;
  which.mcap = rq.mcap;
  // The run records what the replay and the bag need (the trajectory, sensor ranges); the files
  // describe the scenario as given, so that its provenance is the same with or without them.
  Scenario recorded = scenario;
  prepare_outputs(recorded, which);
  check_recording_limits(recorded, rq.file);
  if (!rq.config_out.empty()) write_file_atomically(rq.config_out, scenario_to_yaml(scenario));
  RunContext context;
  context.overrides = rq.sets;
  if (rq.optimum) context.optimum = compute_optimum(scenario);
  if (context.optimum)
    if (auto warning = reachability_warning(scenario, *context.optimum))
      fmt::print(stderr, "floornav: warning: {}: {}\n", rq.file, *warning);
  if (scenario.is_fleet()) {
    const FleetResult f = run_fleet_timed(recorded, rq.threads);
    {
      SignalsHeld held;
      write_fleet_outputs(dir, scenario, f, context, which);
    }
    if (!rq.quiet) fmt::print("{} -> {}\n", describe_fleet(f), dir.string());
    return 0;
  }
  const RunResult r = run_timed(recorded);
  {
    SignalsHeld held;
    write_run_outputs(dir, scenario, r, context, which);
  }
  if (!rq.quiet) fmt::print("{} -> {}\n", describe_run(r), dir.string());
  return 0;
}

/// K/N of --shard.
std::pair<int, int> parse_shard(const std::string& text) {
  int k = 0, n = 0;
  char slash = 0;
  std::istringstream ss(text);
  if (text.empty() || !(ss >> k >> slash >> n) || slash != '/' || n < 1 || k < 1 || k > n ||
      !ss.eof() || n > kMaxShards)
    throw InputError("", "--shard " + text, "expected K/N with 1 <= K <= N (e.g. --shard 2/16)");
  return {k, n};
}

/// --cell-size: a positive, finite number of metres.
double parse_cell_size(const std::string& text) {
  double v = 0.0;
  std::size_t used = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty() || !std::isfinite(v) || v <= 0.0 || v > 1e9)
    throw InputError("", "--cell-size " + text.substr(0, 40),
                     "must be a positive, finite number of metres per cell (at most 1e9)");
  return v;
}

/// `failed` or `all` of --pictures and --mcap.
BatchPictures parse_which_cases(const char* option, const std::string& text) {
  if (text == "failed") return BatchPictures::Failed;
  if (text == "all") return BatchPictures::All;
  throw InputError("", option, "expected failed or all, got '" + text.substr(0, 40) + "'");
}

/// The options batch and sweep share.
struct BatchRequest {
  std::vector<std::string> sets;
  std::string out;
  int jobs{0};
  long limit{-1};
  bool no_timing{false}, resume{false}, no_optimum{false};
  std::string shard;
  std::vector<std::string> pictures;  ///< --pictures failed|all DIR
  std::vector<std::string> mcap;      ///< --mcap failed|all DIR
};

void add_batch_options(CLI::App* cmd, BatchRequest& rq) {
  cmd->add_option("--jobs,-j", rq.jobs, "worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--out", rq.out, "output folder");
  cmd->add_option("--set", rq.sets, "override a key in every scenario")->take_all();
  cmd->add_option("--limit", rq.limit, "run only the first N cases of the sweep")
      ->check(CLI::Range(0L, 1000000000L));
  cmd->add_flag("--no-timing", rq.no_timing,
                "write wall_time as 0 so that repeated runs give identical files");
  cmd->add_flag("--resume", rq.resume,
                "keep the cases already in results.jsonl (of this very sweep) and run the rest");
  cmd->add_flag("--no-optimum", rq.no_optimum,
                "skip the grid A* optimal path length (and path_efficiency) where no .scen "
                "file gives the optimum");
  cmd->add_option("--shard", rq.shard,
                  "K/N: run only shard K of N (every N-th case); join shards with merge");
  cmd->add_option("--pictures", rq.pictures,
                  "failed|all DIR: an SVG and an HTML replay of each failed (or every) case in DIR")
      ->expected(2);
  cmd->add_option("--mcap", rq.mcap,
                  "failed|all DIR: a ROS 2 bag (MCAP) of each failed (or every) case in DIR")
      ->expected(2);
}

int run_sweep(const CaseSource& source, SweepHasher& hash, const BatchRequest& rq) {
  std::size_t count = source.count;
  if (rq.limit >= 0) count = std::min(count, static_cast<std::size_t>(rq.limit));
  const auto [k, n] = rq.shard.empty() ? std::pair{1, 1} : parse_shard(rq.shard);
  // (Not --limit: a sweep cut short by --limit is the same sweep; sweep.json has the count.)
  hash.add("floornav_version", floornav_version());
  hash.add("timing", rq.no_timing ? "off" : "on");
  hash.add("optimum", rq.no_optimum ? "off" : "on");
  BatchOptions opt;
  opt.jobs = rq.jobs;
  opt.out_dir = rq.out;
  if (isatty(STDERR_FILENO)) opt.progress = app::draw_progress_bar;
  opt.timing = !rq.no_timing;
  opt.resume = rq.resume;
  opt.optimum = !rq.no_optimum;
  opt.stop = &g_stop;
  opt.overrides = rq.sets;
  opt.sweep = {hash.id(), k, n, count};
  if (!rq.pictures.empty()) {
    opt.pictures = parse_which_cases("--pictures", rq.pictures[0]);
    opt.pictures_dir = rq.pictures[1];
  }
  if (!rq.mcap.empty()) {
    opt.mcap = parse_which_cases("--mcap", rq.mcap[0]);
    opt.mcap_dir = rq.mcap[1];
  }
  CaseList list{shard_ids(count, k, n), source.make};
  // Every case that will run is checked before any runs (one at a time, none kept: a bad value
  // is an error before the output folder exists). A source that made every case has checked.
  if (!source.checked)
    for (const std::size_t id : list.ids) source.make(id);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  const BatchOutcome o = run_batch(list, opt);
  const auto& a = o.aggregate;
  const auto rate = [&](const char* key) { return 100.0 * a[key].get<double>(); };
  fmt::print(
      "{} of {} cases{}{}: success {:.1f}%, collision {:.1f}%, timeout {:.1f}%, stuck {:.1f}% -> "
      "{}\n",
      o.completed, o.total,
      n > 1 ? fmt::format(" (shard {}/{} of sweep {})", k, n, opt.sweep.id) : std::string(),
      o.interrupted ? " (interrupted; --resume completes it)"
      : o.resumed   ? fmt::format(" ({} kept from before, {} run now)", o.resumed, o.ran)
                    : std::string(),
      rate("success_rate"), rate("collision_rate"), rate("timeout_rate"), rate("stuck_rate"),
      rq.out);
  return o.interrupted ? 130 : 0;
}

/// Refuses a command-line argument that is not UTF-8 (a path, a --set, a --grid value): every one
/// of them can reach a JSON output, which holds UTF-8 only.
void check_arguments_are_utf8(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    // Named by its option where it has one ("--set name=..."), else by its place.
    const std::string_view option = i > 1 ? std::string_view(argv[i - 1]) : std::string_view();
    const bool after_option = option.size() > 2 && option.substr(0, 2) == "--" &&
                              option.find('=') == std::string_view::npos;
    if (const auto at = first_non_utf8(arg))
      throw InputError(
          "",
          after_option ? fmt::format("{} {}", option, arg)
                       : fmt::format("argument {} '{}'", i, arg),
          fmt::format("{} (position {}): {}", describe_non_utf8(arg, *at), *at + 1, kWhyUtf8));
  }
}

/// The name of the subcommand a parse error is about, for the hint.
std::string subcommand_of(const CLI::App& app) {
  for (const CLI::App* s : app.get_subcommands()) return " " + s->get_name();
  return "";
}

/// Standard output is an output too (`floornav bench --json > FILE`, `floornav presets > FILE`):
/// one that could not be written (a full disk) is exit status 1 with the system's reason, never
/// status 0 over a cut-off file. `status` is the command's own.
int check_standard_output(int status) {
  errno = 0;
  if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return status;
  const int error = errno;
  fmt::print(stderr, "floornav: error: standard output: cannot write: {}\n",
             error != 0 ? std::strerror(error) : "a write failed");
  return status == 0 ? 1 : status;
}

/// `floornav run`'s arguments.
struct RunArgs {
  CLI::App* command{nullptr};
  RunRequest rq;
  std::string file;
  bool no_optimum{false};
  bool no_html{false};
};

void add_run_command(CLI::App& app, RunArgs& a) {
  auto* run = app.add_subcommand("run",
                                 "Simulate one scenario; writes summary.json, trajectory.csv, "
                                 "transitions.csv, trajectory.svg and trajectory.html");
  a.command = run;
  run->add_option("scenario", a.file, "scenario YAML file")->required();
  run->add_option("--out", a.rq.out, "output folder (default: out/<scenario name>)");
  run->add_option("--set", a.rq.sets, "override a scenario key: --set controller.kind=blended")
      ->take_all();
  run->add_flag("-q,--quiet", a.rq.quiet, "print nothing on success");
  run->add_flag("--no-html", a.no_html, "do not write trajectory.html (the replay)");
  run->add_flag("--mcap", a.rq.mcap,
                "also write run.mcap: the run as a ROS 2 bag (Foxglove, ros2 bag play)");
  run->add_option("--threads", a.rq.threads,
                  "threads stepping a fleet's robots (default: all cores; same result for any)")
      ->check(CLI::Range(1, 1024));
  run->add_option("--config-out", a.rq.config_out,
                  "also write the resolved scenario (presets and --set applied) as YAML to FILE");
  run->add_option("--record", a.rq.record,
                  "extra trajectory.csv columns: command, heading, clearance, goal, ranges or all "
                  "(comma-separated)");
  run->add_flag("--no-optimum", a.no_optimum,
                "skip the grid optimum (and so the warning when the goal cannot be reached)");
}

int run_scenario(RunArgs a) {
  a.rq.file = a.file;
  a.rq.optimum = !a.no_optimum;
  a.rq.html = !a.no_html;
  return run_one(load_scenario_file(a.file, a.rq.sets), a.rq);
}

/// `floornav batch`'s arguments: the scenarios, or a template and where its cases come from.
struct BatchArgs {
  CLI::App* command{nullptr};
  BatchRequest rq;
  std::vector<std::string> files;
  std::string scen, cell, worlds, barn_paths;
  int floors{0};
  int shared_floors{0};
  std::uint64_t floor_seed{1};
};

void add_batch_command(CLI::App& app, BatchArgs& a) {
  a.rq.out = "out/batch";
  auto* batch = app.add_subcommand("batch",
                                   "Run many scenarios in parallel; writes results.jsonl, "
                                   "aggregate.json and sweep.json");
  a.command = batch;
  batch->add_option("scenarios", a.files, "scenario YAML files (or one template with --scen)")
      ->required();
  add_batch_options(batch, a.rq);
  batch->add_option("--scen", a.scen, "MovingAI .scen file: one case per row, on its map");
  batch->add_option("--cell-size", a.cell, "metres per grid cell for --scen (default 1)");
  batch->add_option("--worlds", a.worlds,
                    "folder of Gazebo .world/.sdf files: one case per world, on the template");
  batch->add_option("--barn-paths", a.barn_paths,
                    "with --worlds: BARN path_N.npy folder, adds optimal_time and the BARN score");
  batch
      ->add_option("--floors", a.floors,
                   "one case per generated factory floor (20 x 20 m, 50 obstacles, a tour of 4 "
                   "goals): N floors, robot and controller from the template")
      ->check(CLI::Range(1, 100000));
  batch
      ->add_option("--shared-floors", a.shared_floors,
                   "one case per generated shared floor (a hall with pillars and boxes, 4 to 12 "
                   "robots with routes of 1 to 3 goals, people and a forklift on some): N floors, "
                   "every robot and controller the template's")
      ->check(CLI::Range(1, 100000));
  batch->add_option("--floor-seed", a.floor_seed,
                    "with --floors or --shared-floors: the first floor's seed (1)");
}

/// The options of `floornav batch` that exclude each other, checked before anything is read.
void check_batch_sources(const BatchArgs& a) {
  if (!a.scen.empty() && !a.worlds.empty())
    throw InputError("", "--scen", "give either --scen or --worlds, not both");
  if (!a.cell.empty() && a.scen.empty())
    throw InputError("", "--cell-size", "applies only with --scen (a MovingAI .scen file)");
  if (!a.barn_paths.empty() && a.worlds.empty())
    throw InputError("", "--barn-paths", "applies only with --worlds");
  if (a.floors > 0 && (!a.scen.empty() || !a.worlds.empty()))
    throw InputError("", "--floors", "give --floors alone, not with --scen or --worlds");
  if (a.shared_floors > 0 && (a.floors > 0 || !a.scen.empty() || !a.worlds.empty()))
    throw InputError("", "--shared-floors",
                     "give --shared-floors alone, not with --floors, --scen or --worlds");
}

/// The one template scenario that `option` (--floors, --worlds, ...) takes.
const std::string& one_template(const BatchArgs& a, const char* option) {
  if (a.files.size() != 1)
    throw InputError("", option, fmt::format("give exactly one template scenario with {}", option));
  return a.files[0];
}

/// Where `floornav batch`'s cases come from: generated floors, worlds, a .scen file's rows or the
/// scenario files themselves.
CaseSource batch_source(const BatchArgs& a, SweepHasher& hash) {
  check_batch_sources(a);
  if (a.shared_floors > 0)
    return make_shared_floor_cases(one_template(a, "--shared-floors"), a.shared_floors,
                                   a.floor_seed, a.rq.sets, hash);
  if (a.floors > 0)
    return make_floor_cases(one_template(a, "--floors"), a.floors, a.floor_seed, a.rq.sets, hash);
  if (!a.worlds.empty())
    return make_world_cases(one_template(a, "--worlds"), a.worlds, a.barn_paths, a.rq.sets, hash);
  if (!a.scen.empty()) {
    const std::string& file = one_template(a, "--scen");
    const double cell = a.cell.empty() ? 1.0 : parse_cell_size(a.cell);
    return make_scen_cases(file, a.scen, cell, a.rq.sets, hash);
  }
  return make_file_cases(a.files, a.rq.sets, hash);
}

/// `floornav sweep`'s arguments.
struct SweepArgs {
  CLI::App* command{nullptr};
  BatchRequest rq;
  std::string template_file;
  std::vector<std::string> grid;
};

void add_sweep_command(CLI::App& app, SweepArgs& a) {
  a.rq.out = "out/sweep";
  auto* sweep = app.add_subcommand(
      "sweep", "Run a template over a grid of parameter values (a batch whose lines carry them)");
  a.command = sweep;
  sweep->add_option("template", a.template_file, "scenario YAML file")->required();
  sweep
      ->add_option("--grid", a.grid,
                   "KEY=FROM:TO:COUNT or KEY=V1,V2,...; several --grid make a product")
      ->take_all()
      ->required();
  add_batch_options(sweep, a.rq);
}

/// `floornav merge`'s arguments.
struct MergeArgs {
  CLI::App* command{nullptr};
  std::vector<std::string> dirs;
  std::string out = "out/merged";
  bool partial{false};
};

void add_merge_command(CLI::App& app, MergeArgs& a) {
  auto* merge = app.add_subcommand("merge", "Join the shards of one sweep (checked)");
  a.command = merge;
  merge->add_option("dirs", a.dirs, "batch output folders, one per shard")->required();
  merge->add_option("--out", a.out, "output folder (default: out/merged)");
  merge->add_flag("--allow-partial", a.partial,
                  "merge even when shards or cases are missing (aggregate says complete: false)");
}

int run_merge(const MergeArgs& a) {
  std::vector<fs::path> dirs(a.dirs.begin(), a.dirs.end());
  const MergeOutcome o = merge_batches(dirs, a.out, a.partial);
  std::string partial;
  if (!o.complete) {
    partial = fmt::format(" (PARTIAL: {} of {} cases", o.merged, o.total);
    if (!o.missing_shards.empty())
      partial += fmt::format(", {} shard(s) missing", o.missing_shards.size());
    partial += "; aggregate.json says complete: false)";
  }
  fmt::print("{} cases merged{}: success {:.1f}% -> {}\n", o.merged, partial,
             100.0 * o.aggregate["success_rate"].get<double>(), a.out);
  return 0;
}

/// `floornav demo`'s arguments.
struct DemoArgs {
  CLI::App* command{nullptr};
  std::string out;
  bool no_html{false};
};

void add_demo_command(CLI::App& app, DemoArgs& a) {
  auto* demo = app.add_subcommand("demo", "Run the built-in factory floor demo (no files needed)");
  a.command = demo;
  demo->add_option("--out", a.out, "output folder (default: out/factory-delivery)");
  demo->add_flag("--no-html", a.no_html, "do not write trajectory.html (the replay)");
}

int run_demo(const DemoArgs& a) {
  RunRequest rq;
  rq.file = "factory-delivery.yaml";
  rq.out = a.out;
  rq.html = !a.no_html;
  return run_one(load_scenario_text(app::kDemoScenarioYaml, "factory-delivery.yaml"), rq);
}

/// `floornav bench`'s arguments.
struct BenchArgs {
  CLI::App* command{nullptr};
  BenchOptions options;
};

void add_bench_command(CLI::App& app, BenchArgs& a) {
  auto* bench = app.add_subcommand("bench", "Measure simulation speed on the standard cases");
  a.command = bench;
  bench->add_flag("--json", a.options.json, "one JSON object instead of the table");
  bench->add_option("--seconds", a.options.seconds_per_case, "timed seconds per case (default 1)")
      ->check(CLI::Range(1e-3, 3600.0));
  bench->add_option("--filter", a.options.filter, "only cases whose name contains this");
}

int print_presets() {
  for (auto name : robot_preset_names()) {
    const RobotPreset p = *find_robot_preset(name);
    fmt::print(
        "{:<18} R {:.4f} m, L {:.4f} m, body radius {:.3f} m, max {:.2f} m/s, {} "
        "range sensors {:.2f}-{:.2f} m\n",
        name, p.robot.drive.wheel_radius, p.robot.drive.track_width, p.robot.body_radius,
        max_forward_speed(p.robot.drive), p.robot.sensors.size(), p.robot.sensors.front().min_range,
        p.robot.sensors.front().max_range);
  }
  return 0;
}

/// Every subcommand's arguments, as the command line fills them in.
struct Commands {
  RunArgs run;
  BatchArgs batch;
  SweepArgs sweep;
  MergeArgs merge;
  DemoArgs demo;
  BenchArgs bench;
  CLI::App* presets{nullptr};
};

void add_commands(CLI::App& app, Commands& c) {
  add_run_command(app, c.run);
  add_batch_command(app, c.batch);
  add_sweep_command(app, c.sweep);
  add_merge_command(app, c.merge);
  add_demo_command(app, c.demo);
  add_bench_command(app, c.bench);
  c.presets = app.add_subcommand("presets", "List the robot presets");
}

/// Runs the subcommand the command line chose; its exit status.
int run_chosen(const Commands& c) {
  if (*c.run.command) return run_scenario(c.run);
  if (*c.demo.command) return run_demo(c.demo);
  if (*c.bench.command) return run_bench(c.bench.options);
  if (*c.presets) return print_presets();
  if (*c.batch.command) {
    SweepHasher hash;
    const CaseSource source = batch_source(c.batch, hash);
    return run_sweep(source, hash, c.batch.rq);
  }
  if (*c.sweep.command) {
    SweepHasher hash;
    const CaseSource source =
        make_grid_cases(c.sweep.template_file, c.sweep.grid, c.sweep.rq.sets, hash);
    return run_sweep(source, hash, c.sweep.rq);
  }
  if (*c.merge.command) return run_merge(c.merge);
  return 0;
}

int run_command(int argc, char** argv) {
  CLI::App app{"floornav: reactive navigation of wheeled mobile robots on factory floors"};
  app.set_version_flag("--version", "floornav " + floornav_version());
  app.require_subcommand(1);
  Commands commands;
  add_commands(app, commands);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    // Every error is one line (CLI11's own would add a second one).
    const InputError one_line("", "", e.what());
    fmt::print(stderr, "floornav: error: {} (see floornav{} --help)\n", one_line.what(),
               subcommand_of(app));
    return 2;
  }

  try {
    check_arguments_are_utf8(argc, argv);
    return run_chosen(commands);
  } catch (const OutputError& e) {  // an output that could not be written
    fmt::print(stderr, "floornav: error: {}\n", e.what());
    return 1;
  } catch (const InputError& e) {
    fmt::print(stderr, "floornav: error: {}\n", e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "floornav: error: out of memory\n");
    return 1;
  } catch (const std::exception& e) {
    if (std::ferror(stdout)) return 1;  // a print failed: check_standard_output says why
    fmt::print(stderr, "floornav: internal error: {}\n",
               InputError("", "", e.what()).what());  // one line, whatever it says
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  return check_standard_output(run_command(argc, argv));
}
