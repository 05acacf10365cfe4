#include "run_caption.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>

namespace floornav::render_detail {

namespace {

// "+ 0.0" turns -0 into 0; a clearance that rounds to zero must not print as "-0.000". An
// infinite one (an empty, unbounded world: nothing to measure from) is "none", as summary.json's
// null.
std::string shown_clearance(double c) {
  if (!std::isfinite(c)) return "none";
  return fmt::format("{:.3f} m", std::round(c * 1000.0) / 1000.0 + 0.0);
}

}  // namespace

Caption run_caption(const Scenario& s, const RunResult& r) {
  Caption c;
  c.title = fmt::format("{} — {} — {} in {:.2f} s", s.name, s.robot().controller.kind,
                        to_string(r.status), r.sim_time);
  c.numbers = fmt::format("path {:.2f} m · min clearance {} · {} switch{} · {} steps",
                          r.path_length, shown_clearance(r.min_clearance), r.mode_switches,
                          r.mode_switches == 1 ? "" : "es", r.steps);
  if (r.goal_count > 1) c.numbers += fmt::format(" · goals {}/{}", r.goals_reached, r.goal_count);
  if (r.chatter_episodes > 0) c.numbers += fmt::format(" · chatter ×{}", r.chatter_episodes);
  return c;
}

Caption fleet_caption(const Scenario& s, const FleetResult& f) {
  Caption c;
  c.title = fmt::format("{} — {} robots — {} in {:.2f} s", s.name, f.robots.size(),
                        to_string(f.status), f.sim_time);
  c.numbers = fmt::format(
      "{} reached · {} collided · deliveries {}/{} · min clearance {} · {} steps", f.reached,
      f.collided, f.deliveries, f.delivery_count, shown_clearance(f.min_clearance), f.steps);
  if (!f.crowd.empty()) {
    const CrowdMetrics& m = f.crowd.metrics;
    c.numbers += fmt::format(" · {} people, {} forklifts · contacts {} / {} · {} intrusions",
                             f.crowd.people.size(), f.crowd.forklifts.size(), m.person_contacts,
                             m.forklift_contacts, m.intrusions);
  }
  return c;
}

}  // namespace floornav::render_detail
