#include "floornav/io/summary_json.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

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
  j["wait_time"] = number(r.wait_time);
  j["safety_time"] = number(r.safety_time);
  j["stuck_cause"] = r.stuck_cause.empty() ? Json(nullptr) : Json(r.stuck_cause);
  j["stuck_with"] = r.stuck_with.empty() ? Json(nullptr) : Json(r.stuck_with);
  j["path_irregularity"] = number(r.path_irregularity);

  const std::size_t shown = std::min(r.transitions.size(), kSummaryMaxTransitions);
  Json transitions = Json::array();
  transitions.get_ref<Json::array_t&>().reserve(shown);
  for (std::size_t i = 0; i < shown; ++i) {
    const Transition& tr = r.transitions[i];
    Json t = Json::object();
    t["t"] = number(tr.time);
    t["from"] = mode_name(r, tr.from);
    t["to"] = mode_name(r, tr.to);
    // A mode change that no guard made (a controller without named guards, such as dwa): null.
    t["guard"] = tr.edge >= 0 ? Json(name_of(r.guard_names, tr.edge, "edge_")) : Json(nullptr);
    t["x"] = number(at_or_nan(r.transition_x, i));
    t["y"] = number(at_or_nan(r.transition_y, i));
    transitions.push_back(std::move(t));
  }
  j["transitions"] = std::move(transitions);
  if (shown < r.transitions.size()) j["transitions_truncated"] = true;
  return j;
}

namespace {

/// The robots' mode time summed by mode name (robots may run different controllers), in the
/// order the names first appear.
Json summed_mode_time(const FleetResult& f) {
  std::vector<std::pair<std::string, double>> modes;
  for (const RunResult& r : f.robots) {
    for (std::size_t m = 0; m < r.mode_time.size(); ++m) {
      if (!(r.mode_time[m] > 0.0)) continue;
      const std::string name = mode_name(r, static_cast<int>(m));
      auto it = std::find_if(modes.begin(), modes.end(), [&](auto& e) { return e.first == name; });
      if (it == modes.end())
        modes.emplace_back(name, r.mode_time[m]);
      else
        it->second += r.mode_time[m];
    }
  }
  Json mode_time = Json::object();
  for (const auto& [name, t] : modes) mode_time[name] = number(t);
  return mode_time;
}

/// The fleet's collisions by what was hit.
struct ContactCounts {
  int world{0}, robot{0}, person{0}, forklift{0};
};

ContactCounts count_contacts(const std::vector<FleetCollision>& collisions) {
  ContactCounts n;
  for (const FleetCollision& c : collisions) {
    switch (c.kind) {
      case ContactKind::World:
        ++n.world;
        break;
      case ContactKind::Robot:
        ++n.robot;
        break;
      case ContactKind::Person:
        ++n.person;
        break;
      case ContactKind::Forklift:
        ++n.forklift;
        break;
    }
  }
  return n;
}

/// Each robot's mean heading error over its steps, weighted by its steps: the mean over every
/// robot step.
double mean_path_irregularity(const FleetResult& f) {
  double heading_error = 0.0;
  long long driven = 0;
  for (const RunResult& r : f.robots) {
    heading_error += r.path_irregularity * static_cast<double>(r.steps);
    driven += r.steps;
  }
  return driven > 0 ? heading_error / static_cast<double>(driven) : 0.0;
}

/// summary.json's `fleet`: the robots' outcomes, deliveries and collisions counted.
Json fleet_counts(const FleetResult& f) {
  int timeouts = 0, stuck = 0;
  double wait = 0.0, safety = 0.0;
  for (const RunResult& r : f.robots) {
    timeouts += r.status == RunStatus::Timeout;
    stuck += r.status == RunStatus::Stuck;
  }
  for (const RunResult& r : f.robots) wait += r.wait_time;
  for (const RunResult& r : f.robots) safety += r.safety_time;
  const ContactCounts contacts = count_contacts(f.collisions);
  Json fleet = Json::object();
  fleet["robots"] = f.robots.size();
  fleet["reached"] = f.reached;
  fleet["collided"] = f.collided;
  fleet["timeout"] = timeouts;
  fleet["stuck"] = stuck;
  fleet["deliveries"] = f.deliveries;
  fleet["delivery_count"] = f.delivery_count;
  fleet["deliveries_per_minute"] =
      f.sim_time > 0.0 ? number(60.0 * f.deliveries / f.sim_time) : Json(nullptr);
  fleet["robot_steps"] = f.robot_steps;
  fleet["robot_collisions"] = contacts.robot;
  fleet["world_collisions"] = contacts.world;
  if (!f.crowd.empty()) {
    fleet["person_collisions"] = contacts.person;
    fleet["forklift_collisions"] = contacts.forklift;
  }
  fleet["wait_time"] = number(wait);
  fleet["safety_time"] = number(safety);
  fleet["path_irregularity"] = number(mean_path_irregularity(f));
  return fleet;
}

/// summary.json's `crowd`: the people and forklifts and what happened between them and the robots.
Json crowd_json(const FleetResult& f) {
  const CrowdMetrics& m = f.crowd.metrics;
  Json crowd = Json::object();
  crowd["people"] = f.crowd.people.size();
  crowd["forklifts"] = f.crowd.forklifts.size();
  crowd["person_contacts"] = m.person_contacts;
  crowd["forklift_contacts"] = m.forklift_contacts;
  crowd["intrusions"] = m.intrusions;
  crowd["intrusion_time"] = number(m.intrusion_time);
  crowd["personal_space"] = kPersonalSpace;
  crowd["min_person_gap"] = number(m.min_person_gap);
  crowd["people_blocked_time"] = number(m.people_blocked_time);
  crowd["forklift_stopped_time"] = number(m.forklift_stopped_time);
  return crowd;
}

/// Robot `i`'s name, or null for a number that names none.
Json robot_name(const FleetResult& f, int i) {
  return i >= 0 && static_cast<std::size_t>(i) < f.robots.size()
             ? Json(f.robots[static_cast<std::size_t>(i)].scenario)
             : Json(nullptr);
}

/// One entry of summary.json's `collisions`: when, which robot, what it hit (by name).
Json collision_json(const FleetResult& f, const FleetCollision& c) {
  Json e = Json::object();
  e["t"] = number(c.time);
  e["robot"] = robot_name(f, c.robot);
  e["other"] = c.kind == ContactKind::Person && c.other >= 0 &&
                       static_cast<std::size_t>(c.other) < f.crowd.people.size()
                   ? Json(f.crowd.people[static_cast<std::size_t>(c.other)].name)
               : c.kind == ContactKind::Forklift && c.other >= 0 &&
                       static_cast<std::size_t>(c.other) < f.crowd.forklifts.size()
                   ? Json(f.crowd.forklifts[static_cast<std::size_t>(c.other)].name)
               : c.kind == ContactKind::Robot ? robot_name(f, c.other)
                                              : Json(nullptr);
  e["kind"] = std::string(to_string(c.kind));
  return e;
}

}  // namespace

