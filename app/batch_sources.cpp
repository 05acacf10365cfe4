#include "batch_sources.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>
#include <optional>
#include <utility>

#include "floornav/core/input_error.hpp"
#include "floornav/core/utf8.hpp"
#include "floornav/io/barn.hpp"
#include "floornav/io/movingai_map.hpp"
#include "floornav/io/scenario_file.hpp"
#include "floornav/scenario/factory_floor.hpp"
#include "floornav/scenario/shared_floor.hpp"
#include "floornav/scenario/validate.hpp"

namespace floornav {

namespace {

/// The most cases a --grid sweep may have (every one is a scenario loaded from the template).
constexpr std::size_t kMaxGridCases = 1000000;
constexpr std::size_t kMaxAxisValues = 100000;  ///< values of one --grid

void add_overrides(SweepHasher& hash, std::span<const std::string> overrides) {
  for (const std::string& o : overrides) hash.add("--set", o);
}

/// The content of every file `s` was made from (its scenario file, map, map image, people file).
void add_inputs(SweepHasher& hash, const Scenario& s) {
  for (const std::string& f : s.input_files) hash.add_content("reads", f);
}

/// A path named in an output must be UTF-8 (outputs are JSON): a file found in a folder is
/// checked as command-line arguments are.
void check_utf8_name(const std::filesystem::path& p, const std::string& where) {
  const std::string& text = p.native();
  if (const auto at = first_non_utf8(text))
    throw InputError(text, where,
                     fmt::format("the name holds byte 0x{:02x} at position {}, which is not "
                                 "UTF-8 (names and paths are written to JSON, which holds "
                                 "nothing else): rename the file",
                                 static_cast<unsigned char>(text[*at]), *at + 1));
}

/// The digits in a file name ("world_17.world" -> "17"), or "" (kept as text: a 23-digit number
/// would overflow any integer).
std::string digits_in(const std::string& name) {
  std::string out;
  for (char c : name) {
    if (c >= '0' && c <= '9')
      out += c;
    else if (!out.empty())
      break;
  }
  const auto first = out.find_first_not_of('0');
  return first == std::string::npos ? (out.empty() ? "" : "0") : out.substr(first);
}

/// Natural order of numbers written as digits: shorter is smaller, then by digits.
bool number_less(const std::string& a, const std::string& b) {
  return a.size() != b.size() ? a.size() < b.size() : a < b;
}

/// path_N.npy in `barn_paths` for world_N.world.
std::filesystem::path barn_path_of(const std::filesystem::path& world,
                                   const std::string& barn_paths) {
  const std::string n = digits_in(world.filename().string());
  if (n.empty())
    throw InputError(world.string(), "",
                     "--barn-paths: the file name has no number N to find path_N.npy by");
  return std::filesystem::path(barn_paths) / fmt::format("path_{}.npy", n);
}

}  // namespace

CaseSource make_file_cases(std::span<const std::string> files,
                           std::span<const std::string> overrides, SweepHasher& hash) {
  hash.add("mode", "files");
  add_overrides(hash, overrides);
  auto list = std::make_shared<const std::vector<std::string>>(files.begin(), files.end());
  auto sets = std::make_shared<const std::vector<std::string>>(overrides.begin(), overrides.end());
  auto make = [list, sets](std::size_t id) {
    BatchCase c;
    c.scenario = load_scenario_file(list->at(id), *sets);
    c.source = list->at(id);
    c.id = id;
    return c;
  };
  // Every file is loaded (and so checked) now, one at a time, for what it reads; none is kept.
  for (std::size_t i = 0; i < list->size(); ++i) {
    const BatchCase c = make(i);
    hash.add_file("scenario", (*list)[i]);
    add_inputs(hash, c.scenario);
  }
  return {list->size(), make, true};
}

namespace {

/// The rows of a .scen file: at least one, all on one map (a row naming another would otherwise
/// run on the first row's map).
std::shared_ptr<const std::vector<MovingAiCase>> load_scen_rows(const std::string& scen_file) {
  auto rows = std::make_shared<const std::vector<MovingAiCase>>(load_movingai_scen(scen_file));
  if (rows->empty()) throw InputError(scen_file, "", "no cases in the .scen file (only a header)");
  const MovingAiCase& first = rows->front();
  for (const MovingAiCase& row : *rows)
    if (row.map_file != first.map_file)
      throw InputError(scen_file, fmt::format("line {}", row.line),
                       fmt::format("names map '{}', but line {} names '{}': the rows of one .scen "
                                   "file are on one map",
                                   row.map_file, first.line, first.map_file));
  return rows;
}

/// The map of a .scen's rows: the path in the .scen relative to it, or a file of that name beside
/// it; a grid the rows can index.
std::filesystem::path find_scen_map(const std::string& scen_file, const MovingAiCase& first) {
  const std::filesystem::path scen_dir = std::filesystem::path(scen_file).parent_path();
  const std::filesystem::path named = scen_dir / first.map_file;
  const std::filesystem::path beside = scen_dir / std::filesystem::path(first.map_file).filename();
  std::error_code ec;
  const std::filesystem::path map = std::filesystem::exists(named, ec) ? named : beside;
  if (!std::filesystem::exists(map, ec))
    throw InputError(scen_file, fmt::format("line {}", first.line),
                     fmt::format("its map '{}' does not exist (looked for {} and {})",
                                 first.map_file, named.string(), beside.string()));
  // A .scen's rows are cells counted from the top-left corner of a grid without an origin: a
  // MovingAI .map, or a bare image with --cell-size. A ROS map yaml brings its own resolution and
  // origin, which the rows know nothing of: the map is at fault, not the cell size.
  std::string ext = map.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext != ".map" && ext != ".pgm" && ext != ".png")
    throw InputError(
        scen_file, fmt::format("line {} (its map)", first.line),
        fmt::format("'{}' is not a grid a .scen can index: its rows are cells of a MovingAI .map "
                    "(or of a bare .pgm/.png image, with --cell-size){}",
                    first.map_file,
                    ext == ".yaml" || ext == ".yml"
                        ? "; a ROS map yaml has its own resolution and origin: run it with "
                          "floornav run or --grid instead"
                        : ""));
  return map;
}

/// A row's start pose (facing its goal) and goal, in metres.
std::pair<Pose2, Vec2> scen_start_and_goal(const MovingAiCase& row, double cell_size) {
  const Vec2 s = movingai_cell_center(row.start_x, row.start_y, row.height, cell_size);
  const Vec2 g = movingai_cell_center(row.goal_x, row.goal_y, row.height, cell_size);
  return {Pose2{s, std::atan2(g.y() - s.y(), g.x() - s.x())}, g};
}

/// The template with the benchmark's map, and the first row's start and goal in place of the
/// template's: each of these values is blamed on where it came from, never on a --set.
Scenario load_scen_template(const std::string& template_file, const std::string& scen_file,
                            const MovingAiCase& first, const std::string& map_path,
                            double cell_size, std::span<const std::string> overrides) {
  const std::string first_line = fmt::format("line {}", first.line);
  const auto [s0, g0] = scen_start_and_goal(first, cell_size);
  std::vector<ScenarioOverride> sets = user_overrides(overrides);
  sets.push_back({"world.map=" + map_path, scen_file, first_line + " (its map)", true});
  sets.push_back(
      {fmt::format("world.cell_size={}", cell_size), "", fmt::format("--cell-size {}", cell_size)});
  sets.push_back({fmt::format("robot.start=[{},{},{}]", s0.position.x(), s0.position.y(), s0.theta),
                  scen_file, first_line + " (its start)"});
  sets.push_back(
      {fmt::format("goal=[{},{}]", g0.x(), g0.y()), scen_file, first_line + " (its goal)"});
  return load_scenario_with_overrides(template_file, sets);
}

/// Checks every row now (start and goal on free floor, the map's size): a bad row is an error
/// before anything runs. One scenario is reused for the checks.
void check_scen_rows(const Scenario& base, const std::vector<MovingAiCase>& rows,
                     const std::string& scen_file, double cell_size) {
  const OccupancyGrid* grid = base.world->grid();
  Scenario probe = base;
  for (const MovingAiCase& row : rows) {
    const std::string where = fmt::format("line {}", row.line);
    if (grid && (row.width != grid->width() || row.height != grid->height()))
      throw InputError(scen_file, where,
                       fmt::format("the row's map size {} x {} differs from the map's {} x {}",
                                   row.width, row.height, grid->width(), grid->height()));
    const auto [start, goal] = scen_start_and_goal(row, cell_size);
    probe.robot().start = start;
    probe.robot().goals = {goal};
    try {
      validate_scenario(probe, scen_file);
    } catch (const InputError& e) {
      throw InputError(
          scen_file, where,
          fmt::format("{}: {}", e.where == "goal" ? "its goal" : "its start", e.detail));
    }
  }
}

/// Case `id` of a .scen batch: the template on row `row`.
BatchCase scen_case(const Scenario& base, const MovingAiCase& row, std::size_t id,
                    const std::string& scen_file, double cell_size) {
  BatchCase c;
  c.scenario = base;
  const auto [start, goal] = scen_start_and_goal(row, cell_size);
  c.scenario.robot().start = start;
  c.scenario.robot().goals = {goal};
  c.scenario.name = fmt::format("{}-{}", base.name, id);
  c.source = fmt::format("{}:{}", scen_file, row.line);
  c.id = id;
  c.optimal_length = row.optimal_length * cell_size;  // the scen's octile optimum, in m
  return c;
}

}  // namespace

