#pragma once
/// @file
/// Many robots in one world. Every step, each robot senses the world
/// and the bodies of the other robots (discs of their body radius) as they stood at the start of
/// the step, then decides and moves exactly as a lone robot does (robot_agent.hpp). Then the
/// robots are checked against each other: bodies that touch end both runs as collisions.
/// A robot that has finished stays where it stopped, an obstacle to the others, unless
/// `sim.park_finished` is off; a collided robot always stays.
///
/// Robots read only the positions of the previous step and write only their own state, so the
/// robots of a step can be stepped on any number of threads with the same result, bit for bit.
/// The per-step work allocates nothing; a neighbour grid (robot_neighbour_grid.hpp) finds who is
/// near whom in O(robots).

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "floornav/core/enum_names.hpp"
#include "floornav/sim/crowd.hpp"
#include "floornav/sim/robot_agent.hpp"
#include "floornav/sim/robot_neighbour_grid.hpp"
#include "floornav/sim/robot_task.hpp"
#include "floornav/sim/run_result.hpp"
#include "floornav/sim/sim_config.hpp"
#include "floornav/world/world.hpp"

namespace floornav {

/// What a robot's body touched.
enum class ContactKind { World, Robot, Person, Forklift };

inline constexpr EnumName<ContactKind> kContactKindNames[]{{ContactKind::World, "world"},
                                                           {ContactKind::Robot, "robot"},
                                                           {ContactKind::Person, "person"},
                                                           {ContactKind::Forklift, "forklift"}};
constexpr std::span<const EnumName<ContactKind>> enum_names(ContactKind) {
  return kContactKindNames;
}

/// Two robots that touched, a robot that hit the world (`other` = -1), or a robot that touched a
/// person or a forklift (`other`: its index in the crowd).
struct FleetCollision {
  double time{0.0};  ///< s
  int robot{-1};
  int other{-1};
  ContactKind kind{ContactKind::Robot};
};

struct FleetResult {
  std::string scenario;
  RunStatus status{RunStatus::Timeout};  ///< reached when all did; else collision if any; ...
  std::vector<RunResult> robots;         ///< per robot; RunResult::scenario is the robot's name
  std::vector<FleetCollision> collisions;
  int reached{0};         ///< robots that completed their whole route
  int collided{0};        ///< robots whose run ended in a collision
  int deliveries{0};      ///< goals reached, over all robots
  int delivery_count{0};  ///< goals given, over all robots
  double sim_time{0.0};   ///< s until the last robot finished (or t_max)
  long long steps{0};     ///< world steps
  long long robot_steps{0};
  double min_clearance{0.0};  ///< smallest over robots (world and each other)
  double wall_time{0.0};      ///< s, set by the caller that timed the run
  CrowdResult crowd;          ///< people and forklifts: their tracks and what the robots did
};

class FleetSimulation {
 public:
  /// `robots` in `world`; world, robots and sim (and `crowd`, people and forklifts, when given)
  /// must outlive the simulation. `name` names the run in its result.
  FleetSimulation(const World& world, std::span<const RobotTask> robots, const SimConfig& sim,
                  std::string name = "fleet", const CrowdSpec* crowd = nullptr);

  /// Advances every running robot one step on the calling thread; false once all have ended.
  bool step();

  /// Stepping from outside, one step at a time (an environment that reads every robot's
  /// observation between steps): from now on each robot keeps its own sensing, taken at the end
  /// of every step (now, for the first), which its next step acts on. The run is the same, bit
  /// for bit: a robot sensed at the end of a step senses what it would at the start of the next.
  void keep_sensing();
  /// One step of every running robot on the calling thread (keep_sensing() first, if not yet):
  /// commands[i], when set, drives robot i instead of its controller (RobotAgent::act), the
  /// others' controllers decide; an empty span lets every controller decide. Then every robot
  /// that ran in the step senses anew (one that ended: where it stopped). False once all ended.
  bool step(std::span<const std::optional<Command>> commands);
  /// Robot i's sensing after keep_sensing(): what its observation is made of.
  const SensingScratch& sensing(std::size_t i) const { return robot_scratch_[i]; }
  /// What robot i's controller sees now (after keep_sensing()).
  Observation observe(std::size_t i) const { return agents_[i].observe(robot_scratch_[i]); }
  /// The people and forklifts (nullptr: none).
  const Crowd* crowd() const { return crowd_.get(); }
  /// World steps taken so far.
  long long steps() const { return steps_; }
  /// Steps until every robot has ended, on `threads` threads (0: all cores).
  void run(int threads = 1);
  /// At most `max_steps` world steps (fewer if every robot ends), on `threads` threads (0: all
  /// cores); returns the steps taken. run() is run_steps(unlimited). An exception thrown by a
  /// robot's controller, on whatever thread, ends the step's work and is rethrown here (the
  /// simulation is then of no further use).
  long long run_steps(long long max_steps, int threads = 1);
  /// The threads run_steps uses when asked for `requested` (0: all cores): fewer when a step is
  /// too little work to share (under ~2,000 rays' worth per thread: a robot's rays, and what its
  /// robot avoidance and safety layer add).
  std::size_t threads_for(int requested) const;
  /// Robot-steps taken so far, over all robots.
  long long robot_steps() const;

  bool finished() const { return running_ == 0; }
  std::size_t size() const { return agents_.size(); }
  const RobotAgent& robot(std::size_t i) const { return agents_[i]; }
  /// The result, with each robot's mode and guard names filled in.
  FleetResult result() const;
  /// The same, moving each robot's run (and its trajectory) out instead of copying it: for the
  /// end of a simulation, which is no use afterwards.
  FleetResult take_result();

