#include "batch_sources.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "bench_cases.hpp"
#include "floornav/core/input_error.hpp"
#include "floornav/io/barn.hpp"
#include "floornav/io/movingai_map.hpp"
#include "floornav/io/scenario_file.hpp"
#include "floornav/scenario/validate.hpp"

namespace floornav {

std::vector<BatchCase> make_scen_cases(const std::string& template_file,
                                       const std::string& scen_file, double cell_size,
                                       std::span<const std::string> overrides) {
  const std::vector<MovingAiCase> rows = load_movingai_scen(scen_file);
  if (rows.empty()) throw InputError(scen_file, "", "no cases in the .scen file");
  // The map: the path in the .scen relative to it, or a file of that name beside it.
  const std::filesystem::path scen_dir = std::filesystem::path(scen_file).parent_path();
  std::filesystem::path map = scen_dir / rows[0].map_file;
  if (!std::filesystem::exists(map))
    map = scen_dir / std::filesystem::path(rows[0].map_file).filename();
  if (!std::filesystem::exists(map))
    throw InputError(scen_file, "line 2",
                     fmt::format("map '{}' not found beside the .scen file", rows[0].map_file));
  // The template with the benchmark's map; start and goal are placeholders replaced per row.
  std::vector<std::string> sets(overrides.begin(), overrides.end());
  sets.push_back("world.map=" + std::filesystem::absolute(map).string());
  sets.push_back(fmt::format("world.cell_size={}", cell_size));
  const OccupancyGrid probe = load_movingai_map(map, cell_size);
  // Load the template once with the first row's start and goal; the world is then shared.
  const Vec2 s0 = movingai_cell_center(rows[0].start_x, rows[0].start_y, rows[0].height, cell_size);
  const Vec2 g0 = movingai_cell_center(rows[0].goal_x, rows[0].goal_y, rows[0].height, cell_size);
  auto with_pose = sets;
  with_pose.push_back(fmt::format("robot.start=[{},{},{}]", s0.x(), s0.y(),
                                  std::atan2(g0.y() - s0.y(), g0.x() - s0.x())));
  with_pose.push_back(fmt::format("goal=[{},{}]", g0.x(), g0.y()));
  const Scenario base = load_scenario_file(template_file, with_pose);

  std::vector<BatchCase> cases;
  cases.reserve(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const MovingAiCase& row = rows[i];
    if (row.width != probe.width() || row.height != probe.height())
      throw InputError(scen_file, fmt::format("line {}", i + 2),
                       "the row's map size differs from the map's");
    Scenario s = base;
    const Vec2 start = movingai_cell_center(row.start_x, row.start_y, row.height, cell_size);
    const Vec2 goal = movingai_cell_center(row.goal_x, row.goal_y, row.height, cell_size);
    s.robot().start = {start, std::atan2(goal.y() - start.y(), goal.x() - start.x())};
    s.robot().goals = {goal};
    s.name = fmt::format("{}-{}", base.name, i);
    validate_scenario(s, fmt::format("{} (row {})", scen_file, i + 2));
    BatchCase c{std::move(s), fmt::format("{}:{}", scen_file, i + 2), i, {}, {}};
    c.optimal_length = row.optimal_length * cell_size;  // the scen's octile optimum, in metres
    cases.push_back(std::move(c));
  }
  return cases;
}

namespace {
// The number in a file name ("world_17.world" -> 17), or -1.
long number_in(const std::string& name) {
  long value = -1;
  for (char c : name) {
    if (c >= '0' && c <= '9')
      value = (value < 0 ? 0 : value * 10) + (c - '0');
    else if (value >= 0)
      break;
  }
  return value;
}
}  // namespace

std::vector<BatchCase> make_world_cases(const std::string& template_file, const std::string& dir,
                                        const std::string& barn_paths,
                                        std::span<const std::string> overrides) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    throw InputError(dir, "", "--worlds needs a folder of .world/.sdf files");
  std::vector<std::filesystem::path> worlds;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".world" || e.path().extension() == ".sdf")
      worlds.push_back(e.path());
  if (worlds.empty()) throw InputError(dir, "", "no .world or .sdf files in the folder");
  std::sort(worlds.begin(), worlds.end(), [](const auto& a, const auto& b) {
    const long na = number_in(a.filename().string()), nb = number_in(b.filename().string());
    return na != nb ? na < nb : a < b;
  });
  std::vector<BatchCase> cases;
  for (std::size_t i = 0; i < worlds.size(); ++i) {
    std::vector<std::string> sets(overrides.begin(), overrides.end());
    sets.push_back("world.map=" + std::filesystem::absolute(worlds[i]).string());
    Scenario s = load_scenario_file(template_file, sets);
    s.name = fmt::format("{}-{}", s.name, worlds[i].stem().string());
    BatchCase c{std::move(s), worlds[i].string(), i, {}, {}};
    if (!barn_paths.empty()) {
      const long n = number_in(worlds[i].filename().string());
      const auto path = std::filesystem::path(barn_paths) / fmt::format("path_{}.npy", n);
      c.optimal_time =
          barn_optimal_time(load_npy_int_pairs(path), c.scenario.robot().start.position,
                            c.scenario.robot().goals.back());
    }
    cases.push_back(std::move(c));
  }
  return cases;
}

std::vector<BatchCase> make_floor_cases(const std::string& template_file, int count,
                                        std::uint64_t first_seed,
                                        std::span<const std::string> overrides) {
  if (count < 1 || count > 100000)
    throw InputError("", "--floors", fmt::format("must be in [1, 100000], got {}", count));
  const Scenario base = load_scenario_file(template_file, overrides);
  std::vector<BatchCase> cases;
  for (int i = 0; i < count; ++i) {
    const std::uint64_t seed = first_seed + static_cast<std::uint64_t>(i);
    BenchFloorParams p;
    p.seed = seed;
    auto world = std::make_shared<const World>(make_bench_floor(p));
    // The tour of make_floor_scenario (free start and four goals across the floor) for this seed.
    const Scenario tour = make_floor_scenario(world, 0, static_cast<int>(seed));
    Scenario s = base;
    s.world = world;
    for (RobotTask& t : s.robots) {
      t.start = tour.robot().start;
      t.goals = tour.robot().goals;
    }
    s.name = fmt::format("{}-floor{}", base.name, seed);
    validate_scenario(s, fmt::format("{} (floor {})", template_file, seed));
    cases.push_back(
        {std::move(s), fmt::format("floor:{}", seed), static_cast<std::size_t>(i), {}, {}});
  }
  return cases;
}

}  // namespace floornav
