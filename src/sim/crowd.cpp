#include "floornav/sim/crowd.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "floornav/sim/robot_agent.hpp"

namespace floornav {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// m: beyond these the model's forces are negligible (walls: U0/R e^-7.5 = 0.03 m/s^2; people and
// robots: the potential's e^-b/sigma is below 1e-6 beyond 4 m).
constexpr double kWallReach = 1.5;
constexpr double kPersonReach = 4.0;
// m: the step of the central differences that give a wall's or forklift's direction.
constexpr double kGradientStep = 1e-3;
// m/s: a person slower than this on its way is blocked.
constexpr double kBlockedSpeed = 0.1;
// rad/s: how fast a forklift turns on the spot at a corner of its route.
constexpr double kForkliftTurnRate = 1.0;
// m: a forklift turns only while nobody is this close to the disc its turn sweeps.
constexpr double kTurnMargin = 0.3;

// Unit vector up the gradient of f at p (central differences), zero where f is flat.
template <class F>
Vec2 gradient_direction(const F& f, const Vec2& p) {
  const Vec2 dx(kGradientStep, 0.0), dy(0.0, kGradientStep);
  return normalized_or_zero(Vec2(f(p + dx) - f(p - dx), f(p + dy) - f(p - dy)));
}

std::size_t route_segments(const ForkliftSpec& f) {
  return f.cyclic ? f.route.size() : f.route.size() - 1;
}

// Segment k of the route: from route[k] to the next point (the first again after the last).
std::pair<Vec2, Vec2> route_segment(const ForkliftSpec& f, std::size_t k) {
  return {f.route[k], f.route[(k + 1) % f.route.size()]};
}

double heading_of(const Vec2& v, double fallback) {
  return v.squaredNorm() > 1e-18 ? std::atan2(v.y(), v.x()) : fallback;
}

}  // namespace

Crowd::Crowd(const CrowdSpec& spec, const World& world, std::size_t robots, bool record)
    : spec_(spec), world_(world), record_(record) {
  const std::size_t n_people = spec.people.size(), n_forklifts = spec.forklifts.size();
  for (std::size_t a = 0; a < n_people; ++a) {
    const PersonSpec& p = spec.people[a];
    bodies_.push_back({p.start, p.radius});
    CrowdTrack track;
    track.name = p.name.empty() ? "person" + std::to_string(a) : p.name;
    track.size = Vec2(2.0 * p.radius, 2.0 * p.radius);
    people_tracks_.push_back(std::move(track));
  }
  velocity_.assign(n_people, Vec2::Zero());
  force_.assign(n_people, Vec2::Zero());
  target_.assign(n_people, 0);
  walking_.resize(n_people);
  for (std::size_t a = 0; a < n_people; ++a) walking_[a] = !spec.people[a].waypoints.empty();
  for (std::size_t k = 0; k < n_forklifts; ++k) {
    const ForkliftSpec& f = spec.forklifts[k];
    const auto [from, to] = route_segment(f, 0);
    boxes_.push_back(OrientedBox::make(from, f.size, heading_of(to - from, 0.0)));
    CrowdTrack track;
    track.name = f.name.empty() ? "forklift" + std::to_string(k) : f.name;
    track.size = f.size;
    forklift_tracks_.push_back(std::move(track));
  }
  segment_.assign(n_forklifts, 0);
  along_.assign(n_forklifts, 0.0);
  driving_.assign(n_forklifts, 1);
  person_state_.assign(robots * n_people, 0);
  forklift_touch_.assign(robots * n_forklifts, 0);
  gap_.assign(robots, kInf);
  metrics_.min_person_gap = kInf;
  save(0.0);
}

void Crowd::save(double t) {
  for (std::size_t a = 0; a < bodies_.size(); ++a) {
    auto& s = people_tracks_[a].samples;
    const double theta = heading_of(velocity_[a], s.empty() ? 0.0 : s.back().theta);
    s.push_back({t, bodies_[a].center.x(), bodies_[a].center.y(), theta});
  }
  for (std::size_t k = 0; k < boxes_.size(); ++k) {
    const OrientedBox& b = boxes_[k];
    forklift_tracks_[k].samples.push_back(
        {t, b.center.x(), b.center.y(), std::atan2(b.axis.y(), b.axis.x())});
  }
}

void Crowd::step(double t, double dt, const RobotBodies& robots) {
  move_people(dt, robots);
  move_forklifts(dt, robots);
  t_ = t + dt;
  if (record_) save(t_);
}

