#pragma once
/// @file
/// Many independent runs stepped together: copies of one robot's task (or of several), each alone
/// in its world, each with its own sensor-noise seed, stepped on a pool of threads. What a
/// reinforcement-learning vector environment needs from the simulator: one call steps every copy,
/// each by its own command (or by its controller), restarts the ones that ended, and lets the
/// caller read every copy's observation in the same parallel pass.
///
/// A copy whose scenario has people or forklifts runs as a fleet of one (FleetSimulation, with its
/// own crowd), so that it senses and meets them as `floornav run` does; the others are a lone
/// RobotAgent each. Each reset may draw the copy's start pose and goal anew (EpisodeDraw), from a
/// stream of its seed.
///
/// Step of one copy: act on the observation sensed at the end of the previous step (or at reset),
/// then sense the next observation at the new pose, exactly as Simulation::step + observe do:
/// the sensors are cast once per step, so a copy's run equals a Simulation's with the same seed,
/// bit for bit, whatever the number of threads. A copy that has ended is sensed once more where
/// it stopped, so that its final observation describes its final pose.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "floornav/nav/controller.hpp"
#include "floornav/nav/navigation_controller.hpp"
#include "floornav/sim/crowd.hpp"
#include "floornav/sim/episode_draw.hpp"
#include "floornav/sim/fleet_simulation.hpp"
#include "floornav/sim/robot_agent.hpp"
#include "floornav/sim/robot_task.hpp"
#include "floornav/sim/sim_config.hpp"
#include "floornav/world/world.hpp"

namespace floornav {

/// A fixed set of threads (the caller's among them) that run one parallel loop at a time.
/// Thread t starts on its own share of the indices, the t-th of `size()` equal ranges, so that a
/// loop run every step hands index i to the same thread (its data stays in that core's cache);
/// a thread that finishes its share early takes chunks from the end of the fullest other share.
class WorkerPool {
 public:
  /// `threads` in all, the calling thread included (0: all cores).
  explicit WorkerPool(int threads = 0);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  std::size_t size() const { return workers_.size() + 1; }

  /// Calls body(begin, end) over [0, n) in chunks of at most `chunk`, on every thread, and
  /// returns once all are done. An exception thrown by a body stops the loop (chunks not yet
  /// started are skipped) and is rethrown here, on the caller's thread.
  void run(std::size_t n, std::size_t chunk,
           const std::function<void(std::size_t, std::size_t)>& body);

 private:
  /// The indices of one thread's share not yet taken: [next, end).
  struct Share {
    std::size_t next{0};
    std::size_t end{0};
  };

  void work_loop(std::size_t self);
  void take_chunks(std::size_t self);
  /// The next chunk for thread `self` (under mutex_): from the front of its own share, else from
  /// the back of the share with the most left; false when every share is taken.
  bool next_chunk(std::size_t self, std::size_t& begin, std::size_t& end);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable done_;
  std::atomic<std::uint64_t> generation_{0};  ///< one per run() (written under mutex_)
  std::atomic<std::size_t> busy_{0};  ///< workers still inside the current run (under mutex_)
  std::atomic<bool> stopping_{false};
  /// How long a waiting thread spins before it sleeps (the fleet barrier's adaptive budget).
  int max_spins_{0};
  std::atomic<int> spins_{0};
  // The current loop.
  const std::function<void(std::size_t, std::size_t)>* body_{nullptr};
  std::size_t chunk_{1};
  std::vector<Share> shares_;  ///< one per thread, the caller's first (under mutex_)
  std::exception_ptr error_;
};

/// One copy's run: its world, task and settings (all must outlive the VecSimulation).
struct VecCopy {
  const World* world{nullptr};
  const RobotTask* task{nullptr};
  /// The seed is the copy's own (reset); nothing is recorded, and RunResult::path_irregularity
  /// is not summed (NaN): a learner reads no run's result.
  const SimConfig* sim{nullptr};
  std::string name;                 ///< RunResult::scenario
  const CrowdSpec* crowd{nullptr};  ///< people and forklifts (none or empty: the robot alone)
};

/// Where copy i's episodes come from when each episode has a world of its own (a generated floor
/// per episode): called as source(i, seed) by reset(i, seed), after copy i's previous episode is
/// gone and before anything is drawn. The copy it returns replaces copy i's: the same robot and
/// controller parameters (the models the copies share), its world, task, settings and crowd
/// valid until the next call for i (the caller owns them). Called on the stepping threads, for
/// different copies at once.
using VecCopySource = std::function<VecCopy(std::size_t i, std::uint64_t seed)>;

class VecSimulation {
 public:
  /// Every copy must have the same number of sensors (observations of one shape). The copies
  /// start unset: reset() each before stepping. `threads` in all (0: all cores). `draw`: what
  /// each reset draws anew.
  VecSimulation(std::vector<VecCopy> copies, int threads = 0, EpisodeDraw draw = {});

  std::size_t size() const { return copies_.size(); }
  /// Range readings per copy (every sensor's beam).
  std::size_t beam_count() const { return beams_; }
  std::size_t thread_count() const { return pool_.size(); }

