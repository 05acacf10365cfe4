#include "floornav/scenario/ranges_interval.hpp"

#include <algorithm>
#include <cmath>

namespace floornav {

int ranges_interval_within(const Scenario& s, double max_values) {
  double per_step = 0.0;
  for (const RobotTask& t : s.robots) per_step += static_cast<double>(t.robot.sensors.size());
  if (per_step <= 0.0 || !(s.sim.dt > 0.0) || !(max_values > 0.0)) return 0;
  const double steps = std::ceil(s.sim.t_max / s.sim.dt) + 1.0;
  return static_cast<int>(std::clamp(std::ceil(per_step * steps / max_values), 1.0, 1e9));
}

}  // namespace floornav
