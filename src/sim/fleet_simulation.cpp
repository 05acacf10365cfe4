#include "floornav/sim/fleet_simulation.hpp"

#include <algorithm>
#include <atomic>
#include <barrier>
#include <cmath>
#include <limits>
#include <thread>
#include <utility>

#include "floornav/nav/navigation_controller.hpp"

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

// Rays a thread should have per step before a fleet is split across threads.
constexpr std::size_t kRaysPerThread = 2000;
// Robots a thread takes at a time: enough to make the shared counter rare, few enough that the
// threads end a step together.
constexpr std::size_t kChunk = 32;

// status_ bits.
constexpr std::uint8_t kFinished = 1;
constexpr std::uint8_t kCollided = 2;

}  // namespace

FleetSimulation::FleetSimulation(const World& world, std::span<const RobotTask> robots,
                                 const SimConfig& sim, std::string name)
    : world_(world), tasks_(robots), sim_(sim), name_(std::move(name)) {
  const std::size_t n = tasks_.size();
  ControllerMaker controllers;  // robots of one built-in kind share one automaton
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
    a.controller = controllers.make(t.controller, {t.robot, t.controller.params, t.name, i});
    a.seed = robot_seed(sim_.seed, i);
    a.name = t.name;
    a.log_transitions = n == 1 || sim_.record_trajectory;
    a.names = false;
    a.reserve_trajectory = n == 1;
    agents_.emplace_back(std::move(a));
    radius_[i] = t.robot.body_radius;
    reach_[i] = sensing_reach(t.robot);
    max_radius_ = std::max(max_radius_, radius_[i]);
    max_reach = std::max(max_reach, reach_[i]);
    max_sensors = std::max(max_sensors, t.robot.sensors.size());
    for (const RangeSensorSpec& sensor : t.robot.sensors)
      rays_per_step_ += static_cast<std::size_t>(std::max(sensor.cone_rays, 1));
  }
  scratch_.emplace_back(max_sensors);
  others_.emplace_back();
  others_.back().reserve(n);

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
  sense_grid_.reset(box, std::max(max_reach + max_radius_, 2.0 * max_radius_), n);
  positions_.resize(n);
  present_.assign(n, 0);
  moving_.assign(n, 0);
  stepped_.assign(n, 0);
  touching_.assign(n, 0);
  status_.assign(n, 0);
  gap_.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) positions_[i] = agents_[i].pose().position;
  next_positions_ = positions_;
  update_snapshot();

  // Robots that start touching each other have collided before the first step.
  after_step();
  steps_ = 0;
}

bool FleetSimulation::update_presence() {
  running_ = 0;
  const bool park = sim_.park_finished;
  bool changed = false;
  for (std::size_t i = 0; i < agents_.size(); ++i) {
    const RobotAgent& a = agents_[i];
    const std::uint8_t present = !a.finished() || park || a.result().collided;
    changed = changed || present != present_[i];
    present_[i] = present;
    running_ += !a.finished();
  }
  return changed;
}

void FleetSimulation::update_snapshot() {
  for (std::size_t i = 0; i < agents_.size(); ++i) moving_[i] = !agents_[i].finished();
  // prepare_contacts() filed the positions already; only robots that left need a rebuild.
  if (update_presence()) grid_.build(positions_, present_);
}

void FleetSimulation::step_robot(std::size_t i, const RobotNeighbourGrid& grid,
                                 std::size_t thread) {
  std::vector<Circle>& others = others_[thread];
  // The bodies this robot's sensors could reach, as they stood at the start of the step.
  others.clear();
  const Vec2 p = positions_[i];
  const double reach = reach_[i];
  grid.for_each_near(p, reach + max_radius_, [&](std::size_t j) {
    if (j == i) return;
    const double r = reach + radius_[j];
    if ((positions_[j] - p).squaredNorm() < r * r) others.push_back({positions_[j], radius_[j]});
  });
  agents_[i].step(scratch_[thread], others);
}

void FleetSimulation::step_robots(std::size_t begin, std::size_t end, std::size_t thread) {
  for (std::size_t i = begin; i < end; ++i)
    if (moving_[i]) step_robot(i, grid_, thread);
}

