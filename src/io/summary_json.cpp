#include "floornav/io/summary_json.hpp"

#include <cmath>
#include <string>

namespace floornav {

namespace {

using Json = nlohmann::ordered_json;

/// JSON has no NaN or infinity: such a value is written as null.
Json number(double value) {
  return std::isfinite(value) ? Json(value) : Json(nullptr);
}

std::string name_of(const std::vector<std::string>& names, int index, const char* fallback) {
  if (index >= 0 && static_cast<std::size_t>(index) < names.size())
    return names[static_cast<std::size_t>(index)];
  return std::string(fallback) + std::to_string(index);
}

std::string mode_name(const RunResult& r, int mode) {
  return name_of(r.mode_names, mode, "mode_");
}

double at_or_nan(const std::vector<double>& v, std::size_t i) {
  return i < v.size() ? v[i] : std::nan("");
}

}  // namespace

nlohmann::ordered_json summary_to_json(const RunResult& r) {
  Json j = Json::object();
  j["scenario"] = r.scenario;
  j["status"] = std::string(to_string(r.status));
  j["reached_goal"] = r.reached_goal;
  j["collided"] = r.collided;
  j["sim_time"] = number(r.sim_time);
  j["path_length"] = number(r.path_length);
  j["min_clearance"] = number(r.min_clearance);
  j["mode_switches"] = r.mode_switches;

  Json mode_time = Json::object();
  for (std::size_t m = 0; m < r.mode_time.size(); ++m)
    if (r.mode_time[m] > 0.0)  // false for NaN too
      mode_time[mode_name(r, static_cast<int>(m))] = number(r.mode_time[m]);
  j["mode_time"] = std::move(mode_time);

  j["steps"] = r.steps;
  j["wall_time"] = number(r.wall_time);

  j["goals_reached"] = r.goals_reached;
  j["goal_count"] = r.goal_count;
  j["chatter_episodes"] = r.chatter_episodes;
  j["first_chatter_time"] =
      r.first_chatter_time < 0.0 ? Json(nullptr) : number(r.first_chatter_time);
  j["final_pose"] = Json::array({number(r.final_x), number(r.final_y), number(r.final_theta)});

  const std::size_t shown = std::min(r.transitions.size(), kSummaryMaxTransitions);
  Json transitions = Json::array();
  transitions.get_ref<Json::array_t&>().reserve(shown);
  for (std::size_t i = 0; i < shown; ++i) {
    const Transition& tr = r.transitions[i];
    Json t = Json::object();
    t["t"] = number(tr.time);
    t["from"] = mode_name(r, tr.from);
    t["to"] = mode_name(r, tr.to);
    t["guard"] = name_of(r.guard_names, tr.edge, "edge_");
    t["x"] = number(at_or_nan(r.transition_x, i));
    t["y"] = number(at_or_nan(r.transition_y, i));
    transitions.push_back(std::move(t));
  }
  j["transitions"] = std::move(transitions);
  if (shown < r.transitions.size()) j["transitions_truncated"] = true;
  return j;
}

}  // namespace floornav
