#include "scen_cases.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>

#include "floornav/io/input_error.hpp"
#include "floornav/io/movingai_map.hpp"
#include "floornav/io/scenario_file.hpp"

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
    s.start = {start, std::atan2(goal.y() - start.y(), goal.x() - start.x())};
    s.goals = {goal};
    s.name = fmt::format("{}-{}", base.name, i);
    validate_scenario(s, fmt::format("{} (row {})", scen_file, i + 2));
    cases.push_back({std::move(s), fmt::format("{}:{}", scen_file, i + 2)});
  }
  return cases;
}

}  // namespace floornav
