#include "floornav/sim/fleet_simulation.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>

#include "floornav/nav/navigation_controller.hpp"
#include "floornav/sim/robot_models.hpp"
#include "spin_barrier.hpp"

namespace floornav {

namespace {

// Robot i's noise seed: the scenario's seed for the first robot (a fleet of one runs exactly as
// Simulation does), then well-spread odd steps so that robots draw independent noise.
std::uint64_t robot_seed(std::uint64_t seed, std::size_t i) {
  return seed + 0x9E3779B97F4A7C15ull * static_cast<std::uint64_t>(i);
}

// The farthest point a sensor of `robot` can report, from the robot's centre.
double sensing_reach(const RobotSpec& robot) {
  double reach = robot.body_radius;
  for (const RangeSensorSpec& s : robot.sensors)
    reach = std::max(reach, s.mount.position.norm() + s.max_range);
  return reach;
}

// m of gap within which another body matters to robot `robot`'s safety layer. The bodies
// within it are the ones whose returns its mapless memory does not keep (RobotAgent).
double safety_reach(const RobotSpec& robot, const SafetyParams& safety, double dt) {
  return SafetyLayer(robot, safety, dt).gap_reach();
}

// The work of a robot's step in rays cast (a ray is ~200 instructions): what a thread should have
// per step before a fleet is split across threads, and what a robot's layers add to its rays
// (callgrind of circle_100: ORCA with its neighbours 25-30 rays, the safety layer ~10). Whole
// runs of circle_100 and BM_Fleet_QuickBotWarehouse/50 and /100 on 1 and 2 threads decide them:
// 100 QuickBots with both layers pay for a second thread, 50 do not.
constexpr std::size_t kRaysPerThread = 2000;
constexpr std::size_t kAvoidanceRays = 25;
constexpr std::size_t kSafetyRays = 10;
// Robots a thread takes at a time when a fleet is split: small enough that the threads finish a
// phase together (robots cost from a free-disc shortcut to a full scan, and finished robots
// nothing), large enough that taking one costs nothing beside stepping it.
constexpr std::size_t kRobotsPerChunk = 16;

}  // namespace

FleetSimulation::FleetSimulation(const World& world, std::span<const RobotTask> robots,
                                 const SimConfig& sim, std::string name, const CrowdSpec* crowd)
    : world_(world), tasks_(robots), sim_(sim), name_(std::move(name)) {
  const std::size_t n = tasks_.size();
  ControllerMaker controllers;  // robots of one built-in kind share one automaton
  RobotModels models;           // and one copy of each robot model
  std::size_t max_sensors = 0;
  double max_reach = 0.0;
  agents_.reserve(n);
  radius_.resize(n);
  reach_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const RobotTask& t = tasks_[i];
    AgentSetup a;
    a.world = &world_;
    a.task = &t;
    a.sim = &sim_;
    a.controller = controllers.make(
        t.controller, {t.robot, t.controller.params, t.name, i, &world, robot_seed(sim_.seed, i)});
    a.seed = robot_seed(sim_.seed, i);
    a.name = t.name;
    a.log_transitions = n == 1 || sim_.record_trajectory;
    a.names = false;
    a.reserve_trajectory = n == 1;
    a.model = models.find(t);
    agents_.emplace_back(std::move(a));
    radius_[i] = t.robot.body_radius;
    reach_[i] = sensing_reach(t.robot);
    max_radius_ = std::max(max_radius_, radius_[i]);
    max_reach = std::max(max_reach, reach_[i]);
    max_sensors = std::max(max_sensors, t.robot.sensors.size());
    top_step_.push_back(max_forward_speed(t.robot.drive) * sim_.dt);
    max_top_step_ = std::max(max_top_step_, top_step_.back());
    if (t.controller.safety.enabled) {
      safety_on_.resize(n, 0);
      safety_reach_.resize(n, 0.0);
      safety_on_[i] = 1;
      safety_reach_[i] = safety_reach(t.robot, t.controller.safety, sim_.dt);
    }
    if (t.controller.avoidance.kind != RobotAvoidance::None) {
      tell_range_.resize(n, 0.0);
      tell_range_[i] = t.controller.avoidance.range;
    }
    for (const RangeSensorSpec& sensor : t.robot.sensors)
      work_per_step_ += static_cast<std::size_t>(std::max(sensor.cone_rays, 1));
    if (t.controller.safety.enabled) work_per_step_ += kSafetyRays;
    if (t.controller.avoidance.kind != RobotAvoidance::None) work_per_step_ += kAvoidanceRays;
  }
  thread_scratch_.emplace_back(max_sensors);
  events_.resize(1);
  if (!tell_range_.empty()) thread_scratch_.back().sensing.robots.resize(n);
  if (!tell_range_.empty() || (crowd && !crowd->empty())) velocities_.assign(n, Vec2::Zero());
  thread_scratch_.back().fit(n);