CaseSource make_scen_cases(const std::string& template_file, const std::string& scen_file,
                           double cell_size, std::span<const std::string> overrides,
                           SweepHasher& hash) {
  const auto rows = load_scen_rows(scen_file);
  const MovingAiCase& first = rows->front();
  const std::filesystem::path map = find_scen_map(scen_file, first);
  const std::string map_path = std::filesystem::absolute(map).lexically_normal().string();
  hash.add("mode", "scen");
  add_overrides(hash, overrides);
  hash.add("cell_size", fmt::format("{}", cell_size));
  hash.add_file("template", template_file);
  hash.add_file("scen", scen_file);
  hash.add_file("map", map);
  auto base = std::make_shared<const Scenario>(
      load_scen_template(template_file, scen_file, first, map_path, cell_size, overrides));
  add_inputs(hash, *base);
  if (base->is_fleet())
    throw InputError(template_file, "robots", "a .scen template has one robot, not a robots list");
  check_scen_rows(*base, *rows, scen_file, cell_size);
  return {rows->size(),
          [base, rows, cell_size, scen_file](std::size_t id) {
            return scen_case(*base, rows->at(id), id, scen_file, cell_size);
          },
          true};
}

CaseSource make_world_cases(const std::string& template_file, const std::string& dir,
                            const std::string& barn_paths, std::span<const std::string> overrides,
                            SweepHasher& hash) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    throw InputError(dir, "",
                     std::filesystem::exists(dir, ec)
                         ? "is not a directory (--worlds needs a folder of .world/.sdf files)"
                         : "does not exist (--worlds needs a folder of .world/.sdf files)");
  std::vector<std::filesystem::path> worlds;
  // Every step of the listing is checked: an unreadable folder is the input's fault, said so.
  std::filesystem::directory_iterator it(dir, ec), end;
  for (; !ec && it != end; it.increment(ec)) {
    const std::filesystem::path& p = it->path();
    if (p.extension() != ".world" && p.extension() != ".sdf") continue;
    check_utf8_name(p, "--worlds");
    worlds.push_back(p);
  }
  if (ec) throw InputError(dir, "", "cannot be read (--worlds): " + ec.message());
  if (worlds.empty()) throw InputError(dir, "", "no .world or .sdf files in the folder");
  std::sort(worlds.begin(), worlds.end(), [](const auto& a, const auto& b) {
    const std::string na = digits_in(a.filename().string()), nb = digits_in(b.filename().string());
    return na != nb ? number_less(na, nb) : a < b;
  });
  hash.add("mode", "worlds");
  add_overrides(hash, overrides);
  hash.add_file("template", template_file);
  auto list = std::make_shared<const std::vector<std::filesystem::path>>(std::move(worlds));
  auto sets = std::make_shared<const std::vector<std::string>>(overrides.begin(), overrides.end());
  auto make = [template_file, barn_paths, list, sets](std::size_t id) {
    const std::filesystem::path& world = list->at(id);
    std::vector<ScenarioOverride> o = user_overrides(*sets);
    o.push_back({"world.map=" + std::filesystem::absolute(world).string(), world.string(),
                 "--worlds", true});
    BatchCase c;
    c.scenario = load_scenario_with_overrides(template_file, o);
    c.scenario.name = fmt::format("{}-{}", c.scenario.name, world.stem().string());
    c.source = world.string();
    c.id = id;
    if (!barn_paths.empty()) {
      c.optimal_time =
          barn_optimal_time(load_barn_path(barn_path_of(world, barn_paths)),
                            c.scenario.robot().start.position, c.scenario.robot().goals.back());
    }
    return c;
  };
  for (std::size_t i = 0; i < list->size(); ++i) {
    hash.add_file("world", (*list)[i]);
    if (!barn_paths.empty()) hash.add_file("barn_path", barn_path_of((*list)[i], barn_paths));
  }
  // What the template reads besides the world (a people_file): the first case's inputs.
  add_inputs(hash, make(0).scenario);
  return {list->size(), make, false};
}

