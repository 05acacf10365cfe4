#pragma once
/// @file
/// People and forklifts on the floor: moving obstacles that the robots' range sensors see and
/// that end a robot's run when its body touches them.
///   - People walk between their waypoints by the social force model (social_force.hpp), pushed
///     by each other, by the walls, and by robots and forklifts: moving obstacles, whose bodies
///     push as walls do (the wall potential of the gap between the bodies; walls themselves
///     push by the distance from the person's centre, as in the paper), and whose next step
///     people anticipate as another person's (robots). Bodies are discs.
///   - Forklifts drive scripted routes (polylines, at a fixed speed, turning on the spot at the
///     corners at 1 rad/s), their footprints rectangles along the route; each stops while a robot
///     or a person stands in the zone `stop_distance` ahead of it (a safety scanner), and turns
///     only while nobody is within 0.3 m of the disc its turn sweeps.
/// A step moves everyone from the state at its start (people do not depend on each other's order),
/// serially: the same scenario gives the same crowd, bit for bit, whatever the robots' threads.
/// With no people and no forklifts a fleet has no Crowd at all.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "floornav/geometry/circle.hpp"
#include "floornav/geometry/oriented_box.hpp"
#include "floornav/sim/social_force.hpp"
#include "floornav/world/world.hpp"

namespace floornav {

struct SensingScratch;

/// A person of the scenario (`people:`).
struct PersonSpec {
  std::string name;
  Vec2 start{Vec2::Zero()};
  std::vector<Vec2> waypoints;  ///< walked in order
  double speed{1.2};            ///< m/s, v0: the desired walking speed
  double radius{0.25};          ///< m: the body disc
  double goal_radius{0.3};      ///< m: a waypoint this close is reached
  bool cyclic{true};            ///< after the last waypoint, the first again (else stand there)
};

/// A forklift of the scenario (`forklifts:`).
struct ForkliftSpec {
  std::string name;
  std::vector<Vec2> route;    ///< at least two points; the forklift starts at the first
  double speed{1.0};          ///< m/s along the route
  Vec2 size{2.0, 1.0};        ///< m: length (along the route) and width
  double stop_distance{1.0};  ///< m: it stops while a body is this close ahead (0: never)
  bool cyclic{true};          ///< back to the first point after the last (else stop there)
};

struct CrowdSpec {
  std::vector<PersonSpec> people;
  std::vector<ForkliftSpec> forklifts;
  SocialForceParams social{};

  bool empty() const { return people.empty() && forklifts.empty(); }
};

/// One recorded state of a person or forklift.
struct CrowdSample {
  double t, x, y, theta;  ///< s, m, m, rad (the walking or driving direction)
};

/// A person's or forklift's run: its samples (every step while the trajectory is recorded; else
/// the first and last) and its own figures.
struct CrowdTrack {
  std::string name;
  Vec2 size{Vec2::Zero()};  ///< forklift: length, width; person: diameter, diameter
  std::vector<CrowdSample> samples;
  double path_length{0.0};  ///< m
  double still_time{0.0};  ///< s: person slower than 0.1 m/s on its way (blocked); forklift stopped
  int waypoints_reached{0};  ///< person: waypoints reached; forklift: route points passed
};

/// What the robots did to the people and forklifts.
struct CrowdMetrics {
  int person_contacts{0};    ///< a robot's body touched a person's (pairs, counted once per touch)
  int forklift_contacts{0};  ///< a robot's body touched a forklift's footprint
  /// A robot's body came within kPersonalSpace of a person's (pairs, counted once per entry).
  int intrusions{0};
  double intrusion_time{0.0};  ///< s, summed over robot-person pairs
  double min_person_gap{0.0};  ///< m: smallest robot-person gap between bodies (inf: none near)
  double people_blocked_time{0.0};    ///< s, summed over people (CrowdTrack::still_time)
  double forklift_stopped_time{0.0};  ///< s, summed over forklifts
};

struct CrowdResult {
  std::vector<CrowdTrack> people;
  std::vector<CrowdTrack> forklifts;
  CrowdMetrics metrics{};
  bool empty() const { return people.empty() && forklifts.empty(); }
};

/// A robot's body touching a person (`forklift` false) or a forklift.
struct CrowdContact {
  std::size_t robot{0};
  std::size_t other{0};  ///< index of the person or forklift
  bool forklift{false};
  double gap{0.0};  ///< m, <= 0
};

/// m: the personal space; a robot's body nearer than this to a person's is an intrusion.
inline constexpr double kPersonalSpace = 0.5;

/// The robots as the crowd sees them at one moment (positions, velocities, radii, and whether
/// each is on the floor).
struct RobotBodies {
  std::span<const Vec2> position;
  std::span<const Vec2> velocity;
  std::span<const double> radius;
  std::span<const std::uint8_t> present;
};

class Crowd {
 public:
  /// `spec` and `world` must outlive the crowd. `robots` sizes the per-pair contact state.
  Crowd(const CrowdSpec& spec, const World& world, std::size_t robots, bool record);

