#include "floornav/sim/vec_simulation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "floornav/nav/navigation_controller.hpp"
#include "floornav/sim/robot_models.hpp"
#include "spin_barrier.hpp"

namespace floornav {

// --- WorkerPool ------------------------------------------------------------------------------

WorkerPool::WorkerPool(int threads) {
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t n = threads > 0 ? static_cast<std::size_t>(threads) : hw;
  // More threads than cores: a spinning thread would hold up the one it waits for.
  max_spins_ = n <= hw ? sim_detail::kBarrierSpins : 0;
  spins_ = max_spins_;
  shares_.resize(n);
  for (std::size_t t = 1; t < n; ++t) workers_.emplace_back([this, t] { work_loop(t); });
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : workers_) t.join();
}

bool WorkerPool::next_chunk(std::size_t self, std::size_t& begin, std::size_t& end) {
  Share& own = shares_[self];
  if (own.next < own.end) {
    begin = own.next;
    end = std::min(own.end, begin + chunk_);
    own.next = end;
    return true;
  }
  // Stealing from the back leaves the other thread the front of its share, which it is taking.
  Share* fullest = nullptr;
  for (Share& s : shares_)
    if (s.next < s.end && (!fullest || s.end - s.next > fullest->end - fullest->next)) fullest = &s;
  if (!fullest) return false;
  end = fullest->end;
  begin = std::max(fullest->next, end - std::min(end, chunk_));
  fullest->end = begin;
  return true;
}

void WorkerPool::take_chunks(std::size_t self) {
  while (true) {
    std::size_t begin, end;
    {
      std::lock_guard lock(mutex_);
      if (error_ || !next_chunk(self, begin, end)) return;
    }
    try {
      (*body_)(begin, end);
    } catch (...) {
      std::lock_guard lock(mutex_);
      if (!error_) error_ = std::current_exception();
      return;
    }
  }
}

void WorkerPool::work_loop(std::size_t self) {
  std::uint64_t seen = 0;
  while (true) {
    // A learner's steps come back to back, and a thread woken from the kernel in a virtual
    // machine comes back tens of microseconds late: spin a while first.
    sim_detail::spin_until(spins_, max_spins_, [&] {
      return generation_.load(std::memory_order_acquire) != seen ||
             stopping_.load(std::memory_order_acquire);
    });
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
      if (stopping_) return;
      seen = generation_;
    }
    take_chunks(self);
    {
      std::lock_guard lock(mutex_);
      --busy_;
    }
    done_.notify_one();
  }
}

void WorkerPool::run(std::size_t n, std::size_t chunk,
                     const std::function<void(std::size_t, std::size_t)>& body) {
  if (n == 0) return;
  chunk = std::max<std::size_t>(chunk, 1);
  if (workers_.empty() || n <= chunk) {  // nothing to share: no wake-up to pay for
    body(0, n);
    return;
  }
  {
    std::lock_guard lock(mutex_);
    body_ = &body;
    chunk_ = chunk;
    const std::size_t threads = shares_.size();
    for (std::size_t t = 0; t < threads; ++t) shares_[t] = {n * t / threads, n * (t + 1) / threads};
    error_ = nullptr;
    busy_ = workers_.size();
    ++generation_;
  }
  wake_.notify_all();
  take_chunks(0);
  sim_detail::spin_until(spins_, max_spins_,
                         [&] { return busy_.load(std::memory_order_acquire) == 0; });
  std::exception_ptr error;
  {
    std::unique_lock lock(mutex_);
    done_.wait(lock, [&] { return busy_ == 0; });
    body_ = nullptr;
    error = std::exchange(error_, nullptr);
  }
  if (error) std::rethrow_exception(error);
}

// --- VecSimulation ---------------------------------------------------------------------------

namespace {

// The frame of this thread that the copies without kept frames sense into (VecSimulation::
// keep_frames): one per thread, where it stays in the core's caches.
thread_local SensorFrame thread_frame;

// Chunks small enough to balance copies that cost differently, large enough that taking one
// (a lock) is rare next to stepping it.
std::size_t chunk_for(std::size_t n, std::size_t threads) {
  return std::max<std::size_t>(1, n / (8 * threads));
}
}  // namespace