namespace {

/// The values of one --grid: "key=FROM:TO:COUNT" or "key=V1,V2,...".
struct GridAxis {
  std::string key;
  std::vector<std::string> values;
};

/// Why two --grid keys cannot both be swept (the same key, one inside the other, or goal and
/// goals), or nullopt.
std::optional<std::string> axes_overlap(const std::string& a, const std::string& b) {
  if (a == b) return fmt::format("--grid sets '{}'", b);
  const auto under = [](const std::string& x, const std::string& y) {  // x is inside y
    return x.size() > y.size() && x.compare(0, y.size(), y) == 0 &&
           (x[y.size()] == '.' || x[y.size()] == '[');
  };
  if (under(a, b) || under(b, a)) return fmt::format("--grid sets '{}', which overlaps '{}'", b, a);
  const auto last = [](const std::string& k) { return k.substr(k.rfind('.') + 1); };
  const auto parent = [](const std::string& k) {
    const auto dot = k.rfind('.');
    return dot == std::string::npos ? std::string() : k.substr(0, dot);
  };
  const std::string la = last(a), lb = last(b);
  if (parent(a) == parent(b) &&
      ((la == "goal" && lb == "goals") || (la == "goals" && lb == "goal")))
    return fmt::format("--grid sets '{}', which replaces '{}'", b, a);
  return std::nullopt;
}

/// Whether a --grid on `key` can change which files a case reads (a map, a people file).
bool names_files(const std::string& key) {
  for (const char* k : {"world.map", "people_file"}) {
    const std::string file_key = k;
    if (key == file_key ||
        (file_key.size() > key.size() && file_key.compare(0, key.size(), key) == 0 &&
         file_key[key.size()] == '.'))
      return true;
  }
  return false;
}

GridAxis parse_grid(const std::string& spec) {
  const std::string where = "--grid " + spec;
  auto bad = [&](const std::string& what) { throw InputError("", where, what); };
  const auto eq = spec.find('=');
  if (eq == std::string::npos || eq == 0)
    bad("expected KEY=FROM:TO:COUNT or KEY=V1,V2,... (e.g. controller.d_o=0.1:0.5:5)");
  GridAxis axis{spec.substr(0, eq), {}};
  const std::string rhs = spec.substr(eq + 1);
  if (rhs.empty()) bad("no values after '='");
  if (rhs.find(':') != std::string::npos) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    for (std::size_t p; (p = rhs.find(':', start)) != std::string::npos; start = p + 1)
      parts.push_back(rhs.substr(start, p - start));
    parts.push_back(rhs.substr(start));
    if (parts.size() != 3) bad("a range is FROM:TO:COUNT, e.g. 0.1:0.5:5");
    double from = 0, to = 0;
    long count = 0;
    std::size_t used = 0;
    try {
      from = std::stod(parts[0], &used);
      if (used != parts[0].size()) throw std::invalid_argument("");
      to = std::stod(parts[1], &used);
      if (used != parts[1].size()) throw std::invalid_argument("");
      count = std::stol(parts[2], &used);
      if (used != parts[2].size()) throw std::invalid_argument("");
    } catch (const std::exception&) {
      bad("FROM and TO are numbers and COUNT a whole number, e.g. 0.1:0.5:5");
    }
    if (!std::isfinite(from) || !std::isfinite(to)) bad("FROM and TO must be finite");
    if (count < 1 || count > static_cast<long>(kMaxAxisValues))
      bad(fmt::format("COUNT must be between 1 and {}", kMaxAxisValues));
    for (long i = 0; i < count; ++i) {
      // Evenly spaced, both ends exact.
      const double v = count == 1       ? from
                       : i == count - 1 ? to
                                        : from + (to - from) * static_cast<double>(i) /
                                                     static_cast<double>(count - 1);
      axis.values.push_back(fmt::format("{}", v));
    }
  } else {
    std::size_t start = 0;
    for (std::size_t p;; start = p + 1) {
      p = rhs.find(',', start);
      const std::string v = rhs.substr(start, p == std::string::npos ? p : p - start);
      if (v.empty()) bad("an empty value in the list");
      if (axis.values.size() >= kMaxAxisValues)
        bad(fmt::format("more than {} values", kMaxAxisValues));
      axis.values.push_back(v);
      if (p == std::string::npos) break;
    }
  }
  return axis;
}

}  // namespace

