#pragma once
/// @file
/// PID on a wrapped angle error (eqs. 5.12-5.15), with anti-windup.

namespace floornav {

/// Gains of omega = K_p p + K_i integral(p dt) + K_d dp/dt (eqs. 5.13/5.15).
struct PidGains {
  double kp{4.0};              ///< 1/s
  double ki{0.0};              ///< 1/s^2
  double kd{0.0};              ///< dimensionless
  double integral_limit{1.0};  ///< rad s; |integral| is clamped to this (anti-windup)

  bool operator==(const PidGains&) const = default;

  template <class Archive>
  void serialize(Archive& a) {
    a("kp", kp, "proportional gain, 1/s");
    a("ki", ki, "integral gain, 1/s^2");
    a("kd", kd, "derivative gain");
    a("integral_limit", integral_limit, "anti-windup clamp on the integral, rad s");
  }
};

/// What a PID remembers between steps.
struct PidState {
  double integral{0.0};
  double previous_error{0.0};
  bool has_previous{false};
};

/// One PID step on `error` (already wrapped to (-pi, pi], eq. 5.14) over `dt` seconds.
/// The derivative of a wrapped error is taken on the wrapped difference, so crossing +-pi does
/// not produce a spike.
double pid_step(const PidGains& gains, PidState& state, double error, double dt);

}  // namespace floornav