  /// Starts copy `i` afresh with sensor-noise seed `seed` (its start and goal drawn from
  /// episode_draw_seed(seed) when the simulation draws them), and senses its first observation.
  /// Throws DrawError when no free start or goal could be drawn.
  void reset(std::size_t i, std::uint64_t seed);
  /// reset(which[k], seeds[k]) for every k, in parallel; then after(which[k]) on the thread that
  /// reset it.
  void reset(std::span<const std::size_t> which, std::span<const std::uint64_t> seeds,
             const std::function<void(std::size_t)>& after = {});

  /// One step of every copy that is running: commands[i] drives copy i through the pipeline and
  /// saturation of the built-in controllers (RobotAgent::act); an empty span lets every copy's
  /// controller drive. Then each copy senses its next observation, and after(i) runs on the
  /// thread that stepped it (for every copy, running or not). Throws what a step throws (a
  /// command that is not finite: std::domain_error; a user controller's exception), after every
  /// thread has stopped.
  void step(std::span<const Command> commands, const std::function<void(std::size_t)>& after = {});

  /// What copy i's controller sees now (valid until the copy is stepped or reset). Without kept
  /// frames (keep_frames), a running copy's beams and ranges are shown inside after(i) alone.
  Observation observe(std::size_t i) const;
  /// Whether copies keep their beams and ranges once after(i) has returned (default: they do).
  /// keep_frames(false): a copy whose controller reads neither (controller_reads_frames) senses
  /// them into a frame of its stepping thread's, observed inside after(i); it keeps only its
  /// returns, and a copy that has ended keeps its last frame. A caller that reads each
  /// observation in after(i) (a learner's arrays) then steps a thousand copies without their
  /// frames passing through the caches. From the next sensing on.
  void keep_frames(bool keep) { keep_frames_ = keep; }
  const RobotAgent& agent(std::size_t i) const {
    return fleets_[i] ? fleets_[i]->robot(0) : *agents_[i];
  }
  /// The sensing behind observe(i): returns and points, and beams and ranges in its frame
  /// (empty without kept frames).
  const SensingScratch& sensing(std::size_t i) const {
    return fleets_[i] ? fleets_[i]->sensing(0) : scratch_[i];
  }
  /// Copy i's task in its current episode: the scenario's, with the start and goal drawn.
  const RobotTask& task(std::size_t i) const { return tasks_[i]; }
  const VecCopy& copy(std::size_t i) const { return copies_[i]; }
  /// Copy i's people and forklifts now (nullptr: none).
  const Crowd* crowd(std::size_t i) const { return fleets_[i] ? fleets_[i]->crowd() : nullptr; }
  const EpisodeDraw& draw() const { return draw_; }
  /// From now on every reset takes copy i from `source` (none: the copy as made keeps its world).
  void set_copy_source(VecCopySource source) { source_ = std::move(source); }
  /// The threads that step the copies, for other per-copy work (rendering frames).
  WorkerPool& pool() { return pool_; }

 private:
  /// Copy i from source_ (its robot checked against the shared model) with its own settings.
  void replace_copy(std::size_t i, VecCopy c);
  /// reset(i, seed) up to the first sensing.
  void restart(std::size_t i, std::uint64_t seed);
  /// Copy i (not in a fleet) senses its next observation: into its own frame, or, without kept
  /// frames, into `frame` (its thread's), lent to it until report(i) returns.
  void sense_copy(std::size_t i, SensorFrame& frame);
  /// after(i), then the frame lent to copy i goes back (observe(i) shows it no more).
  void report(std::size_t i, const std::function<void(std::size_t)>& after);

  std::vector<VecCopy> copies_;
  EpisodeDraw draw_;
  VecCopySource source_;
  std::vector<RobotTask> tasks_;  ///< per copy: the scenario's task, start and goal drawn
  std::vector<SimConfig> sims_;   ///< per copy: its seed, nothing recorded
  std::vector<std::optional<RobotAgent>> agents_;
  /// Copies among people or forklifts: a fleet of one each (the others: null).
  std::vector<std::unique_ptr<FleetSimulation>> fleets_;
  std::vector<std::optional<Command>> fleet_command_;  ///< per copy, for a fleet's step
  /// Per copy: where the crowd starts (drawn starts and goals keep clear of it).
  std::vector<std::vector<Circle>> keep_discs_;
  std::vector<std::vector<OrientedBox>> keep_boxes_;
  std::vector<RobotModel> models_;  ///< per copy, shared by copies of one kind
  std::vector<SensingScratch> scratch_;
  /// Per copy: its controller reads beams and ranges (controller_reads_frames), so it keeps them.
  std::vector<std::uint8_t> reads_frames_;
  /// Per copy: the frame it sensed into while after(i) runs, when not its own (else null).
  std::vector<const SensorFrame*> lent_;
  bool keep_frames_{true};
  std::size_t beams_{0};
  std::mutex maker_mutex_;  ///< ControllerMaker is not thread-safe; resets may run in parallel
  ControllerMaker maker_;
  WorkerPool pool_;
};

}  // namespace floornav