 private:
  void step_robots(std::size_t begin, std::size_t end, std::size_t thread);
  /// Robot i senses the world, the bodies near it and what it is told, into `scratch`.
  struct ThreadScratch;
  void sense_robot(std::size_t i, SensingScratch& scratch, ThreadScratch& bodies);
  // The serial and parallel parts of a step after the robots moved: file the new positions,
  // measure each robot's gap to the nearest other body (parallel), apply contacts and gaps.
  void prepare_contacts();
  double nearest_gap(std::size_t i) const;
  void measure_gaps(std::size_t begin, std::size_t end, std::size_t thread);
  void apply_gaps();
  void after_step();
  void update_snapshot();
  /// The other robots near robot i: the bodies its sensors could reach (`others`), those it is
  /// told of when it uses robot avoidance (Observation::robots), and those its safety layer
  /// keeps clear of. Returns how many of `others` it wrote.
  std::size_t gather_robots(std::size_t i, SensingScratch& scratch, ThreadScratch& bodies) const;
  /// The name of a body of the floor (a robot's, a person's, a forklift's).
  std::string body_name(const BodyRef& who, const CrowdResult& crowd) const;
  /// The fleet's result from each robot's run (in robot order), names filled in.
  FleetResult make_result(std::vector<RunResult> runs) const;

  const World& world_;
  std::span<const RobotTask> tasks_;
  const SimConfig& sim_;
  std::string name_;
  std::vector<RobotAgent> agents_;
  // The fleet as the robots see it at the start of a step (contiguous, for the grid).
  std::vector<Vec2> positions_;
  std::vector<std::uint8_t> present_;  ///< still an obstacle to the others
  std::vector<std::uint8_t> moving_;   ///< running at the start of the step
  std::vector<double> radius_;
  std::vector<double> gap_;  ///< m to the nearest other body after the move (moving robots)
  // Each robot's position and status after its move, written by the thread that moved it, so
  // that the serial part reads small arrays rather than every robot's state. moved_to_ holds
  // every robot's (a robot that did not move: its position) and becomes positions_ by a swap,
  // rather than being copied on the thread that completes the step: one serial loop fewer.
  std::vector<Vec2> moved_to_;
  std::vector<std::uint32_t> moved_cell_;  ///< grid_.cell_index(moved_to_[i])
  /// Each robot's velocity after its move (zero once ended), to become velocities_ by a swap:
  /// empty when velocities_ is.
  std::vector<Vec2> moved_velocity_;
  void note_velocity(std::size_t i);
  static constexpr std::uint8_t kEnded = 1, kCollided = 2;
  std::vector<std::uint8_t> status_;  ///< kEnded | kCollided, as of the last note_status(i)
  void note_status(std::size_t i);
  // Per thread (a cache line each): whether a robot it stepped this step ended, collided or
  // touched another. A step without any leaves the serial part nothing to apply.
  struct alignas(64) StepEvents {
    bool any{true};  // the first check, before any step, looks at every robot
  };
  std::vector<StepEvents> events_;
  bool take_events();
  std::vector<double> reach_;  ///< m from the centre: the farthest a sensor of robot i sees
  // Robot avoidance (nav/robot_avoidance.hpp): who is told of the others, how far, and the
  // velocities they are told (start of the step). Empty when no robot uses it.
  std::vector<double> tell_range_;  ///< m; 0: not told
  std::vector<Vec2> velocities_;
  // The safety layer (nav/safety_layer.hpp): which robots run it, how near another body must be
  // to matter to it (m of gap), and how far each robot can drive in one step. Empty when none.
  std::vector<std::uint8_t> safety_on_;
  std::vector<double> safety_reach_;
  std::vector<double> top_step_;
  double max_top_step_{0.0};
  double max_radius_{0.0};
  std::size_t work_per_step_{0};  ///< over all robots, in rays cast: to size the threads
  RobotNeighbourGrid grid_;
  // Per thread, each on cache lines of its own: a step writes the counts and vector ends in them
  // for every robot, and two threads' std::vector headers side by side would share a line
  // (BM_Fleet_QuickBotWarehouse/1000/2 in bench/fleet_bench.cpp decides this).
  struct alignas(64) ThreadScratch {
    explicit ThreadScratch(std::size_t sensors) : sensing(sensors) {}
    SensingScratch sensing;
    std::vector<Circle> others;       ///< the bodies a robot's sensors could reach; room for all
    std::vector<std::uint32_t> near;  ///< gather_robots' three lists of indices, room for all

    /// Room for every robot and person.
    void fit(std::size_t robots, std::size_t people = 0) {
      others.resize(robots + people);
      near.resize(3 * robots);
    }
  };
  std::vector<ThreadScratch> thread_scratch_;
  std::vector<FleetCollision> collisions_;
  // People and forklifts (none: no crowd), moved serially after the robots each step.
  std::unique_ptr<Crowd> crowd_;
  std::vector<CrowdContact> crowd_contacts_;
  RobotBodies bodies() const { return {positions_, velocities_, radius_, present_}; }
  void apply_crowd_contacts();
  std::size_t running_{0};
  long long steps_{0};
  // keep_sensing(): each robot's own sensing, and the commands of the step under way.
  std::vector<SensingScratch> robot_scratch_;
  std::span<const std::optional<Command>> commands_;
  std::vector<std::uint8_t> ran_;  ///< moving_ at the start of the step under way
};

}  // namespace floornav