void Crowd::build_person_grid() {
  const std::size_t n = bodies_.size();
  if (n == 0) return;
  Vec2 lo = bodies_[0].center, hi = lo;
  for (const Circle& c : bodies_) lo = lo.cwiseMin(c.center), hi = hi.cwiseMax(c.center);
  // Cells of at least the reach (so that the 3 x 3 around a person hold everyone who can push
  // it), coarser when the people are spread far apart: at most 4 cells a person.
  double cell = kPersonReach * (1.0 + 1e-9);  // above the reach, whatever the rounding
  const double max_cells = 4.0 * static_cast<double>(n) + 16.0;
  const auto count = [&](double c) {
    return (std::floor((hi.x() - lo.x()) / c) + 1.0) * (std::floor((hi.y() - lo.y()) / c) + 1.0);
  };
  while (count(cell) > max_cells) cell *= 2.0;
  grid_origin_ = lo;
  grid_cell_ = cell;
  grid_nx_ = static_cast<int>(std::floor((hi.x() - lo.x()) / cell)) + 1;
  grid_ny_ = static_cast<int>(std::floor((hi.y() - lo.y()) / cell)) + 1;
  const std::size_t cells = static_cast<std::size_t>(grid_nx_) * static_cast<std::size_t>(grid_ny_);
  cell_of_.resize(n);
  cell_start_.assign(cells + 1, 0);
  for (std::size_t a = 0; a < n; ++a) {
    const Vec2 q = (bodies_[a].center - lo) / cell;
    const int ix = std::min(grid_nx_ - 1, static_cast<int>(q.x()));
    const int iy = std::min(grid_ny_ - 1, static_cast<int>(q.y()));
    cell_of_[a] = static_cast<std::uint32_t>(iy * grid_nx_ + ix);
    ++cell_start_[cell_of_[a] + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_items_.resize(n);
  fill_.assign(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t a = 0; a < n; ++a)  // in index order: each cell's list ascends
    cell_items_[fill_[cell_of_[a]]++] = static_cast<std::uint32_t>(a);
}

void Crowd::neighbours_of(std::size_t a) {
  near_.clear();
  const int cx = static_cast<int>(cell_of_[a]) % grid_nx_;
  const int cy = static_cast<int>(cell_of_[a]) / grid_nx_;
  for (int y = std::max(0, cy - 1); y <= std::min(grid_ny_ - 1, cy + 1); ++y)
    for (int x = std::max(0, cx - 1); x <= std::min(grid_nx_ - 1, cx + 1); ++x) {
      const std::size_t c = static_cast<std::size_t>(y * grid_nx_ + x);
      near_.insert(near_.end(), cell_items_.begin() + cell_start_[c],
                   cell_items_.begin() + cell_start_[c + 1]);
    }
  std::sort(near_.begin(), near_.end());
}

void Crowd::move_people(double dt, const RobotBodies& robots) {
  const SocialForceParams& sf = spec_.social;
  const std::size_t n = bodies_.size();
  build_person_grid();
  person_pairs_tested_ = 0;
  // Forces from the state at the start of the step, for everyone; then everyone moves.
  for (std::size_t a = 0; a < n; ++a) {
    const PersonSpec& spec = spec_.people[a];
    const Vec2 x = bodies_[a].center;
    const Vec2 e = walking_[a] ? normalized_or_zero(spec.waypoints[target_[a]] - x) : Vec2::Zero();
    // What the person looks along: where it walks, else where it moves.
    const Vec2 look = walking_[a] ? e : normalized_or_zero(velocity_[a]);
    Vec2 force = driving_force(velocity_[a], e, walking_[a] ? spec.speed : 0.0, sf);
    auto push = [&](const Vec2& from, const Vec2& v) {
      const Vec2 r = x - from;
      if (r.squaredNorm() > kPersonReach * kPersonReach) return;
      const Vec2 f = person_repulsion(r, v, sf);
      force += (look.squaredNorm() > 0.0 ? sight_weight(look, f, sf) : 1.0) * f;
    };
    // Only people within kPersonReach push: those of the 3 x 3 grid cells around, in index
    // order, so that the sum is the all-pairs loop's bit for bit (the others add nothing).
    neighbours_of(a);
    person_pairs_tested_ += near_.size() - 1;  // near_ holds a itself
    for (const std::uint32_t b : near_)
      if (b != a) push(bodies_[b].center, velocity_[b]);
    // A robot is a moving obstacle: people anticipate its step as they do another person's,
    // and keep their bodies off its body as off a wall (the wall potential of the gap).
    for (std::size_t j = 0; j < robots.position.size(); ++j) {
      if (!robots.present[j]) continue;
      push(robots.position[j], robots.velocity[j]);
      const Vec2 r = x - robots.position[j];
      const double gap = r.norm() - robots.radius[j] - spec.radius;
      if (gap < kWallReach) force += wall_repulsion(gap, normalized_or_zero(r), sf);
    }
    const double wall = world_.clearance(x);
    if (wall < kWallReach) {
      const Vec2 away = gradient_direction([&](const Vec2& q) { return world_.clearance(q); }, x);
      force += wall_repulsion(wall, away, sf);
    }
    for (const OrientedBox& box : boxes_) {
      const double d = signed_distance(box, x) - spec.radius;  // the gap to the body
      if (d >= kWallReach) continue;
      const Vec2 away =
          gradient_direction([&](const Vec2& q) { return signed_distance(box, q); }, x);
      force += wall_repulsion(d, away, sf);
    }
    force_[a] = force;
  }
  for (std::size_t a = 0; a < n; ++a) {
    const PersonSpec& spec = spec_.people[a];
    CrowdTrack& track = people_tracks_[a];
    Vec2 v = velocity_[a] + dt * force_[a];
    const double v_max = sf.max_speed_factor * spec.speed;
    if (v.norm() > v_max) v *= v_max / v.norm();
    velocity_[a] = v;
    bodies_[a].center += dt * v;
    track.path_length += dt * v.norm();
    if (!walking_[a]) continue;
    if (v.norm() < kBlockedSpeed) {
      track.still_time += dt;
      metrics_.people_blocked_time += dt;
    }
    if ((spec.waypoints[target_[a]] - bodies_[a].center).norm() < spec.goal_radius) {
      ++track.waypoints_reached;
      if (++target_[a] >= spec.waypoints.size()) {
        target_[a] = 0;
        walking_[a] = spec.cyclic;
      }
    }
  }
}

bool Crowd::disc_occupied(const Vec2& centre, double radius, const RobotBodies& robots) const {
  for (std::size_t j = 0; j < robots.position.size(); ++j) {
    const double r = radius + robots.radius[j];
    if (robots.present[j] && (robots.position[j] - centre).squaredNorm() < r * r) return true;
  }
  for (const Circle& c : bodies_) {
    const double r = radius + c.radius;
    if ((c.center - centre).squaredNorm() < r * r) return true;
  }
  return false;
}

bool Crowd::zone_occupied(const OrientedBox& box, double stop_distance,
                          const RobotBodies& robots) const {
  const OrientedBox zone{box.center + (box.half.x() + 0.5 * stop_distance) * box.axis,
                         Vec2(0.5 * stop_distance, box.half.y()), box.axis};
  for (std::size_t j = 0; j < robots.position.size(); ++j)
    if (robots.present[j] && signed_distance(zone, robots.position[j]) < robots.radius[j])
      return true;
  for (const Circle& c : bodies_)
    if (signed_distance(zone, c.center) < c.radius) return true;
  return false;
}

void Crowd::move_forklifts(double dt, const RobotBodies& robots) {
  for (std::size_t k = 0; k < boxes_.size(); ++k) {
    const ForkliftSpec& f = spec_.forklifts[k];
    CrowdTrack& track = forklift_tracks_[k];
    OrientedBox& box = boxes_[k];
    const auto [from, to] = route_segment(f, segment_[k]);
    const Vec2 dir = normalized_or_zero(to - from);
    const double turn = std::atan2(cross(box.axis, dir), box.axis.dot(dir));
    // At a corner it turns on the spot first, sweeping the disc round its centre: it waits
    // while a body is within kTurnMargin of that disc; on a straight, while one is in the zone
    // stop_distance ahead. With stop_distance 0 it never waits.
    const bool turning = std::abs(turn) > 1e-9;
    const bool blocked =
        !driving_[k] ||
        (f.stop_distance > 0.0 &&
         (turning ? disc_occupied(box.center,
                                  box.bounding_radius() + std::min(f.stop_distance, kTurnMargin),
                                  robots)
                  : zone_occupied(box, f.stop_distance, robots)));
    if (blocked) {
      track.still_time += dt;
      metrics_.forklift_stopped_time += dt;
      continue;
    }
    if (turning) {
      const double step = std::clamp(turn, -kForkliftTurnRate * dt, kForkliftTurnRate * dt);
      box.axis = step == turn ? dir : normalized_or_zero(rotate(box.axis, step));
      continue;
    }
    // Along the segment, to its end at most (the turn there takes the next steps).
    const double length = (to - from).norm();
    const double moved = std::min(f.speed * dt, length - along_[k]);
    along_[k] += moved;
    track.path_length += moved;
    box.center = from + along_[k] * dir;
    if (along_[k] >= length) {
      ++track.waypoints_reached;
      if (segment_[k] + 1 >= route_segments(f) && !f.cyclic) {
        driving_[k] = 0;
        continue;
      }
      segment_[k] = (segment_[k] + 1) % route_segments(f);
      along_[k] = 0.0;
    }
  }
}

void Crowd::check(double dt, const RobotBodies& robots, std::vector<CrowdContact>& contacts) {
  const std::size_t n_people = bodies_.size(), n_forklifts = boxes_.size();
  for (std::size_t i = 0; i < robots.position.size(); ++i) {
    std::uint8_t* person = person_state_.data() + i * n_people;
    std::uint8_t* forklift = forklift_touch_.data() + i * n_forklifts;
    if (!robots.present[i]) {
      std::fill(person, person + n_people, 0);
      std::fill(forklift, forklift + n_forklifts, 0);
      gap_[i] = kInf;
      continue;
    }
    const Vec2 p = robots.position[i];
    const double r = robots.radius[i];
    double nearest = kInf;
    for (std::size_t a = 0; a < n_people; ++a) {
      const double gap = (bodies_[a].center - p).norm() - r - bodies_[a].radius;
      nearest = std::min(nearest, gap);
      metrics_.min_person_gap = std::min(metrics_.min_person_gap, gap);
      const bool touching = gap <= 0.0, intruding = gap < kPersonalSpace;
      if (touching && !(person[a] & 1u)) {
        ++metrics_.person_contacts;
        contacts.push_back({i, a, false, gap});
      }
      if (intruding && !(person[a] & 2u)) ++metrics_.intrusions;
      if (intruding) metrics_.intrusion_time += dt;
      person[a] = static_cast<std::uint8_t>((touching ? 1u : 0u) | (intruding ? 2u : 0u));
    }
    for (std::size_t k = 0; k < n_forklifts; ++k) {
      const double gap = signed_distance(boxes_[k], p) - r;
      nearest = std::min(nearest, gap);
      const bool touching = gap <= 0.0;
      if (touching && !forklift[k]) {
        ++metrics_.forklift_contacts;
        contacts.push_back({i, k, true, gap});
      }
      forklift[k] = touching;
    }
    gap_[i] = nearest;
  }
}

void Crowd::safety_bodies_near(const Vec2& p, double reach, double dt, double person_margin,
                               SensingScratch& scratch) const {
  const SocialForceParams& sf = spec_.social;
  for (std::size_t a = 0; a < bodies_.size(); ++a) {
    const Circle& c = bodies_[a];
    const double r =
        reach + c.radius + person_margin + sf.max_speed_factor * spec_.people[a].speed * dt;
    if ((c.center - p).squaredNorm() >= r * r) continue;
    SafetyDisc& d = scratch.safety_discs[scratch.safety_disc_count++];
    d.position = c.center;
    d.radius = c.radius;
    d.approach = sf.max_speed_factor * spec_.people[a].speed * dt;
    d.reciprocal = false;
    d.extra_margin = person_margin;
    d.who = {BodyRef::Kind::Person, static_cast<std::uint32_t>(a)};
  }
  for (std::size_t k = 0; k < boxes_.size(); ++k) {
    const OrientedBox& b = boxes_[k];
    // Driving on, or turning on the spot at a corner of its route (its far corners sweep fastest).
    const double approach =
        std::max(spec_.forklifts[k].speed, kForkliftTurnRate * b.bounding_radius()) * dt;
    if (signed_distance(b, p) >= reach + approach) continue;
    scratch.safety_boxes[scratch.safety_box_count++] = {
        b, approach, {BodyRef::Kind::Forklift, static_cast<std::uint32_t>(k)}};
  }
}

std::size_t Crowd::people_near(const Vec2& p, double reach, std::span<Circle> out,
                               std::size_t n) const {
  for (const Circle& c : bodies_) {
    const double r = reach + c.radius;
    if ((c.center - p).squaredNorm() < r * r) out[n++] = c;
  }
  return n;
}

CrowdResult Crowd::result() const {
  CrowdResult r;
  r.people = people_tracks_;
  r.forklifts = forklift_tracks_;
  r.metrics = metrics_;
  // Unrecorded runs keep the start and the end.
  if (!record_) {
    for (std::size_t a = 0; a < bodies_.size(); ++a)
      r.people[a].samples.push_back(
          {t_, bodies_[a].center.x(), bodies_[a].center.y(), heading_of(velocity_[a], 0.0)});
    for (std::size_t k = 0; k < boxes_.size(); ++k)
      r.forklifts[k].samples.push_back({t_, boxes_[k].center.x(), boxes_[k].center.y(),
                                        std::atan2(boxes_[k].axis.y(), boxes_[k].axis.x())});
  }
  return r;
}

}  // namespace floornav
