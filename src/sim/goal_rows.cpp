#include "floornav/sim/goal_rows.hpp"

#include <cmath>

namespace floornav {

std::vector<std::int64_t> goal_reached_rows(const RobotTask& task, const RunResult& r) {
  std::vector<std::int64_t> out;
  out.reserve(task.goals.size());
  std::size_t row = 0;
  bool reached = true;
  for (std::size_t g = 0; g < task.goals.size(); ++g) {
    if (reached && static_cast<int>(g) < r.goals_reached) {
      reached = false;
      for (; row < r.trajectory.size(); ++row) {
        const TrajectorySample& s = r.trajectory[row];
        if (std::hypot(s.x - task.goals[g].x(), s.y - task.goals[g].y()) <
            task.controller.params.epsilon) {
          reached = true;
          break;
        }
      }
    } else {
      reached = false;
    }
    out.push_back(reached ? static_cast<std::int64_t>(row) : -1);
  }
  return out;
}

}  // namespace floornav
