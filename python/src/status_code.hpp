#pragma once
/// The status codes of the Python environments' status arrays and dicts (floornav.STATUS_NAMES),
/// shared by VecEnv and ParallelEnv.

#include <cstdint>

#include "floornav/sim/robot_agent.hpp"

namespace floornav::python {

constexpr std::int8_t kRunning = 0;

inline std::int8_t status_code(const RobotAgent& a) {
  if (!a.finished()) return kRunning;
  switch (a.result().status) {
    case RunStatus::Reached:
      return 1;
    case RunStatus::Collision:
      return 2;
    case RunStatus::Timeout:
      return 3;
    case RunStatus::Stuck:
      return 4;
  }
  return 3;
}

}  // namespace floornav::python