  // The grid covers the world (and the robots, for unbounded worlds); cells about one sensing
  // reach wide, so a robot's query touches few cells.
  Box2 box = world_.extent();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 p = tasks_[i].start.position;
    if (i == 0 && box.size().x() <= 0.0 && box.size().y() <= 0.0) box = Box2{p, p};
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  grid_.reset(box, std::max(max_reach + max_radius_, 2.0 * max_radius_), n);
  positions_.resize(n);
  present_.assign(n, 0);
  moving_.assign(n, 0);
  gap_.assign(n, 0.0);
  status_.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    positions_[i] = agents_[i].pose().position;
    note_status(i);
  }
  moved_to_ = positions_;
  if (!velocities_.empty()) {
    moved_velocity_.resize(n);
    for (std::size_t i = 0; i < n; ++i) note_velocity(i);
  }
  moved_cell_.resize(n);
  for (std::size_t i = 0; i < n; ++i) moved_cell_[i] = grid_.cell_index(positions_[i]);
  update_snapshot();

  // Robots that start touching each other have collided before the first step.
  after_step();
  steps_ = 0;
  // The crowd starts after that check (validation keeps robots clear of people and forklifts).
  if (crowd && !crowd->empty()) {
    crowd_ = std::make_unique<Crowd>(*crowd, world_, n, sim_.record_trajectory);
    thread_scratch_.back().fit(n, crowd->people.size());
  }
  if (!safety_on_.empty()) {
    SensingScratch& first = thread_scratch_.back().sensing;
    first.safety_discs.resize(n + (crowd ? crowd->people.size() : 0));
    first.safety_boxes.resize(crowd ? crowd->forklifts.size() : 0);
  }
}

void FleetSimulation::update_snapshot() {
  running_ = 0;
  const bool park = sim_.park_finished;
  bool presence_changed = false;
  for (std::size_t i = 0; i < agents_.size(); ++i) {
    const bool ended = (status_[i] & kEnded) != 0;
    moving_[i] = !ended;
    const std::uint8_t present = !ended || park || (status_[i] & kCollided) != 0;
    presence_changed = presence_changed || present != present_[i];
    present_[i] = present;
    running_ += moving_[i];
  }
  // prepare_contacts() filed the positions already; only robots that left need a rebuild.
  if (presence_changed) grid_.build(positions_, present_);
}

void FleetSimulation::step_robots(std::size_t begin, std::size_t end, std::size_t thread) {
  SensingScratch& scratch = thread_scratch_[thread].sensing;
  ThreadScratch& bodies = thread_scratch_[thread];
  for (std::size_t i = begin; i < end; ++i) {
    if (!moving_[i]) {
      moved_to_[i] = positions_[i];
      if (!moved_velocity_.empty()) moved_velocity_[i] = Vec2::Zero();
      continue;
    }
    if (robot_scratch_.empty()) {
      sense_robot(i, scratch, bodies);
      agents_[i].act(scratch);
    } else {  // sensed at the end of the last step (keep_sensing)
      const bool commanded = !commands_.empty() && commands_[i].has_value();
      agents_[i].act(robot_scratch_[i], commanded ? &*commands_[i] : nullptr);
    }
    // What the serial part needs of the robot, written while its state is in this core's cache.
    moved_to_[i] = agents_[i].pose().position;
    moved_cell_[i] = grid_.cell_index(moved_to_[i]);
    note_status(i);
    if (!moved_velocity_.empty()) note_velocity(i);
    if (status_[i] != 0) events_[thread].any = true;
  }
}

void FleetSimulation::sense_robot(std::size_t i, SensingScratch& scratch, ThreadScratch& bodies) {
  std::size_t n_others = gather_robots(i, scratch, bodies);
  std::span<Circle> others = bodies.others;
  const Vec2 p = positions_[i];
  if (crowd_) {
    if (!safety_on_.empty() && safety_on_[i])
      crowd_->safety_bodies_near(p, radius_[i] + safety_reach_[i] + max_top_step_, sim_.dt,
                                 tasks_[i].controller.safety.person_margin, scratch);
    n_others = crowd_->people_near(p, reach_[i], others, n_others);
    agents_[i].sense(scratch, others.first(n_others), crowd_->forklifts());
  } else {
    agents_[i].sense(scratch, others.first(n_others));
  }
}