void FleetSimulation::prepare_contacts() {
  ++steps_;
  for (std::size_t i = 0; i < agents_.size(); ++i) positions_[i] = agents_[i].pose().position;
  grid_.build(positions_, present_);
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

void FleetSimulation::measure_gaps(std::size_t begin, std::size_t end) {
  for (std::size_t i = begin; i < end; ++i)
    if (moving_[i]) gap_[i] = nearest_gap(i);
}

void FleetSimulation::log_world_collisions() {
  // World collisions of this step (robot contacts are not applied yet).
  for (std::size_t i = 0; i < agents_.size(); ++i)
    if (moving_[i] && agents_[i].result().collided)
      collisions_.push_back({agents_[i].time(), static_cast<int>(i), -1});
}

void FleetSimulation::apply_gap(std::size_t i) {
  RobotAgent& a = agents_[i];
  const double gap = gap_[i];
  if (gap > 0.0) {
    if (gap < std::numeric_limits<double>::infinity()) a.note_robot_gap(gap);
    return;
  }
  touching_[i] = 1;  // logged by log_contacts
  a.collide_with_robot(gap);
}

void FleetSimulation::log_contacts() {
  // Contacts between bodies at the positions after the move (in grid_). Robots that stopped or
  // left this step still count: they were there while the others moved. Each touching pair is
  // logged once, by its lower index unless that robot was not moving.
  for (std::size_t i = 0; i < agents_.size(); ++i) {
    if (!touching_[i]) continue;
    touching_[i] = 0;
    const Vec2 p = positions_[i];
    const double t = agents_[i].time();
    grid_.for_each_near(p, radius_[i] + max_radius_, [&](std::size_t j) {
      if (j == i || (moving_[j] && j < i)) return;
      if ((positions_[j] - p).norm() - radius_[i] - radius_[j] <= 0.0)
        collisions_.push_back({t, static_cast<int>(i), static_cast<int>(j)});
    });
  }
}

void FleetSimulation::apply_gaps() {
  log_world_collisions();
  for (std::size_t i = 0; i < agents_.size(); ++i)
    if (moving_[i]) apply_gap(i);
  log_contacts();
  update_snapshot();
}

void FleetSimulation::after_step() {
  prepare_contacts();
  measure_gaps(0, agents_.size());
  apply_gaps();
}

bool FleetSimulation::step() {
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
  // A step must hold enough work to pay for two barriers (a few microseconds each): about 2,000
  // rays per thread (100 QuickBots are 500 rays, a step of ~50 us: one thread is faster).
  return std::min(wanted, std::max<std::size_t>(1, rays_per_step_ / kRaysPerThread));
}

void FleetSimulation::advance(std::size_t i, bool contacts_pending,
                              const RobotNeighbourGrid& sense_grid, std::size_t thread) {
  RobotAgent& a = agents_[i];
  if (contacts_pending && moving_[i]) {
    gap_[i] = nearest_gap(i);
    apply_gap(i);
  }
  const bool running = !a.finished();
  stepped_[i] = running;
  if (running) step_robot(i, sense_grid, thread);
  // What the serial part of the step needs, copied while the robot's state is in this core's
  // cache: the serial part then reads contiguous arrays, not a thousand robots' states.
  next_positions_[i] = a.pose().position;
  status_[i] = static_cast<std::uint8_t>((a.finished() ? kFinished : 0) |
                                         (a.result().collided ? kCollided : 0));
}

bool FleetSimulation::end_phase(bool& contacts_pending, const RobotNeighbourGrid*& sense_grid) {
  const std::size_t n = agents_.size();
  if (contacts_pending) log_contacts();
  std::swap(moving_, stepped_);  // moving_: the robots that moved in this step
  bool any = false;
  for (std::size_t i = 0; i < n; ++i) any = any || moving_[i];
  contacts_pending = any;
  if (!any) return false;  // every running robot ended in a contact: no step was taken
  // World collisions of this step (robot contacts are measured in the next phase).
  for (std::size_t i = 0; i < n; ++i)
    if (moving_[i] && (status_[i] & kCollided))
      collisions_.push_back({agents_[i].time(), static_cast<int>(i), -1});
  ++steps_;
  std::swap(positions_, next_positions_);
  grid_.build(positions_, present_);  // the robots present during the step, for its contacts
  // Who is present and running now (contacts change neither: a robot they end was running, and
  // collided robots stay).
  running_ = 0;
  bool changed = false;
  const bool park = sim_.park_finished;
  for (std::size_t i = 0; i < n; ++i) {
    const bool finished = status_[i] & kFinished;
    const std::uint8_t present = !finished || park || (status_[i] & kCollided);
    changed = changed || present != present_[i];
    present_[i] = present;
    running_ += !finished;
  }
  sense_grid = &grid_;
  if (changed) {
    sense_grid_.build(positions_, present_);
    sense_grid = &sense_grid_;
  }
  return running_ > 0;
}

void FleetSimulation::settle(bool contacts_pending, const RobotNeighbourGrid* sense_grid) {
  // The gaps after the last step, as step() measures them (grid_ holds the robots present
  // during it); then grid_ becomes the grid of the robots present now, as step() leaves it.
  const std::size_t n = agents_.size();
  if (contacts_pending) {
    measure_gaps(0, n);
    for (std::size_t i = 0; i < n; ++i)
      if (moving_[i]) apply_gap(i);
    log_contacts();
  }
  if (sense_grid != &grid_) std::swap(grid_, sense_grid_);
  update_snapshot();
}

long long FleetSimulation::run_steps(long long max_steps, int threads) {
  const long long first = steps_;
  const std::size_t n_threads = threads_for(threads);
  while (scratch_.size() < n_threads) {
    scratch_.emplace_back(scratch_.front().beams.size());
    others_.emplace_back();
    others_.back().reserve(agents_.size());
  }
  // A step as one pass over the robots: for each robot that moved in the step before, first its
  // gap to the other bodies at the positions after that step is measured and applied (a contact
  // ends its run), then the robot steps if it still runs. Robot i reads only what the serial
  // part between passes filed (positions, grids) and writes only its own state. The serial part
  // (end_phase) logs contacts and world collisions in robot order, files the positions and counts
  // the step; settle() measures the last step's gaps. Every result is what step() gives.
  const std::size_t n = agents_.size();
  bool contacts_pending = false;
  const RobotNeighbourGrid* sense_grid = &grid_;  // where the robots sense each other
  bool done = running_ == 0 || max_steps <= 0;
  if (n_threads <= 1) {
    while (!done) {
      for (std::size_t i = 0; i < n; ++i) advance(i, contacts_pending, *sense_grid, 0);
      done = !end_phase(contacts_pending, sense_grid) || steps_ - first >= max_steps;
    }
    settle(contacts_pending, sense_grid);
    return steps_ - first;
  }
  // On threads: one barrier per step, whose completion (one thread) is the serial part. Between
  // barriers the threads take chunks of robots from a shared counter (a robot's result does not
  // depend on which thread steps it), so they end a step together.
  std::atomic<std::size_t> next{0};
  auto completion = [&]() noexcept {
    next.store(0, std::memory_order_relaxed);
    done = !end_phase(contacts_pending, sense_grid) || steps_ - first >= max_steps;
  };
  std::barrier sync(static_cast<std::ptrdiff_t>(n_threads), completion);
  auto work = [&](std::size_t t) {
    while (!done) {
      for (std::size_t begin; (begin = next.fetch_add(kChunk, std::memory_order_relaxed)) < n;) {
        const std::size_t end = std::min(n, begin + kChunk);
        for (std::size_t i = begin; i < end; ++i) advance(i, contacts_pending, *sense_grid, t);
      }
      sync.arrive_and_wait();
    }
  };
  {
    std::vector<std::jthread> workers;
    for (std::size_t t = 1; t < n_threads; ++t) workers.emplace_back(work, t);
    work(0);
  }
  settle(contacts_pending, sense_grid);
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

FleetResult FleetSimulation::make_result(std::vector<RunResult> runs) const {
  FleetResult f;
  f.scenario = name_;
  f.collisions = collisions_;
  f.steps = steps_;
  f.min_clearance = std::numeric_limits<double>::infinity();
  bool any_collision = false, any_stuck = false;
  for (std::size_t i = 0; i < agents_.size(); ++i) {
    RunResult r = std::move(runs[i]);
    r.mode_names = agents_[i].controller().mode_names();
    r.guard_names = agents_[i].controller().guard_names();
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