  /// Moves everyone from time t to t + dt around the robots' bodies.
  void step(double t, double dt, const RobotBodies& robots);
  /// Measures the robots' bodies against the people and forklifts at time t after a step:
  /// metrics, and every robot-person or robot-forklift pair that has just come into contact
  /// appended to `contacts`. `moving[i]`: robot i was running during the step.
  void check(double dt, const RobotBodies& robots, std::vector<CrowdContact>& contacts);
  /// m: the gap from robot i's body to the nearest person or forklift (inf: none).
  double nearest_gap(std::size_t robot) const { return gap_[robot]; }

  /// The people's bodies now.
  std::span<const Circle> people() const { return bodies_; }
  /// The forklifts' footprints now.
  std::span<const OrientedBox> forklifts() const { return boxes_; }
  /// Writes to the safety scratch of a robot at `p` the people and forklifts whose bodies come
  /// within `reach` of it, each with how far it may come in one step of `dt`; people get
  /// `person_margin` as extra margin.
  void safety_bodies_near(const Vec2& p, double reach, double dt, double person_margin,
                          SensingScratch& scratch) const;
  /// Writes the bodies of the people whose disc comes within `reach` of `p` into `out` from
  /// index `n` (out has room for every person beyond it); returns the new count.
  std::size_t people_near(const Vec2& p, double reach, std::span<Circle> out, std::size_t n) const;

  /// How many (ordered) pairs of people the last step tested for a push: at most n (n - 1), only
  /// the pairs within a grid cell of each other (docs/RELIABILITY.md, "Limits").
  std::size_t person_pairs_tested() const { return person_pairs_tested_; }

  /// The tracks and metrics so far (the last state recorded as the final sample).
  CrowdResult result() const;

 private:
  void move_people(double dt, const RobotBodies& robots);
  void move_forklifts(double dt, const RobotBodies& robots);
  void save(double t);  ///< appends the current state to the tracks
  bool zone_occupied(const OrientedBox& box, double stop_distance, const RobotBodies& robots) const;
  bool disc_occupied(const Vec2& centre, double radius, const RobotBodies& robots) const;

  const CrowdSpec& spec_;
  const World& world_;
  bool record_;
  double t_{0.0};
  // People: bodies, velocities, the waypoint each walks to.
  std::vector<Circle> bodies_;
  std::vector<Vec2> velocity_;
  std::vector<std::size_t> target_;
  std::vector<std::uint8_t> walking_;  ///< has a waypoint to go to
  std::vector<Vec2> force_;            ///< scratch: each person's force this step
  // Scratch of the people's grid (build_person_grid): who can push whom without testing every
  // pair (10,000 people once took minutes a simulated minute).
  void build_person_grid();
  void neighbours_of(std::size_t a);  ///< into near_, ascending
  Vec2 grid_origin_{Vec2::Zero()};
  double grid_cell_{1.0};
  int grid_nx_{1}, grid_ny_{1};
  std::vector<std::uint32_t> cell_of_, cell_start_, cell_items_, fill_, near_;
  std::size_t person_pairs_tested_{0};
  // Forklifts: footprint, the route segment and how far along it.
  std::vector<OrientedBox> boxes_;
  std::vector<std::size_t> segment_;
  std::vector<double> along_;
  std::vector<std::uint8_t> driving_;
  // Robot-person (robot-major) and robot-forklift contact and intrusion state.
  std::vector<std::uint8_t> person_state_;
  std::vector<std::uint8_t> forklift_touch_;
  std::vector<double> gap_;
  std::vector<CrowdTrack> people_tracks_, forklift_tracks_;
  CrowdMetrics metrics_{};
};

}  // namespace floornav