std::size_t FleetSimulation::gather_robots(std::size_t i, SensingScratch& scratch,
                                           ThreadScratch& bodies) const {
  // One pass over the grid for the three lists of other robots, each in the grid's order:
  // the bodies this robot's sensors could reach, as they stood at the start of the step; the
  // robots it is told of (tell_range_); the bodies its safety layer keeps clear of.
  const Vec2 p = positions_[i];
  const double reach = reach_[i];
  const double tell = tell_range_.empty() ? 0.0 : tell_range_[i];
  const bool safety = !safety_on_.empty() && safety_on_[i];
  // Bodies beyond this gap cannot bind this step (SafetyLayer::slack's quick bound).
  const double gap_reach = safety ? safety_reach_[i] + max_top_step_ : 0.0;
  double look = std::max(reach + max_radius_, tell);
  if (safety) look = std::max(look, radius_[i] + max_radius_ + gap_reach);
  const double tell_sq = tell * tell, radius_i = radius_[i];
  const std::size_t keeps = safety;
  // Plain pointers and local counts: the stores into the lists would otherwise make the compiler
  // reload every member array for each robot visited.
  const Vec2* const position = positions_.data();
  const double* const radius = radius_.data();
  const std::size_t n = agents_.size();
  std::uint32_t* const near_bodies = bodies.near.data();
  std::uint32_t* const near_told = near_bodies + n;
  std::uint32_t* const near_discs = near_told + n;
  std::size_t n_bodies = 0, n_told = 0, n_discs = 0;
  // The candidates come in no order of distance: a branch on each one's distance would be
  // mispredicted for about one in three. Each is written into every list of indices and kept
  // where it lies within that list's reach (each within `look`; room for every robot), and
  // the lists are filled from the indices kept.
  grid_.for_each_near(p, look, [&](std::size_t j) {
    const double d2 = (position[j] - p).squaredNorm();
    const std::size_t other = j != i;
    const double r = reach + radius[j], keep = radius_i + radius[j] + gap_reach;
    const auto index = static_cast<std::uint32_t>(j);
    near_bodies[n_bodies] = index;
    n_bodies += other & static_cast<std::size_t>(d2 < r * r);
    near_told[n_told] = index;
    n_told += other & static_cast<std::size_t>(d2 < tell_sq);
    near_discs[n_discs] = index;
    n_discs += other & keeps & static_cast<std::size_t>(d2 < keep * keep);
  });
  Circle* const others = bodies.others.data();
  for (std::size_t k = 0; k < n_bodies; ++k) {
    const std::uint32_t j = near_bodies[k];
    others[k] = {position[j], radius[j]};
  }
  NearbyRobot* const told = scratch.robots.data();
  for (std::size_t k = 0; k < n_told; ++k) {
    const std::uint32_t j = near_told[k];
    told[k] = {position[j], velocities_[j], radius[j], moving_[j] != 0};
  }
  SafetyDisc* const discs = scratch.safety_discs.data();
  for (std::size_t k = 0; k < n_discs; ++k) {
    const std::uint32_t j = near_discs[k];
    const bool runs = moving_[j] != 0;
    SafetyDisc& d = discs[k];
    d.position = position[j];
    d.radius = radius[j];
    d.reciprocal = runs && safety_on_[j];
    d.approach = runs && !safety_on_[j] ? top_step_[j] : 0.0;
    d.extra_margin = 0.0;
    d.who = {BodyRef::Kind::Robot, j};
  }
  scratch.robot_count = n_told;
  scratch.safety_disc_count = n_discs;
  scratch.safety_box_count = 0;
  return n_bodies;
}

void FleetSimulation::keep_sensing() {
  if (!robot_scratch_.empty()) return;
  const SensingScratch& first = thread_scratch_.front().sensing;
  robot_scratch_.reserve(agents_.size());
  for (std::size_t i = 0; i < agents_.size(); ++i) {
    SensingScratch& s = robot_scratch_.emplace_back(tasks_[i].robot.sensors.size());
    s.robots.resize(first.robots.size());
    s.safety_discs.resize(first.safety_discs.size());
    s.safety_boxes.resize(first.safety_boxes.size());
    if (moving_[i]) sense_robot(i, s, thread_scratch_.front());
  }
}

