#pragma once
/// @file
/// What a run produced: the outcome (a value, never an exception), the metrics of the summary,
/// the transition log, and the trajectory when it was recorded.

#include <string>
#include <string_view>
#include <vector>

#include "floornav/automaton/hybrid_automaton.hpp"
#include "floornav/core/enum_names.hpp"

namespace floornav {

enum class RunStatus { Reached, Collision, Timeout, Stuck };

inline constexpr EnumName<RunStatus> kRunStatusNames[]{{RunStatus::Reached, "reached"},
                                                       {RunStatus::Collision, "collision"},
                                                       {RunStatus::Timeout, "timeout"},
                                                       {RunStatus::Stuck, "stuck"}};
constexpr std::span<const EnumName<RunStatus>> enum_names(RunStatus) {
  return kRunStatusNames;
}

/// One row of trajectory.csv: the state after a step and the commands that drove it.
struct TrajectorySample {
  double t, x, y, theta;   ///< s, m, m, rad
  double v, omega;         ///< m/s, rad/s actually driven (after saturation)
  double w_left, w_right;  ///< rad/s
  int mode;                ///< index into RunResult::mode_names
};

struct RunResult {
  std::string scenario;
  RunStatus status{RunStatus::Timeout};
  bool reached_goal{false};  ///< every goal was reached
  bool collided{false};
  int goals_reached{0};
  int goal_count{0};
  double sim_time{0.0};
  double path_length{0.0};
  /// s the robot's body moved slower than 1 cm/s before its run ended (waiting, turning on the
  /// spot): SEAN 2.0's and SocNavBench's "time not moving".
  double wait_time{0.0};
  /// rad: path irregularity, the mean over steps of the angle between the robot's heading and
  /// the straight line to the goal it drives to (SocNavBench; 0 for a robot driving straight at
  /// its goal). See RobotAgent::act.
  double path_irregularity{0.0};
  /// s during which the safety layer changed the controller's command (slowed, stopped it)
  double safety_time{0.0};
  int safety_steps{0};  ///< steps at which it did
  /// Why a `stuck` run ended: "no_progress" (it stayed put, nothing moving near), "deadlock"
  /// (held up among moving bodies for sim.deadlock_window), "livelock" (moving among them
  /// without nearing its goal for sim.livelock_window), "controller" (its controller gave up);
  /// empty otherwise.
  std::string stuck_cause;
  /// The moving body nearest the robot when a deadlock or livelock ended its run: a robot's,
  /// person's or forklift's name (filled in by the fleet); empty otherwise.
  std::string stuck_with;
  double min_clearance{0.0};  ///< m between body and obstacles, over the run (<= 0 on collision)
  int mode_switches{0};
  int steps{0};
  double wall_time{0.0};  ///< s, set by the caller that timed the run
  int chatter_episodes{0};
  double first_chatter_time{-1.0};
  std::vector<std::string> mode_names;   ///< indexable by mode
  std::vector<std::string> guard_names;  ///< indexable by Transition::edge
  std::vector<double> mode_time;         ///< s per mode
  std::vector<Transition> transitions;
  std::vector<double> transition_x, transition_y;  ///< where each transition happened
  std::vector<TrajectorySample> trajectory;
  /// Sensor ranges recorded every SimConfig::record_ranges_every steps (empty when it is 0):
  /// frame k was sensed after range_steps[k] steps (at the pose of trajectory row
  /// range_steps[k]) and holds one range per sensor (m, as the robot read it, noise included):
  /// ranges[k * sensors + i] for sensor i.
  std::vector<int> range_steps;
  std::vector<float> ranges;
  /// The extra columns recorded with the trajectory (SimConfig::record), by name, and their
  /// values: extra_columns.size() per trajectory row, row-major; NaN where a value does not apply
  /// (no velocity command, the first row's command and ranges).
  std::vector<std::string> extra_columns;
  std::vector<double> extra;
  double final_x{0.0}, final_y{0.0}, final_theta{0.0};
};

}  // namespace floornav