VecSimulation::VecSimulation(std::vector<VecCopy> copies, int threads, EpisodeDraw draw)
    : copies_(std::move(copies)), draw_(std::move(draw)), pool_(threads) {
  if (copies_.empty()) throw std::invalid_argument("a vector simulation needs at least one copy");
  beams_ = copies_.front().task->robot.sensors.size();
  sims_.reserve(copies_.size());
  models_.reserve(copies_.size());
  tasks_.reserve(copies_.size());
  RobotModels models;  // copies of one kind share one robot model
  for (const VecCopy& c : copies_) {
    if (!c.world || !c.task || !c.sim)
      throw std::invalid_argument("a copy needs a world, a task and sim settings");
    if (c.task->robot.sensors.size() != beams_)
      throw std::invalid_argument("every copy must have as many sensors as the first (" +
                                  std::to_string(beams_) + "), '" + c.name + "' has " +
                                  std::to_string(c.task->robot.sensors.size()));
    SimConfig s = *c.sim;
    s.record_trajectory = false;  // a learner keeps what it needs; a run here is not written out
    s.path_irregularity = false;
    sims_.push_back(s);
    models_.push_back(models.find(*c.task));
    tasks_.push_back(*c.task);
  }
  agents_.resize(copies_.size());
  fleets_.resize(copies_.size());
  fleet_command_.resize(copies_.size());
  keep_discs_.resize(copies_.size());
  keep_boxes_.resize(copies_.size());
  for (std::size_t i = 0; i < copies_.size(); ++i)
    if (copies_[i].crowd && !copies_[i].crowd->empty())
      crowd_starts(*copies_[i].crowd, keep_discs_[i], keep_boxes_[i]);
  scratch_.assign(copies_.size(), SensingScratch(beams_, /*with_frame=*/false));
  reads_frames_.resize(copies_.size());
  lent_.assign(copies_.size(), nullptr);
  for (std::size_t i = 0; i < copies_.size(); ++i)
    reads_frames_[i] = controller_reads_frames(tasks_[i].controller);
}

Observation VecSimulation::observe(std::size_t i) const {
  if (fleets_[i]) return fleets_[i]->observe(0);
  const SensingScratch& s = scratch_[i];
  return agents_[i]->observe(s, lent_[i] ? *lent_[i] : s.frame);
}

void VecSimulation::sense_copy(std::size_t i, SensorFrame& frame) {
  RobotAgent& a = *agents_[i];
  SensingScratch& s = scratch_[i];
  // A copy that has ended is observed at every step until its reset: it keeps its last frame.
  if (keep_frames_ || reads_frames_[i] || a.finished()) {
    a.sense(s);
    return;
  }
  s.frame.fit(0);  // the frame it last kept is not this sensing's
  lent_[i] = &frame;
  a.sense(s, frame);
}

void VecSimulation::report(std::size_t i, const std::function<void(std::size_t)>& after) {
  // The frame goes back even when after(i) throws: the thread senses another copy into it next.
  struct Release {
    const SensorFrame*& lent;
    ~Release() { lent = nullptr; }
  } release{lent_[i]};
  if (after) after(i);
}

void VecSimulation::replace_copy(std::size_t i, VecCopy c) {
  if (!c.world || !c.task || !c.sim)
    throw std::invalid_argument("a copy needs a world, a task and sim settings");
  const RobotModel& m = models_[i];  // null: the copy's agents keep models of their own
  if ((m.robot && !(c.task->robot == *m.robot)) ||
      (m.params && !(c.task->controller.params == *m.params)))
    throw std::invalid_argument("a copy source must keep copy " + std::to_string(i) +
                                "'s robot and controller parameters ('" + c.name + "' does not)");
  sims_[i] = *c.sim;
  sims_[i].record_trajectory = false;
  tasks_[i] = *c.task;
  reads_frames_[i] = controller_reads_frames(tasks_[i].controller);
  keep_discs_[i].clear();
  keep_boxes_[i].clear();
  if (c.crowd && !c.crowd->empty()) crowd_starts(*c.crowd, keep_discs_[i], keep_boxes_[i]);
  copies_[i] = std::move(c);
}