bool FleetSimulation::step(std::span<const std::optional<Command>> commands) {
  if (!commands.empty() && commands.size() != agents_.size())
    throw std::invalid_argument("step: one command (or none) per robot");
  keep_sensing();
  if (running_ == 0) return false;
  ran_.assign(moving_.begin(), moving_.end());
  commands_ = commands;
  try {
    step_robots(0, agents_.size(), 0);
  } catch (...) {
    commands_ = {};
    throw;
  }
  commands_ = {};
  after_step();
  for (std::size_t i = 0; i < agents_.size(); ++i)
    if (ran_[i]) sense_robot(i, robot_scratch_[i], thread_scratch_.front());
  return running_ > 0;
}

void FleetSimulation::note_status(std::size_t i) {
  const RobotAgent& a = agents_[i];
  status_[i] = static_cast<std::uint8_t>((a.finished() ? kEnded : 0) |
                                         (a.result().collided ? kCollided : 0));
}

void FleetSimulation::note_velocity(std::size_t i) {
  moved_velocity_[i] = (status_[i] & kEnded) != 0 ? Vec2::Zero() : agents_[i].velocity();
}

void FleetSimulation::prepare_contacts() {
  ++steps_;
  positions_.swap(moved_to_);  // step_robots wrote every robot's
  velocities_.swap(moved_velocity_);
  grid_.refile(moved_cell_, present_);  // the cells taken on the robots' threads
  if (crowd_) crowd_->step(static_cast<double>(steps_ - 1) * sim_.dt, sim_.dt, bodies());
}

double FleetSimulation::nearest_gap(std::size_t i) const {
  const Vec2 p = positions_[i];
  // Gaps beyond a grid cell (about one sensing reach) are not looked for: they could lower
  // min_clearance only while the robot is far from everything else, too.
  const double look = std::min(std::max(agents_[i].result().min_clearance, 0.0), grid_.cell_size());
  double nearest = std::numeric_limits<double>::infinity();
  grid_.for_each_near(p, radius_[i] + max_radius_ + look, [&](std::size_t j) {
    if (j != i) nearest = std::min(nearest, (positions_[j] - p).norm() - radius_[i] - radius_[j]);
  });
  return nearest;
}

void FleetSimulation::measure_gaps(std::size_t begin, std::size_t end, std::size_t thread) {
  // A gap that is not a contact only lowers the robot's own min_clearance: taken here, on the
  // robot's thread, rather than in the serial part (a touching pair is left to apply_gaps).
  for (std::size_t i = begin; i < end; ++i) {
    if (!moving_[i]) continue;
    const double gap = nearest_gap(i);
    gap_[i] = gap;
    if (gap > 0.0 && gap < std::numeric_limits<double>::infinity()) agents_[i].note_robot_gap(gap);
    if (!(gap > 0.0)) events_[thread].any = true;
  }
}

bool FleetSimulation::take_events() {
  bool any = false;
  for (StepEvents& e : events_) {
    any = any || e.any;
    e.any = false;
  }
  return any;
}

void FleetSimulation::apply_gaps() {
  // Nothing ended, collided or touched: the loops below would find nothing, and the snapshot
  // stays as it is (with people and forklifts, their contacts are checked every step).
  if (!take_events() && !crowd_) return;
  // World collisions of this step (robot contacts are not applied yet).
  for (std::size_t i = 0; i < agents_.size(); ++i)
    if (moving_[i] && (status_[i] & kCollided) != 0)
      collisions_.push_back({agents_[i].recorded_time(agents_[i].result().steps),
                             static_cast<int>(i), -1, ContactKind::World});
  // Contacts between bodies at the positions after the move. Robots that stopped or left this
  // step still count: they were there while the others moved.
  for (std::size_t i = 0; i < agents_.size(); ++i) {
    if (!moving_[i]) continue;
    const double gap = gap_[i];
    if (gap > 0.0) continue;  // noted by measure_gaps
    RobotAgent& a = agents_[i];
    // Touching (rare): each touching pair is logged once, by its lower index unless that robot
    // was not moving.
    const Vec2 p = positions_[i];
    grid_.for_each_near(p, radius_[i] + max_radius_, [&](std::size_t j) {
      if (j == i || (moving_[j] && j < i)) return;
      if ((positions_[j] - p).norm() - radius_[i] - radius_[j] <= 0.0)
        collisions_.push_back({a.recorded_time(a.result().steps), static_cast<int>(i),
                               static_cast<int>(j), ContactKind::Robot});
    });
    a.collide_with_robot(gap);
    note_status(i);
  }
  if (crowd_) apply_crowd_contacts();
  update_snapshot();
}

