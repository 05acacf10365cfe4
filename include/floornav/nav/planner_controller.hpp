#pragma once
/// @file
/// The planning layer over a reactive controller (the chapter's three levels: a plan, the
/// reactive automaton, execution). A planner finds a path to the goal on a map, string-pulls it,
/// and hands the inner controller (the automaton of Fig 5.11, or DWA) a subgoal `lookahead`
/// metres along it as the goal of its Observation; the automaton keeps doing what the plan could
/// not know (avoid, follow a boundary). GoalReached is reported only at the real goal.
///
/// One step:
///   1. map: with the sensed map (or the memory on), the rolling grid takes this step's ranges;
///   2. goal: within epsilon of the real goal -> GoalReached;
///   3. plan: when there is no path yet, on the sensed map every replan_period, when the robot
///      has strayed from the path, or after a recovery: octile A* on the raster inflated by
///      radius + inflation (then by the radius alone if that finds nothing), string-pulled;
///   4. progress: the path left must shrink by progress_distance within progress_window, else a
///      recovery: back up backup_distance, turn towards the new plan, replan. After
///      max_recoveries without progress in between (or when the known map has no path at all),
///      the command is Command::stuck() and the run ends `stuck`;
///   5. follow: the subgoal (frozen while the automaton follows a boundary or avoids, so that its
///      progress guard, eq. 5.26, measures against a fixed point) goes to the inner controller,
///      with the remembered obstacle points added to what the sensors see now.
///
///   6. guard (planner.guard_horizon > 0): the command (a velocity u tracked here by the pipeline
///      of Fig 5.12, as the simulator would) is checked by sweeping the footprint along it
///      against this step's points and the rolling grid's remembered ones
///      (nav/footprint_guard.hpp), and slowed or replaced; the recovery's back-up ends when it is
///      blocked behind, and its turn goes the other way round when blocked (both ways: it ends).
///
/// Mode names: the inner controller's, then recovery_back_up, recovery_turn, stuck. Guard
/// names: the inner's, then progress_stalled, no_path, recovered.

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "floornav/nav/controller.hpp"
#include "floornav/nav/footprint_guard.hpp"
#include "floornav/nav/pid.hpp"
#include "floornav/nav/planned_path.hpp"
#include "floornav/nav/progress_checker.hpp"
#include "floornav/nav/rolling_grid.hpp"
#include "floornav/nav/sampling_planner.hpp"
#include "floornav/planning/octile_astar.hpp"
#include "floornav/planning/raster_frame.hpp"

namespace floornav {

/// The planning raster of a known map, for one planning radius: built once and shared by every
/// robot that plans on it (a fleet on one floor, say).
struct KnownMapRaster {
  RasterFrame frame;
  FreeRaster raster;
  double radius{0.0};  ///< m the raster is inflated by
};

/// Where planners find the rasters of known maps: one per (world, radius, frame), built on first
/// use. Thread-safe (robots of a fleet plan on their own threads).
class KnownMapRasters {
 public:
  /// The raster of `world` for a disc of `radius` over the frame that scenario_optimum would
  /// use for `from` -> `goal` with cells of `cell` m; nullptr when that raster would be too large.
  std::shared_ptr<const KnownMapRaster> get(const World& world, double radius, double cell,
                                            const Vec2& from, const Vec2& goal);

 private:
  struct Entry {
    const World* world;
    std::shared_ptr<const KnownMapRaster> raster;
  };
  std::mutex mutex_;
  std::vector<Entry> entries_;
};

class PlannerController final : public Controller {
 public:
  struct Setup {
    std::unique_ptr<Controller> inner;  ///< the reactive controller that drives
    NavigationParams params;            ///< the chapter's keys of the robot's controller section
    PlannerParams planner;              ///< its `planner:` section
    const RobotSpec* robot{nullptr};    ///< must outlive the controller
    const World* map{nullptr};          ///< the known map (planner.map: known)
    std::shared_ptr<KnownMapRasters> rasters;  ///< shared raster cache; made when null
    std::uint64_t seed{1};  ///< the run's seed: rrt_connect's samples (ControllerContext::seed)
  };
  /// Throws std::invalid_argument when the known map is asked for and not given.
  explicit PlannerController(Setup setup);

  Decision decide(const Observation& obs) override;
  void reset() override;
  int mode() const override { return mode_; }

