#pragma once
/// @file
/// The planning layer's parameters (`controller.planner` in a scenario): which planner feeds the
/// chapter's automaton subgoals, on which map, and how it replans, recovers and gives up.
/// A length of 0 means "derived from the robot" (see each field); every default leaves the
/// chapter alone (`kind: none`).

#include <span>

#include "floornav/core/enum_names.hpp"

namespace floornav {

/// Which planner (`planner.kind`).
enum class PlannerKind {
  None,   ///< the chapter alone: the automaton drives straight for the goal
  AStar,  ///< octile A* on the inflated raster, string-pulled (planning/octile_astar.hpp)
  /// OMPL's RRT-Connect in R^2 on the same inflated raster, seeded from sim.seed, a budget of
  /// max_samples per plan, string-pulled like astar (nav/sampling_planner.hpp)
  RrtConnect,
};

/// Which map the planner plans on (`planner.map`).
enum class PlannerMap {
  Known,   ///< the world itself (ControllerContext::map): a floor plan known in advance
  Sensed,  ///< a rolling occupancy grid built from the robot's own range readings (no prior map)
};

inline constexpr EnumName<PlannerKind> kPlannerKindNames[]{
    {PlannerKind::None, "none"},
    {PlannerKind::AStar, "astar"},
    {PlannerKind::RrtConnect, "rrt_connect"}};
constexpr std::span<const EnumName<PlannerKind>> enum_names(PlannerKind) {
  return kPlannerKindNames;
}
inline constexpr EnumName<PlannerMap> kPlannerMapNames[]{{PlannerMap::Known, "known"},
                                                         {PlannerMap::Sensed, "sensed"}};
constexpr std::span<const EnumName<PlannerMap>> enum_names(PlannerMap) {
  return kPlannerMapNames;
}

/// The most samples one rrt_connect plan may draw (`max_samples`): a plan's time grows faster than
/// its samples (the nearest-neighbour search): 1 s for 10^5 and 43 s for 10^6 on an enclosed goal.
inline constexpr int kMaxRrtConnectSamples = 200000;

struct PlannerParams {
  PlannerKind kind{PlannerKind::None};
  PlannerMap map{PlannerMap::Known};
  /// m: the disc the plan is made for; 0: the body radius. (A footprint robot may plan as the
  /// disc of its half-width and leave the corners to the automaton's footprint clearance.)
  double radius{0.0};
  double inflation{0.05};  ///< m kept beyond `radius` from obstacles, where there is room
  /// m: planning cells; 0: the occupancy grid's own cells on a known grid map, else radius / 3.
  double cell_size{0.0};
  double lookahead{0.0};          ///< m along the path to the subgoal; 0: 6 x the body radius
  double replan_period{1.0};      ///< s between plans on the sensed map (the map keeps changing)
  double progress_window{8.0};    ///< s: the progress checker's window ...
  double progress_distance{0.0};  ///< ... in which the path left must shrink this much (m; 0: r)
  double backup_distance{0.0};    ///< m a recovery backs up; 0: the body radius
  double recovery_turn{1.5708};   ///< rad a recovery then turns on the spot (towards the path)
  int max_recoveries{3};  ///< recoveries without progress in between, then the run is `stuck`
  /// Rolling grid (the sensed map, and the memory below): side of the square window that moves
  /// with the robot, m; 0: 20 m.
  double window{0.0};
  double decay{30.0};       ///< s after which a cell not seen again fades by one step (of 4)
  double sense_range{0.0};  ///< m of each beam entered into the grid; 0: the sensor's own range
  /// m of clearance: remembered occupied cells this close to the body are given to the automaton
  /// as obstacle points, besides what the sensors see now (sparse IR rings); 0: off.
  double memory_range{0.0};
  /// rrt_connect: samples (tree extensions) one plan may draw; none connecting start and goal
  /// within them is "no path", as when A* finds none. A count, not a time, so that a plan does
  /// not depend on how fast the machine is.
  int max_samples{100000};
  /// s: the footprint guard's horizon (nav/footprint_guard.hpp): every command is checked by
  /// sweeping the robot's footprint (or its body disc) along it this long against the sensed and
  /// remembered points, and slowed or replaced when it would come within guard_margin; the
  /// recovery's back-up and turn stop or turn the other way when blocked. 0: off (the default).
  double guard_horizon{0.0};
  double guard_margin{0.02};  ///< m the footprint guard keeps from every point

  bool operator==(const PlannerParams&) const = default;

  /// Lists every field once, with its key and doc (core/param_fields.hpp).
  template <class Fields>
  static void fields(Fields& f) {
    using P = PlannerParams;
    f("kind", &P::kind, "none (the chapter alone) | astar | rrt_connect");
    f("map", &P::map, "known (the world's map) | sensed (a rolling grid from the robot's ranges)");
    f("radius", &P::radius, "disc the plan is made for, m (0: the body radius)");
    f("inflation", &P::inflation, "margin the plan keeps beyond the radius, m");
    f("cell_size", &P::cell_size, "planning cell, m (0: the map's cells, or radius / 3)");
    f("lookahead", &P::lookahead, "subgoal distance along the path, m (0: 6 x body radius)");
    f("replan_period", &P::replan_period, "s between plans on the sensed map");
    f("progress_window", &P::progress_window, "progress checker window, s");
    f("progress_distance", &P::progress_distance,
      "path length that must be gained within the window, m (0: the body radius)");
    f("backup_distance", &P::backup_distance, "recovery back-up, m (0: the body radius)");
    f("recovery_turn", &P::recovery_turn, "recovery turn on the spot, rad");
    f("max_recoveries", &P::max_recoveries, "recoveries without progress before `stuck`");
    f("window", &P::window, "rolling grid side, m (0: 20)");
    f("decay", &P::decay, "s after which an unseen rolling-grid cell fades by one step");
    f("sense_range", &P::sense_range,
      "m of each beam entered in the rolling grid (0: sensor range)");
    f("memory_range", &P::memory_range,
      "remembered cells within this clearance are obstacle points for the automaton, m (0: off)");
    f("max_samples", &P::max_samples, "rrt_connect: samples per plan before it gives up");
    f("guard_horizon", &P::guard_horizon,
      "s: sweep the footprint along each command this long and slow or replace it when it "
      "would come within guard_margin of a sensed or remembered point (0: off)");
    f("guard_margin", &P::guard_margin, "m the footprint guard keeps between footprint and points");
  }
};

}  // namespace floornav