void FleetSimulation::apply_crowd_contacts() {
  crowd_contacts_.clear();
  crowd_->check(sim_.dt, bodies(), crowd_contacts_);
  for (std::size_t i = 0; i < agents_.size(); ++i) {
    const double gap = crowd_->nearest_gap(i);
    if (moving_[i] && gap < std::numeric_limits<double>::infinity()) agents_[i].note_robot_gap(gap);
  }
  // A running robot that touched a person or a forklift ends its run as a collision (one that
  // had stopped, or ended this step otherwise, is counted in the crowd's metrics only).
  for (const CrowdContact& c : crowd_contacts_) {
    RobotAgent& a = agents_[c.robot];
    if (!moving_[c.robot] || a.finished()) continue;
    collisions_.push_back({a.time(), static_cast<int>(c.robot), static_cast<int>(c.other),
                           c.forklift ? ContactKind::Forklift : ContactKind::Person});
    a.collide_with_robot(c.gap);
    note_status(c.robot);
  }
}

void FleetSimulation::after_step() {
  prepare_contacts();
  measure_gaps(0, agents_.size(), 0);
  apply_gaps();
}

bool FleetSimulation::step() {
  if (!robot_scratch_.empty()) return step({});
  if (running_ == 0) return false;
  step_robots(0, agents_.size(), 0);
  after_step();
  return running_ > 0;
}

void FleetSimulation::run(int threads) {
  run_steps(std::numeric_limits<long long>::max(), threads);
}

long long FleetSimulation::robot_steps() const {
  long long n = 0;
  for (const RobotAgent& a : agents_) n += a.result().steps;
  return n;
}

std::size_t FleetSimulation::threads_for(int requested) const {
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t wanted = requested > 0 ? static_cast<std::size_t>(requested) : hw;
  // A step must hold enough work to pay for two barriers (a few microseconds each).
  return std::min(wanted, std::max<std::size_t>(1, work_per_step_ / kRaysPerThread));
}

long long FleetSimulation::run_steps(long long max_steps, int threads) {
  const long long first = steps_;
  // Kept sensing is taken at the end of each step(commands), on the calling thread.
  const std::size_t n_threads = robot_scratch_.empty() ? threads_for(threads) : 1;
  if (n_threads <= 1) {
    while (steps_ - first < max_steps && step()) {
    }
    return steps_ - first;
  }
  while (thread_scratch_.size() < n_threads) {
    // Sized as the first thread's (read before emplace_back may move it).
    const ThreadScratch& first = thread_scratch_.front();
    const std::size_t sensors = first.sensing.frame.beams.size(),
                      told = first.sensing.robots.size(), robots = agents_.size(),
                      people = first.others.size() - robots;
    const std::size_t discs = first.sensing.safety_discs.size(),
                      boxes = first.sensing.safety_boxes.size();
    ThreadScratch& added = thread_scratch_.emplace_back(sensors);
    added.sensing.robots.resize(told);
    added.sensing.safety_discs.resize(discs);
    added.sensing.safety_boxes.resize(boxes);
    added.fit(robots, people);
  }
  events_.resize(std::max(events_.size(), n_threads));
  // Each thread steps its own slice of the robots, in chunks taken from the slice's counter,
  // then helps with what is left of the others' slices: robots stay on their thread's core from
  // step to step (its caches hold their state; BM_Fleet_QuickBotWarehouse/1000/2 decides this
  // against chunks from one shared counter), and a slice whose robots have finished leaves no
  // thread waiting. A robot's result does not depend on which thread steps it. Two phases per
  // step: move, then measure the gaps between bodies; the serial parts (filing positions,
  // applying contacts) run as the barrier's completion (one thread, once per phase) between them.
  const std::size_t n = agents_.size();
  const auto slice_begin = [&](std::size_t t) { return n * t / n_threads; };
  struct alignas(64) Cursor {  // one cache line each: the threads take from them at once
    std::atomic<std::size_t> next{0};
  };
  std::vector<Cursor> cursors(n_threads);
  const auto rewind = [&] {
    for (std::size_t t = 0; t < n_threads; ++t)
      cursors[t].next.store(slice_begin(t), std::memory_order_relaxed);
  };
  rewind();
  bool done = running_ == 0 || max_steps <= 0;
  bool moved = true;  // which phase the barrier is completing
  // A user's controller may throw on any thread: the first exception is kept, every thread
  // still meets the barriers until the step ends, then it is rethrown on the calling thread.
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto completion = [&]() noexcept {
    rewind();  // the barrier orders it before the next phase
    if (moved) {
      prepare_contacts();
    } else {
      apply_gaps();
      done = failure != nullptr || running_ == 0 || steps_ - first >= max_steps;
    }
    moved = !moved;
  };
  const bool spare_cores = n_threads <= std::max(1u, std::thread::hardware_concurrency());
  sim_detail::SpinBarrier sync(n_threads, completion, spare_cores ? sim_detail::kBarrierSpins : 0);
  const auto each_chunk = [&](std::size_t t, auto&& f) {
    for (std::size_t k = 0; k < n_threads; ++k) {
      const std::size_t u = (t + k) % n_threads;
      const std::size_t end = slice_begin(u + 1);
      for (;;) {
        const std::size_t begin =
            cursors[u].next.fetch_add(kRobotsPerChunk, std::memory_order_relaxed);
        if (begin >= end) break;
        f(begin, std::min(end, begin + kRobotsPerChunk));
      }
    }
  };
  auto work = [&](std::size_t t) {
    while (!done) {
      each_chunk(t, [&](std::size_t begin, std::size_t end) {
        try {
          step_robots(begin, end, t);
        } catch (...) {
          const std::lock_guard lock(failure_mutex);
          if (!failure) failure = std::current_exception();
        }
      });
      sync.arrive_and_wait();
      each_chunk(t, [&](std::size_t begin, std::size_t end) { measure_gaps(begin, end, t); });
      sync.arrive_and_wait();
    }
  };
  {
    std::vector<std::jthread> workers;
    for (std::size_t t = 1; t < n_threads; ++t) workers.emplace_back(work, t);
    work(0);
  }
  if (failure) std::rethrow_exception(failure);
  return steps_ - first;
}

