// What pickle keeps of a RunResult: the result's data (a lone robot's run or a fleet's, the
// summary's context once computed) as CBOR bytes, which hold every double bit for bit (NaN and
// infinities included) and need no second simulation to load.

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "bindings.hpp"
#include "floornav/runner/scenario_optimum.hpp"

// std::optional as null or the value (nlohmann 3.11 has no serializer of its own for it).
namespace nlohmann {
template <class T>
struct adl_serializer<std::optional<T>> {
  static void to_json(json& j, const std::optional<T>& o) {
    if (o)
      j = *o;
    else
      j = nullptr;
  }
  static void from_json(const json& j, std::optional<T>& o) {
    if (j.is_null())
      o.reset();
    else
      o = j.get<T>();
  }
};
// Vec2 (an Eigen type: found by no lookup in floornav's namespace) as [x, y].
template <>
struct adl_serializer<floornav::Vec2> {
  static void to_json(json& j, const floornav::Vec2& v) { j = json::array({v.x(), v.y()}); }
  static void from_json(const json& j, floornav::Vec2& v) {
    v = floornav::Vec2(j.at(0).get<double>(), j.at(1).get<double>());
  }
};
}  // namespace nlohmann

namespace floornav {

// nlohmann's field lists: each field once, the same list for writing and reading (not in the core
// headers, which know no format).
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Transition, time, from, to, edge)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(TrajectorySample, t, x, y, theta, v, omega, w_left, w_right,
                                   mode)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(RunResult, scenario, status, reached_goal, collided,
                                   goals_reached, goal_count, sim_time, path_length, wait_time,
                                   path_irregularity, safety_time, safety_steps, stuck_cause,
                                   stuck_with, min_clearance, mode_switches, steps, wall_time,
                                   chatter_episodes, first_chatter_time, mode_names, guard_names,
                                   mode_time, transitions, transition_x, transition_y, trajectory,
                                   range_steps, ranges, extra_columns, extra, final_x, final_y,
                                   final_theta)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(FleetCollision, time, robot, other, kind)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(CrowdSample, t, x, y, theta)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(CrowdMetrics, person_contacts, forklift_contacts, intrusions,
                                   intrusion_time, min_person_gap, people_blocked_time,
                                   forklift_stopped_time)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(CrowdTrack, name, size, samples, path_length, still_time,
                                   waypoints_reached)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(CrowdResult, people, forklifts, metrics)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(FleetResult, scenario, status, robots, collisions, reached,
                                   collided, deliveries, delivery_count, sim_time, steps,
                                   robot_steps, min_clearance, wall_time, crowd)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Optimum, status, length, octile_length, cell_size, width, height,
                                   path)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(RunContext, overrides, optimum, optimal_length, optimal_time,
                                   swept)

}  // namespace floornav

namespace floornav::python {

namespace {
// Bumped when a field list above changes: an older pickle is refused by name, not misread.
constexpr int kStateVersion = 1;
}  // namespace

py::bytes run_result_data(const PyRunResult& r, bool with_context) {
  const nlohmann::json j = {{"version", kStateVersion},
                            {"run", r.run},
                            {"fleet", r.fleet},
                            {"context", with_context ? r.context : std::nullopt}};
  const std::vector<std::uint8_t> cbor = nlohmann::json::to_cbor(j);
  return py::bytes(reinterpret_cast<const char*>(cbor.data()), cbor.size());
}

void load_run_result_data(PyRunResult& r, const py::bytes& data) {
  const std::string_view bytes = data;
  try {
    const nlohmann::json j = nlohmann::json::from_cbor(bytes.begin(), bytes.end());
    if (j.at("version").get<int>() != kStateVersion)
      throw py::value_error(
          fmt::format("a pickled RunResult of version {} (this floornav reads {})",
                      j.at("version").dump(), kStateVersion));
    j.at("run").get_to(r.run);
    j.at("fleet").get_to(r.fleet);
    j.at("context").get_to(r.context);
  } catch (const nlohmann::json::exception& e) {
    throw py::value_error(fmt::format("a pickled RunResult that cannot be read: {}", e.what()));
  }
  if (r.run.has_value() == r.fleet.has_value())
    throw py::value_error("a pickled RunResult holds neither or both of a run and a fleet run");
}

}  // namespace floornav::python