nlohmann::ordered_json fleet_summary_to_json(const FleetResult& f) {
  Json j = Json::object();
  j["scenario"] = f.scenario;
  j["status"] = std::string(to_string(f.status));
  j["reached_goal"] = f.reached == static_cast<int>(f.robots.size());
  j["collided"] = f.collided > 0;
  j["sim_time"] = number(f.sim_time);
  double path = 0.0;
  long long switches = 0;
  for (const RunResult& r : f.robots) {
    path += r.path_length;
    switches += r.mode_switches;
  }
  j["path_length"] = number(path);
  j["min_clearance"] = number(f.min_clearance);
  j["mode_switches"] = switches;
  j["mode_time"] = summed_mode_time(f);
  j["steps"] = f.steps;
  j["wall_time"] = number(f.wall_time);
  j["fleet"] = fleet_counts(f);
  if (!f.crowd.empty()) j["crowd"] = crowd_json(f);

  Json collisions = Json::array();
  const std::size_t shown = std::min(f.collisions.size(), kSummaryMaxCollisions);
  for (std::size_t k = 0; k < shown; ++k) collisions.push_back(collision_json(f, f.collisions[k]));
  j["collisions"] = std::move(collisions);
  if (shown < f.collisions.size()) j["collisions_truncated"] = true;

  Json robots = Json::array();
  for (const RunResult& r : f.robots) robots.push_back(summary_to_json(r));
  j["robots"] = std::move(robots);
  return j;
}

}  // namespace floornav
