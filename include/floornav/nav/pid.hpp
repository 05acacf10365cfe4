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

  /// Lists every field once, with its key and doc (core/param_fields.hpp).
  template <class Fields>
  static void fields(Fields& f) {
    using P = PidGains;
    f("kp", &P::kp, "proportional gain, 1/s");
    f("ki", &P::ki, "integral gain, 1/s^2");
    f("kd", &P::kd, "derivative gain");
    f("integral_limit", &P::integral_limit, "anti-windup clamp on the integral, rad s");
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