void VecSimulation::reset(std::size_t i, std::uint64_t seed) {
  restart(i, seed);
  if (agents_[i]) agents_[i]->sense(scratch_[i]);  // observed after this returns: kept
}

void VecSimulation::restart(std::size_t i, std::uint64_t seed) {
  // The old episode's controller goes before the new one is made (and before a copy source
  // replaces the world it ran in).
  agents_.at(i).reset();
  fleets_[i].reset();
  if (source_) replace_copy(i, source_(i, seed));
  const VecCopy& c = copies_[i];
  sims_[i].seed = seed;
  RobotTask& task = tasks_[i];
  if (draw_.any()) {
    task.start = c.task->start;
    task.goals.assign(c.task->goals.begin(), c.task->goals.end());
    Rng rng(episode_draw_seed(seed));
    draw_episode(draw_, *c.world, task, {keep_discs_[i], keep_boxes_[i]}, rng);
  }
  if (c.crowd && !c.crowd->empty()) {
    fleets_[i] = std::make_unique<FleetSimulation>(*c.world, std::span<const RobotTask>(&task, 1),
                                                   sims_[i], c.name, c.crowd);
    fleets_[i]->keep_sensing();
    return;
  }
  AgentSetup setup;
  setup.world = c.world;
  setup.task = &task;
  setup.sim = &sims_[i];
  setup.model = models_[i];
  {
    std::lock_guard lock(maker_mutex_);
    setup.controller = maker_.make(
        task.controller, {task.robot, task.controller.params, task.name, 0, c.world, seed});
  }
  setup.seed = seed;
  setup.name = c.name;
  setup.log_transitions = false;  // counts only: resets would otherwise keep growing logs
  setup.names = false;
  setup.reserve_trajectory = false;
  agents_[i].emplace(std::move(setup));
}

void VecSimulation::reset(std::span<const std::size_t> which, std::span<const std::uint64_t> seeds,
                          const std::function<void(std::size_t)>& after) {
  if (which.size() != seeds.size())
    throw std::invalid_argument("reset: as many seeds as copies are needed");
  pool_.run(which.size(), chunk_for(which.size(), pool_.size()),
            [&](std::size_t begin, std::size_t end) {
              SensorFrame& frame = thread_frame;  // one look-up of the thread's own per chunk
              for (std::size_t k = begin; k < end; ++k) {
                const std::size_t i = which[k];
                restart(i, seeds[k]);
                if (agents_[i]) sense_copy(i, frame);
                report(i, after);
              }
            });
}

void VecSimulation::step(std::span<const Command> commands,
                         const std::function<void(std::size_t)>& after) {
  if (!commands.empty() && commands.size() != copies_.size())
    throw std::invalid_argument("step: one command per copy, or none");
  for (std::size_t i = 0; i < copies_.size(); ++i)
    if (!agents_[i] && !fleets_[i]) throw std::logic_error("step: every copy must be reset first");
  pool_.run(copies_.size(), chunk_for(copies_.size(), pool_.size()),
            [&](std::size_t begin, std::size_t end) {
              SensorFrame& frame = thread_frame;  // one look-up of the thread's own per chunk
              for (std::size_t i = begin; i < end; ++i) {
                if (FleetSimulation* fleet = fleets_[i].get()) {
                  if (!fleet->finished()) {
                    if (commands.empty()) {
                      fleet->step({});
                    } else {
                      fleet_command_[i] = commands[i];
                      fleet->step({&fleet_command_[i], 1});
                    }
                  }
                } else if (RobotAgent& a = *agents_[i]; !a.finished()) {
                  a.act(scratch_[i], commands.empty() ? nullptr : &commands[i]);
                  sense_copy(i, frame);  // the next observation; at the final pose if it ended
                }
                report(i, after);
              }
            });
}

}  // namespace floornav
