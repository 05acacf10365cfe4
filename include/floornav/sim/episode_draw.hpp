#pragma once
/// @file
/// Episodes that differ: a robot's start pose and goal drawn anew for each episode of a learning
/// environment (VecEnv's and ParallelEnv's `randomize`), uniformly over the collision-free poses
/// of an area, from a seeded Rng (the same seed, the same draws).
///
/// A start pose is free when the robot's body (its disc or footprint, at the drawn heading) keeps
/// more than `clearance` from every obstacle and from the bodies it must keep clear of (robots
/// drawn before it, people and forklifts where they start); a goal is free when the body's disc
/// centred on it does. Drawing is by rejection: uniform over the free part of the area.

#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include "floornav/core/rng.hpp"
#include "floornav/geometry/box2.hpp"
#include "floornav/geometry/circle.hpp"
#include "floornav/geometry/oriented_box.hpp"
#include "floornav/sim/crowd.hpp"
#include "floornav/sim/robot_task.hpp"
#include "floornav/world/world.hpp"

namespace floornav {

/// What is drawn per episode, and where.
struct EpisodeDraw {
  bool start{false};  ///< draw the start pose (position and heading)
  bool goal{false};   ///< draw the goal (the route becomes that one goal)
  /// Where starts and goals are drawn: this box within the world's bounds (none: the bounds, or
  /// the extent of an unbounded world).
  std::optional<Box2> start_region;
  std::optional<Box2> goal_region;
  double clearance{0.0};  ///< m the body keeps from everything at the start and the goal (> it)
  /// m between the start and a drawn goal; the goal tolerance (controller.epsilon) at least.
  double min_goal_distance{0.0};
  double max_goal_distance{std::numeric_limits<double>::infinity()};
  int max_tries{100000};  ///< draws before giving up (an area with no free pose)

  bool any() const { return start || goal; }
};

/// Bodies a drawn start or goal keeps clear of.
struct Keepout {
  std::span<const Circle> discs;
  std::span<const OrientedBox> boxes;
};

/// The box draws are made in: `region` within the world's bounds (the bounds alone without a
/// region; the world's extent when it has no bounds). Empty (size <= 0 on an axis) when the
/// region lies outside the bounds or the world has no extent.
Box2 draw_area(const World& world, const std::optional<Box2>& region);

/// A start pose for `robot`, uniform over the free poses in `area` (heading uniform in
/// [-pi, pi)); none after `tries` draws.
std::optional<Pose2> draw_free_pose(const World& world, const RobotSpec& robot, const Box2& area,
                                    double clearance, const Keepout& keep, Rng& rng, int tries);

/// A goal for a body of `radius`, uniform over the free points in `area` whose distance from
/// `from` lies in [min_distance, max_distance]; none after `tries` draws.
std::optional<Vec2> draw_free_goal(const World& world, double radius, const Box2& area,
                                   double clearance, const Vec2& from, double min_distance,
                                   double max_distance, const Keepout& keep, Rng& rng, int tries);

/// No free start or goal could be drawn (the area holds none, or too few to find).
struct DrawError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Draws `task`'s start and/or goal as `draw` says (a drawn goal replaces the route). Throws
/// DrawError saying what could not be drawn and where.
void draw_episode(const EpisodeDraw& draw, const World& world, RobotTask& task, const Keepout& keep,
                  Rng& rng);

/// Draws every robot's start and/or goal in turn (robot order): a start keeps clear of `keep`
/// (where the people and forklifts start) and of the starts drawn before it, a goal of the goals
/// drawn before it. Throws DrawError as draw_episode does.
void draw_fleet_episode(const EpisodeDraw& draw, const World& world, std::span<RobotTask> tasks,
                        const Keepout& keep, Rng& rng);

/// Where a crowd's people and forklifts stand at the start (for draws to keep clear of).
void crowd_starts(const CrowdSpec& crowd, std::vector<Circle>& discs,
                  std::vector<OrientedBox>& boxes);

/// The draws' seed for an episode whose sensor-noise seed is `seed`: another stream, so that the
/// noise and the draws do not repeat each other.
inline std::uint64_t episode_draw_seed(std::uint64_t seed) {
  return seed ^ 0xD1B54A32D192ED03ull;
}

}  // namespace floornav