CaseSource make_grid_cases(const std::string& template_file, std::span<const std::string> grid,
                           std::span<const std::string> overrides, SweepHasher& hash) {
  if (grid.empty()) throw InputError("", "--grid", "give at least one --grid KEY=VALUES");
  auto axes = std::make_shared<std::vector<GridAxis>>();
  std::size_t count = 1;
  for (const std::string& spec : grid) {
    GridAxis axis = parse_grid(spec);
    // Two axes on one key (or on a key and a part of it, or on goal and goals, which replace
    // each other) would have the later silently undo the earlier: refused.
    for (std::size_t a = 0; a < axes->size(); ++a)
      if (const auto why = axes_overlap((*axes)[a].key, axis.key))
        throw InputError("", "--grid " + spec,
                         fmt::format("{} as --grid {} does, so one would undo the other: give "
                                     "each key one --grid (with all its values)",
                                     *why, grid[a]));
    axes->push_back(std::move(axis));
    count *= axes->back().values.size();
    if (count > kMaxGridCases)
      throw InputError("", "--grid " + spec,
                       fmt::format("the grid has more than {} cases", kMaxGridCases));
  }
  hash.add("mode", "grid");
  add_overrides(hash, overrides);
  for (const std::string& spec : grid) hash.add("--grid", spec);
  hash.add_file("template", template_file);
  auto specs = std::make_shared<const std::vector<std::string>>(grid.begin(), grid.end());
  auto sets = std::make_shared<const std::vector<std::string>>(overrides.begin(), overrides.end());
  // Case `id`'s value index on every axis: the last axis varies fastest.
  auto indices = [axes](std::size_t id) {
    std::vector<std::size_t> at(axes->size(), 0);
    for (std::size_t a = axes->size(); a-- > 0;) {
      at[a] = id % (*axes)[a].values.size();
      id /= (*axes)[a].values.size();
    }
    return at;
  };
  auto id_of = [axes](const std::vector<std::size_t>& at) {
    std::size_t id = 0;
    for (std::size_t a = 0; a < axes->size(); ++a) id = id * (*axes)[a].values.size() + at[a];
    return id;
  };
  auto make = [template_file, axes, specs, sets, indices](std::size_t id) {
    const std::vector<std::size_t> at = indices(id);
    std::vector<ScenarioOverride> o = user_overrides(*sets);
    BatchCase c;
    std::string label;
    for (std::size_t a = 0; a < axes->size(); ++a) {
      const std::string assignment = (*axes)[a].key + "=" + (*axes)[a].values[at[a]];
      o.push_back({assignment, "", "--grid " + (*specs)[a] + " (" + assignment + ")"});
      c.swept.push_back(assignment);
      label += (a ? " " : "") + assignment;
    }
    c.scenario = load_scenario_with_overrides(template_file, o);
    c.source = template_file + " [" + label + "]";
    c.id = id;
    return c;
  };
  // The files the cases read: those of the first case, and, for an axis that names files (a
  // world.map, a people_file), those of each of its values. Other axes change no file read.
  add_inputs(hash, make(0).scenario);
  for (std::size_t a = 0; a < axes->size(); ++a) {
    if (!names_files((*axes)[a].key)) continue;
    for (std::size_t v = 1; v < (*axes)[a].values.size(); ++v) {
      std::vector<std::size_t> at(axes->size(), 0);
      at[a] = v;
      add_inputs(hash, make(id_of(at)).scenario);
    }
  }
  return {count, make, false};
}