  // What the planner is doing, for tests and pictures.
  const PlannedPath& path() const { return path_; }
  Vec2 subgoal() const { return subgoal_; }
  int plans() const { return plans_; }
  int recoveries() const { return recoveries_total_; }
  /// The rolling grid (nullptr unless the map is sensed or the memory is on).
  const RollingGrid* grid() const { return grid_ ? &*grid_ : nullptr; }
  /// The planning radius and lookahead in use (the 0 defaults resolved), m.
  double plan_radius() const { return radius_; }
  double lookahead() const { return lookahead_; }
  /// Steps at which the footprint guard slowed (scaled) or replaced the command.
  int guard_slowed() const { return guard_slowed_; }
  int guard_replaced() const { return guard_replaced_; }

 private:
  enum class Phase { Follow, BackUp, Turn, Stuck };
  Decision follow(const Observation& obs);
  Decision recover(const Observation& obs);
  Decision give_up(int guard);
  /// Starts a recovery (or gives up when there were too many); `guard` says why.
  Decision begin_recovery(const Observation& obs, int guard);
  /// Plans from `from` to `goal`; false when there is no path. Updates path_ and the checker.
  bool plan(const Vec2& from, const Vec2& goal, double t);
  bool plan_known(const Vec2& from, const Vec2& goal);
  bool plan_sensed(const Vec2& from, const Vec2& goal, double t);
  /// Sensed map: the path from `x` on is still clear of the grid's inflated obstacles.
  bool sensed_path_clear(const Vec2& x, double t);
  /// The planner kind's path from cell `s` to cell `g` of `raster` (frame `f`), appended to
  /// polyline_ as world points: A*'s cell centres or RRT-Connect's samples. False: none.
  bool search_cells(const FreeRaster& raster, const RasterFrame& f, GridCell s, GridCell g);
  /// Fills points_ with the observation's points and the remembered ones; the span over them.
  std::span<const Vec2> points_with_memory(const Observation& obs);
  int own_mode(Phase p) const;
  /// The guard's points for this step: the observation's and the remembered ones nearby.
  void guard_points(const Observation& obs);
  /// The decision's command through the footprint guard (a velocity tracked to a unicycle).
  Decision guarded(const Observation& obs, Decision d);
  /// The guard says the recovery's command (v, omega) is blocked.
  bool guard_blocks(double v, double omega) const;

  std::unique_ptr<Controller> inner_;
  NavigationParams nav_;
  PlannerParams p_;
  const RobotSpec* robot_;
  const World* map_;
  std::shared_ptr<KnownMapRasters> rasters_;
  int inner_modes_{0};
  int inner_guards_{0};
  std::vector<bool> holds_subgoal_;  ///< per inner mode: a boundary-following episode

  // Resolved parameters (the zero defaults made concrete), m.
  double radius_{0.0};
  double lookahead_{0.0};
  double corner_{0.0};
  double progress_distance_{0.0};
  double backup_distance_{0.0};

  // Working memory, sized once.
  std::optional<RollingGrid> grid_;
  GridSearch search_;
  GridPath cells_;
  FreeRaster raster_;  ///< sensed map: the inflated window; known: the tight fallback
  std::shared_ptr<const KnownMapRaster> known_;
  std::vector<Vec2> polyline_;  ///< the octile path before pulling
  std::vector<Vec2> samples_;   ///< rrt_connect: the sampled path, cell units
  std::uint64_t seed_{1};
  SampledPathSearch rrt_connect_{nullptr};  ///< rrt_connect's search, as installed at construction
  std::uint64_t searches_{0};  ///< since reset: each sampling search draws from its own stream
  std::vector<Vec2> pulled_;
  std::vector<Vec2> points_;  ///< observation points plus remembered ones
  std::vector<Vec2> remembered_;
  std::optional<FootprintGuard> guard_;
  PidState pid_{};  ///< the pipeline's heading PID, when the guard tracks u itself

  // State.
  PlannedPath path_;
  Vec2 plan_goal_{Vec2::Zero()};  ///< the goal the path leads to (the real one, or clamped)
  double tail_{0.0};              ///< m from the path's end to the real goal (sensed map)
  Vec2 subgoal_{Vec2::Zero()};
  bool subgoal_held_{false};
  ProgressChecker progress_;
  double last_plan_time_{-1e300};
  double last_t_{-1e300};
  bool planned_{false};
  bool replan_now_{false};  ///< the inner controller reached its subgoal: plan again
  Phase phase_{Phase::Follow};
  double phase_start_{0.0};
  Pose2 phase_pose_{};
  double turn_target_{0.0};
  int recoveries_{0};  ///< since the last progress
  int recoveries_total_{0};
  int plans_{0};
  int mode_{0};
  int turn_sign_{0};  ///< recovery turn: 0 the short way; +1/-1 forced (the short way blocked)
  int guard_slowed_{0};
  int guard_replaced_{0};
};

}  // namespace floornav
