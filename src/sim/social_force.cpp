#include "floornav/sim/social_force.hpp"

#include <cmath>

namespace floornav {

Vec2 driving_force(const Vec2& v, const Vec2& e, double v0, const SocialForceParams& p) {
  return (v0 * e - v) / p.tau;
}

Vec2 person_repulsion(const Vec2& r, const Vec2& v_b, const SocialForceParams& p) {
  const double s = v_b.norm() * p.step_time;
  const Vec2 step = v_b.norm() > 0.0 ? Vec2(v_b * p.step_time) : Vec2::Zero();
  const double a1 = r.norm();
  const Vec2 r2 = r - step;
  const double a2 = r2.norm();
  if (a1 <= 0.0) return Vec2::Zero();  // same place: no direction to push
  const double sum = a1 + a2;
  const double b = 0.5 * std::sqrt(std::max(sum * sum - s * s, 0.0));
  const double magnitude = p.v_person / p.sigma * std::exp(-b / p.sigma);
  if (b <= 1e-9 || a2 <= 0.0) return magnitude * r / a1;  // on the other's step: straight away
  const Vec2 grad_b = sum * (r / a1 + r2 / a2) / (4.0 * b);
  return magnitude * grad_b;
}

Vec2 wall_repulsion(double distance, const Vec2& away, const SocialForceParams& p) {
  return p.u_wall / p.r_wall * std::exp(-distance / p.r_wall) * away;
}

double sight_weight(const Vec2& e, const Vec2& f, const SocialForceParams& p) {
  return e.dot(-f) >= f.norm() * std::cos(p.sight_half) ? 1.0 : p.unseen_weight;
}

}  // namespace floornav
