#include "floornav/sim/episode_draw.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "floornav/robot/body_clearance.hpp"

namespace floornav {

namespace {

bool clear_of(const Keepout& keep, const Vec2& p, double radius, double clearance) {
  for (const Circle& c : keep.discs)
    if ((c.center - p).norm() - c.radius - radius <= clearance) return false;
  for (const OrientedBox& b : keep.boxes)
    if (signed_distance(b, p) - radius <= clearance) return false;
  return true;
}

Vec2 uniform_in(const Box2& area, Rng& rng) {
  const double x = rng.uniform(area.min.x(), area.max.x());
  return {x, rng.uniform(area.min.y(), area.max.y())};
}

std::string text(const Box2& b) {
  return fmt::format("[{}, {}, {}, {}]", b.min.x(), b.min.y(), b.max.x(), b.max.y());
}

}  // namespace

Box2 draw_area(const World& world, const std::optional<Box2>& region) {
  Box2 area = world.bounds() ? *world.bounds() : world.extent();
  if (region) {
    area.min = area.min.cwiseMax(region->min);
    area.max = area.max.cwiseMin(region->max);
    if (!world.bounds() && world.extent().size().x() <= 0.0) area = *region;
  }
  return area;
}

std::optional<Pose2> draw_free_pose(const World& world, const RobotSpec& robot, const Box2& area,
                                    double clearance, const Keepout& keep, Rng& rng, int tries) {
  if (!(area.size().x() > 0.0 && area.size().y() > 0.0)) return std::nullopt;
  double reach = robot.body_radius;  // the body's circumscribed disc, against other bodies
  for (const Vec2& v : robot.footprint) reach = std::max(reach, v.norm());
  for (int k = 0; k < tries; ++k) {
    const Vec2 p = uniform_in(area, rng);
    const double theta = rng.uniform(-std::numbers::pi, std::numbers::pi);
    if (!clear_of(keep, p, reach, clearance)) continue;
    if (body_clearance(world, robot, Pose2{p, theta}) > clearance) return Pose2{p, theta};
  }
  return std::nullopt;
}

std::optional<Vec2> draw_free_goal(const World& world, double radius, const Box2& area,
                                   double clearance, const Vec2& from, double min_distance,
                                   double max_distance, const Keepout& keep, Rng& rng, int tries) {
  if (!(area.size().x() > 0.0 && area.size().y() > 0.0)) return std::nullopt;
  for (int k = 0; k < tries; ++k) {
    const Vec2 p = uniform_in(area, rng);
    const double d = (p - from).norm();
    if (d < min_distance || d > max_distance || !clear_of(keep, p, radius, clearance)) continue;
    if (world.clearance(p) - radius > clearance) return p;
  }
  return std::nullopt;
}

void draw_episode(const EpisodeDraw& draw, const World& world, RobotTask& task, const Keepout& keep,
                  Rng& rng) {
  if (draw.start) {
    const Box2 area = draw_area(world, draw.start_region);
    const auto pose =
        draw_free_pose(world, task.robot, area, draw.clearance, keep, rng, draw.max_tries);
    if (!pose)
      throw DrawError(fmt::format("no free start pose for '{}' in {} after {} draws", task.name,
                                  text(area), draw.max_tries));
    task.start = *pose;
  }
  if (draw.goal) {
    const Box2 area = draw_area(world, draw.goal_region);
    const double min_d = std::max(draw.min_goal_distance, task.controller.params.epsilon);
    const auto goal =
        draw_free_goal(world, task.robot.body_radius, area, draw.clearance, task.start.position,
                       min_d, draw.max_goal_distance, keep, rng, draw.max_tries);
    if (!goal)
      throw DrawError(
          fmt::format("no free goal for '{}' in {} between {} and {} m of its start after {} draws",
                      task.name, text(area), min_d, draw.max_goal_distance, draw.max_tries));
    task.goals.assign(1, *goal);
  }
}

void draw_fleet_episode(const EpisodeDraw& draw, const World& world, std::span<RobotTask> tasks,
                        const Keepout& keep, Rng& rng) {
  std::vector<Circle> starts(keep.discs.begin(), keep.discs.end());
  std::vector<Circle> goals;
  for (RobotTask& task : tasks) {
    double reach = task.robot.body_radius;
    for (const Vec2& v : task.robot.footprint) reach = std::max(reach, v.norm());
    if (draw.start) {
      EpisodeDraw only_start = draw;
      only_start.goal = false;
      draw_episode(only_start, world, task, {starts, keep.boxes}, rng);
      starts.push_back({task.start.position, reach});
    }
    if (draw.goal) {
      EpisodeDraw only_goal = draw;
      only_goal.start = false;
      draw_episode(only_goal, world, task, {goals, {}}, rng);
      goals.push_back({task.goals.front(), task.robot.body_radius});
    }
  }
}

void crowd_starts(const CrowdSpec& crowd, std::vector<Circle>& discs,
                  std::vector<OrientedBox>& boxes) {
  for (const PersonSpec& p : crowd.people) discs.push_back({p.start, p.radius});
  for (const ForkliftSpec& f : crowd.forklifts) {
    const Vec2 along = f.route.size() > 1 ? Vec2(f.route[1] - f.route[0]) : Vec2(1.0, 0.0);
    boxes.push_back(OrientedBox::make(f.route.front(), f.size, std::atan2(along.y(), along.x())));
  }
}

}  // namespace floornav
