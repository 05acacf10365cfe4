#include "floornav/runner/run_summary.hpp"

#include <fmt/format.h>

#include "floornav/io/provenance.hpp"
#include "floornav/io/summary_json.hpp"
#include "floornav/runner/batch.hpp"

namespace floornav {

namespace {

using Json = nlohmann::ordered_json;

void put_tail(Json& j, const Scenario& s, const RunContext& c,
              const std::vector<std::string>& warnings) {
  if (!c.swept.empty()) {
    Json swept = Json::object();
    for (const std::string& kv : c.swept) {
      const auto eq = kv.find('=');
      const std::string key = kv.substr(0, eq);
      const std::string value = eq == std::string::npos ? std::string() : kv.substr(eq + 1);
      // A swept number is written as a number, anything else as its text.
      const Json parsed = Json::parse(value, nullptr, false);
      swept[key] = parsed.is_discarded() || parsed.is_object() ? Json(value) : parsed;
    }
    j["swept"] = std::move(swept);
  }
  if (!warnings.empty()) j["warnings"] = warnings;
  const Json p = provenance_json(s, c.overrides);
  for (const auto& [k, v] : p.items()) j[k] = v;
}

}  // namespace

const RobotTask* optimum_task(const Scenario& s) {
  if (!s.world || s.is_fleet() || s.robots.empty()) return nullptr;
  return &s.robot();
}

std::optional<Optimum> compute_optimum(const Scenario& s) {
  const RobotTask* t = optimum_task(s);
  if (!t) return std::nullopt;
  return scenario_optimum(*s.world, t->robot.body_radius, t->start.position, t->goals);
}

std::optional<std::string> reachability_warning(const Scenario& s, const Optimum& o) {
  if (s.robots.empty()) return std::nullopt;
  const RobotTask& t = s.robot();
  if (o.status == OptimumStatus::Unreachable)
    return fmt::format(
        "no path from the start ({:.6g}, {:.6g}) through the goal{} on the known map for a body "
        "of radius {:.6g} m (a {:.6g} m raster): the run will not reach it",
        t.start.position.x(), t.start.position.y(), t.goals.size() == 1 ? "" : "s",
        t.robot.body_radius, o.cell_size);
  if (o.status == OptimumStatus::NoFreeCell)
    return fmt::format(
        "the start or a goal has no free cell within reach on the known map for a body of "
        "radius {:.6g} m (a {:.6g} m raster): the run will not reach the goal",
        t.robot.body_radius, o.cell_size);
  return std::nullopt;
}

nlohmann::ordered_json run_summary(const Scenario& s, const RunResult& r, const RunContext& c) {
  Json j = summary_to_json(r);
  const RobotTask& t = s.robot();
  j["controller"] = t.controller.kind;
  j["robot"] = t.robot.preset;
  j["start"] = Json::array({t.start.position.x(), t.start.position.y(), t.start.theta});
  Json goals = Json::array();
  for (const Vec2& g : t.goals) goals.push_back(Json::array({g.x(), g.y()}));
  j["goals"] = std::move(goals);
  std::optional<double> optimal = c.optimal_length;
  if (c.optimum && c.optimum->status == OptimumStatus::Found) optimal = c.optimum->length;
  if (c.optimal_length || c.optimum) {
    j["optimal_length"] = optimal ? Json(*optimal) : Json(nullptr);
    j["path_efficiency"] = optimal && r.reached_goal && r.path_length > 0
                               ? Json(*optimal / r.path_length)
                               : Json(nullptr);
    j["optimal_source"] = c.optimal_length ? "scen" : "grid_astar";
  }
  if (c.optimum) {
    if (c.optimum->status == OptimumStatus::Found)
      j["optimal_octile_length"] = c.optimum->octile_length;
    else
      j["optimal_status"] = std::string(to_string(c.optimum->status));
    j["optimal_cell_size"] = c.optimum->cell_size;
  }
  if (c.optimal_time) {
    j["optimal_time"] = *c.optimal_time;
    j["score"] = barn_score(r.reached_goal && !r.collided, r.sim_time, *c.optimal_time);
  }
  std::vector<std::string> warnings;
  if (c.optimum)
    if (auto w = reachability_warning(s, *c.optimum)) warnings.push_back(*w);
  put_tail(j, s, c, warnings);
  return j;
}

nlohmann::ordered_json fleet_run_summary(const Scenario& s, const FleetResult& f,
                                         const RunContext& c) {
  Json j = fleet_summary_to_json(f);
  j["controller"] = s.robot().controller.kind;
  j["robot"] = s.robot().robot.preset;
  put_tail(j, s, c, {});
  return j;
}

}  // namespace floornav
