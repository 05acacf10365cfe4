#pragma once
/// @file
/// The social force model of pedestrian motion (D. Helbing, P. Molnár, "Social force model for
/// pedestrian dynamics", Physical Review E 51(5), 4282-4286, 1995): a person accelerates towards
/// its desired velocity and is pushed away from other people (an exponential potential over the
/// ellipse that the other's next step sweeps), from walls (an exponential potential of the
/// distance) and from moving machines, with less weight on what it does not see (behind it).
/// Written here: no Debian package provides a social force library (PySocialForce and HuNavSim's
/// lightsfm are not packaged).

#include "floornav/geometry/vec2.hpp"

namespace floornav {

/// The model's constants, with the paper's values.
struct SocialForceParams {
  double tau{0.5};                 ///< s: relaxation time of the driving term
  double v_person{2.1};            ///< m^2/s^2: V0 of the person-person potential
  double sigma{0.3};               ///< m: its range
  double step_time{2.0};           ///< s: Delta t, the other's step s = |v| Delta t in the ellipse
  double u_wall{10.0};             ///< m^2/s^2: U0 of the wall potential
  double r_wall{0.2};              ///< m: its range
  double sight_half{1.745329252};  ///< rad: phi, half the field of view (100 degrees)
  double unseen_weight{0.5};       ///< c: weight of forces from outside the field of view
  double max_speed_factor{1.3};    ///< v_max = 1.3 v0
};

/// The driving term (v0 e - v) / tau: towards the desired direction `e` (unit, or zero to stop)
/// at the desired speed v0.
Vec2 driving_force(const Vec2& v, const Vec2& e, double v0, const SocialForceParams& p);

/// The repulsion -grad V(b) that a person at r_b + `r` feels from another at r_b moving at `v_b`,
/// V(b) = V0 exp(-b / sigma), with 2b = sqrt((|r| + |r - s e_b|)^2 - s^2) (the semi-minor axis of
/// the ellipse through the person with foci at the other and at the other's next step, s = |v_b|
/// Delta t). Computed in closed form: grad b = (|r| + |r - s e_b|) (r/|r| + (r - s e_b)/|r - s
/// e_b|) / (4b).
Vec2 person_repulsion(const Vec2& r, const Vec2& v_b, const SocialForceParams& p);

/// The repulsion -grad U from a wall or machine at `distance` (m, from the person's centre),
/// U = U0 exp(-d / R): (U0 / R) exp(-d / R) along `away` (unit, pointing away from it).
Vec2 wall_repulsion(double distance, const Vec2& away, const SocialForceParams& p);

/// The field-of-view weight of a force `f` on a person walking along `e`: 1 when its source is
/// within phi of the walking direction (e . (-f) >= |f| cos phi), otherwise c.
double sight_weight(const Vec2& e, const Vec2& f, const SocialForceParams& p);

}  // namespace floornav
