#include "floornav/nav/pid.hpp"

#include <algorithm>

#include "floornav/geometry/angle.hpp"

namespace floornav {

double pid_step(const PidGains& gains, PidState& state, double error, double dt) {
  state.integral =
      std::clamp(state.integral + error * dt, -gains.integral_limit, gains.integral_limit);
  const double derivative =
      state.has_previous && dt > 0.0 ? wrap_angle(error - state.previous_error) / dt : 0.0;
  state.previous_error = error;
  state.has_previous = true;
  return gains.kp * error + gains.ki * state.integral + gains.kd * derivative;
}

}  // namespace floornav