CaseSource make_floor_cases(const std::string& template_file, int count, std::uint64_t first_seed,
                            std::span<const std::string> overrides, SweepHasher& hash) {
  if (count < 1 || count > 100000)
    throw InputError("", "--floors", fmt::format("must be in [1, 100000], got {}", count));
  hash.add("mode", "floors");
  add_overrides(hash, overrides);
  hash.add("floors", fmt::format("{}", count));
  hash.add("floor_seed", fmt::format("{}", first_seed));
  hash.add_file("template", template_file);
  auto base = std::make_shared<const Scenario>(load_scenario_file(template_file, overrides));
  add_inputs(hash, *base);
  auto make = [base, first_seed, template_file](std::size_t i) {
    const std::uint64_t seed = first_seed + static_cast<std::uint64_t>(i);
    return BatchCase{make_generated_floor(*base, seed, template_file),
                     fmt::format("floor:{}", seed),
                     i,
                     {},
                     {},
                     {}};
  };
  return {static_cast<std::size_t>(count), make, false};
}

CaseSource make_shared_floor_cases(const std::string& template_file, int count,
                                   std::uint64_t first_seed, std::span<const std::string> overrides,
                                   SweepHasher& hash) {
  if (count < 1 || count > 100000)
    throw InputError("", "--shared-floors", fmt::format("must be in [1, 100000], got {}", count));
  hash.add("mode", "shared_floors");
  add_overrides(hash, overrides);
  hash.add("shared_floors", fmt::format("{}", count));
  hash.add("floor_seed", fmt::format("{}", first_seed));
  hash.add_file("template", template_file);
  auto base = std::make_shared<const Scenario>(load_scenario_file(template_file, overrides));
  add_inputs(hash, *base);
  auto make = [base, first_seed, template_file](std::size_t i) {
    const std::uint64_t seed = first_seed + static_cast<std::uint64_t>(i);
    return BatchCase{make_shared_floor_case(*base, seed, template_file),
                     fmt::format("shared_floor:{}", seed),
                     i,
                     {},
                     {},
                     {}};
  };
  return {static_cast<std::size_t>(count), make, false};
}

}  // namespace floornav
