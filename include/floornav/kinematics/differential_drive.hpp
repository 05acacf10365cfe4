#pragma once
/// @file
/// Differential-drive kinematics (eqs. 5.5-5.8), the unicycle mapping (eqs. 5.10/5.11) and wheel
/// saturation that keeps the turn ("ensure omega").

namespace floornav {

/// Geometry and limits of a differential-drive base.
struct DiffDriveParams {
  double wheel_radius{0.0325};    ///< R, metres (QuickBot: 0.0325)
  double track_width{0.09925};    ///< L, metres between the wheels (QuickBot: 0.09925)
  double max_wheel_speed{13.61};  ///< rad/s each wheel, both directions (QuickBot: 130 RPM)
  double min_wheel_speed{0.0};    ///< rad/s; a wheel asked for less (but not 0) stalls to 0
  bool operator==(const DiffDriveParams&) const = default;
};

/// Wheel angular speeds, rad/s.
struct WheelSpeeds {
  double left{0.0};   ///< w_l
  double right{0.0};  ///< w_r
};

/// Unicycle inputs (eq. 5.9): forward speed V (m/s) and turn rate omega (rad/s).
struct UnicycleCommand {
  double v{0.0};
  double omega{0.0};
};

/// Eqs. 5.5-5.8: V = R (w_r + w_l) / 2, omega = R (w_r - w_l) / L.
UnicycleCommand wheels_to_unicycle(const DiffDriveParams& p, const WheelSpeeds& w);

/// Eqs. 5.10/5.11: w_r = (2V + omega L) / (2R), w_l = (2V - omega L) / (2R).
WheelSpeeds unicycle_to_wheels(const DiffDriveParams& p, const UnicycleCommand& u);

/// Wheel speeds that the motors can run, for command `u`:
/// omega is kept (clipped only to what the wheels can turn on the spot) and V gives way first,
/// so saturation never flips or weakens the turn while speed can still be shed; then wheels
/// asked for less than `min_wheel_speed` stall to 0.
WheelSpeeds saturate_wheels(const DiffDriveParams& p, const UnicycleCommand& u);

/// The fastest forward speed (m/s) the base can drive straight: R * max_wheel_speed.
inline double max_forward_speed(const DiffDriveParams& p) {
  return p.wheel_radius * p.max_wheel_speed;
}
/// The fastest turn on the spot (rad/s): 2 R max_wheel_speed / L.
inline double max_turn_rate(const DiffDriveParams& p) {
  return 2.0 * p.wheel_radius * p.max_wheel_speed / p.track_width;
}

}  // namespace floornav