FleetResult FleetSimulation::result() const {
  std::vector<RunResult> runs;
  runs.reserve(agents_.size());
  for (const RobotAgent& a : agents_) runs.push_back(a.result());
  return make_result(std::move(runs));
}

FleetResult FleetSimulation::take_result() {
  std::vector<RunResult> runs;
  runs.reserve(agents_.size());
  for (RobotAgent& a : agents_) runs.push_back(std::move(a.result()));
  return make_result(std::move(runs));
}

std::string FleetSimulation::body_name(const BodyRef& who, const CrowdResult& crowd) const {
  switch (who.kind) {
    case BodyRef::Kind::Robot:
      return tasks_[who.index].name;
    case BodyRef::Kind::Person:
      return crowd.people[who.index].name;
    case BodyRef::Kind::Forklift:
      return crowd.forklifts[who.index].name;
    case BodyRef::Kind::None:
      break;
  }
  return {};
}

FleetResult FleetSimulation::make_result(std::vector<RunResult> runs) const {
  FleetResult f;
  f.scenario = name_;
  f.collisions = collisions_;
  f.steps = steps_;
  if (crowd_) f.crowd = crowd_->result();
  f.min_clearance = std::numeric_limits<double>::infinity();
  bool any_collision = false, any_stuck = false;
  for (std::size_t i = 0; i < agents_.size(); ++i) {
    RunResult r = std::move(runs[i]);
    r.mode_names = agents_[i].controller().mode_names();
    r.guard_names = agents_[i].controller().guard_names();
    if (r.stuck_cause == "deadlock" || r.stuck_cause == "livelock")
      r.stuck_with = body_name(agents_[i].mover(), f.crowd);
    f.reached += r.reached_goal;
    f.collided += r.collided;
    f.deliveries += r.goals_reached;
    f.delivery_count += r.goal_count;
    f.robot_steps += r.steps;
    f.sim_time = std::max(f.sim_time, r.sim_time);
    f.min_clearance = std::min(f.min_clearance, r.min_clearance);
    any_collision = any_collision || r.collided;
    any_stuck = any_stuck || r.status == RunStatus::Stuck;
    f.robots.push_back(std::move(r));
  }
  f.status = f.reached == static_cast<int>(agents_.size()) ? RunStatus::Reached
             : any_collision                               ? RunStatus::Collision
             : any_stuck                                   ? RunStatus::Stuck
                                                           : RunStatus::Timeout;
  return f;
}

}  // namespace floornav
