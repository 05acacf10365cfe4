// The C++ side of floornav.VecEnv: many copies of a scenario stepped together on all cores
// (sim/vec_simulation.hpp), every observation written straight into numpy arrays with a leading
// n_envs dimension (no Python object per copy), the default reward, and the automatic reset of
// copies whose run ended.

#include <fmt/format.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>

#include "bindings.hpp"
#include "floornav/core/input_error.hpp"
#include "floornav/core/rng.hpp"
#include "floornav/render/frame_raster.hpp"
#include "floornav/render/palette.hpp"
#include "floornav/scenario/factory_floor.hpp"
#include "floornav/sim/vec_simulation.hpp"
#include "status_code.hpp"

namespace floornav::python {

namespace {

/// The default reward of one step, per copy: progress * (d_before - d_after) + goal * (goals
/// reached in the step) - collision * (the step ended in a collision) - time * dt; d is the
/// distance to the goal that was current when the step began.
struct RewardParams {
  double progress{1.0};   ///< per metre of progress towards the goal
  double goal{1.0};       ///< per goal reached
  double collision{1.0};  ///< once, on a collision
  double time{0.0};       ///< per second
};

// The GIL is released while the copies step: a second Python thread stepping the same VecEnv at
// that time is refused rather than let race.
class Busy {
 public:
  explicit Busy(std::atomic<bool>& flag) : flag_(flag) {
    if (flag_.exchange(true))
      throw std::runtime_error("this VecEnv is being stepped by another thread");
  }
  ~Busy() { flag_.store(false); }
  Busy(const Busy&) = delete;
  Busy& operator=(const Busy&) = delete;

 private:
  std::atomic<bool>& flag_;
};

/// A generated floor per episode (VecEnv's randomize["floor"]): which floors an episode draws
/// from, uniformly, with a stream of its seed.
struct FloorDraw {
  std::string generator;             ///< "factory_floor"; empty: the scenario's own world
  std::vector<std::uint64_t> seeds;  ///< the floors to draw from; empty: `count` from `start`
  std::uint64_t start{0}, step{1};   ///< the range start, start + step, ... (count of them)
  std::uint64_t count{0};            ///< 0 (and no seeds): any floor, a 64-bit seed
  bool any() const { return !generator.empty(); }

  /// The floor of the episode whose sensor-noise seed is `seed`: a stream of its own (neither the
  /// noise's nor the start and goal draws').
  std::uint64_t pick(std::uint64_t seed) const {
    Rng rng(seed ^ 0x9E6C63D0676A9A99ull);
    if (!seeds.empty()) return seeds[rng.next() % seeds.size()];
    if (count > 0) return start + step * (rng.next() % count);
    return rng.next();
  }
};

template <class T>
T* data_of(py::array& a) {
  return static_cast<T*>(a.mutable_data());
}

class VecCore {
 public:
  VecCore(std::vector<ScenarioPtr> scenarios, int threads, bool copy, RewardParams reward,
          EpisodeDraw draw, FloorDraw floors)
      : scenarios_(std::move(scenarios)),
        vec_(copies_of(scenarios_), python_controller(scenarios_) ? 1 : threads, draw),
        copy_(copy),
        reward_(reward),
        floor_draw_(std::move(floors)) {
    // Each observation is copied to the arrays in after(i) (write_observation), where the
    // stepping thread's frame still holds it.
    vec_.keep_frames(false);
    const std::size_t n = scenarios_.size();
    if (floor_draw_.any()) {
      if (floor_draw_.generator != "factory_floor")
        throw py::value_error(
            fmt::format("randomize['floor'] is 'factory_floor', got '{}'", floor_draw_.generator));
      for (const ScenarioPtr& x : scenarios_)
        if (!x->generator.empty())
          throw py::value_error(fmt::format(
              "randomize['floor']: scenario '{}' is already generated floor {} of {}; give "
              "the template it was made from",
              x->scenario.name, x->floor_seed, x->generator));
      floors_.resize(n);
      floor_seeds_.assign(n, 0);
      vec_.set_copy_source(
          [this](std::size_t i, std::uint64_t seed) { return next_floor(i, seed); });
    }
    episode_.assign(n, 0);
    started_.assign(n, 0);
    distance_.assign(n, 0.0);
    goals_.assign(n, 0);
    step_goal_.assign(n, 0);
    ended_.assign(n, 0);
    beams_ = vec_.beam_count();
  }

  std::size_t size() const { return scenarios_.size(); }
  std::size_t beams() const { return beams_; }
  std::size_t threads() const { return vec_.thread_count(); }

  py::dict reset(std::optional<std::uint64_t> seed) {
    const Busy busy(busy_);
    // Gymnasium's convention: a seed starts the episodes over; without one, every copy goes on to
    // its next episode (the first reset starts from the seed the env was made with).
    if (seed) {
      base_seed_ = *seed;
      std::fill(episode_.begin(), episode_.end(), 0);
    } else {
      for (std::size_t i = 0; i < episode_.size(); ++i) episode_[i] += started_[i];
    }
    const std::size_t n = size();
    std::vector<std::size_t> which(n);
    std::vector<std::uint64_t> seeds(n);
    for (std::size_t i = 0; i < n; ++i) {
      which[i] = i;
      seeds[i] = seed_of(i);
    }
    Buffers b = buffers();
    last_ = b;
    {
      py::gil_scoped_release nogil;
      reset_copies(which, seeds, b);
    }
    std::fill(started_.begin(), started_.end(), 1);
    return b.dict();
  }

  /// One step; with `autoreset`, copies that ended are restarted and their final observations
  /// returned in info["final_obs"].
  py::tuple step(py::handle actions, bool autoreset) {
    const Busy busy(busy_);
    read_actions(actions);
    const std::size_t n = size();
    Buffers b = buffers();
    last_ = b;
    py::array_t<double> reward(static_cast<py::ssize_t>(n));
    py::array_t<double> progress(static_cast<py::ssize_t>(n));
    py::array_t<double> distance(static_cast<py::ssize_t>(n));
    py::array_t<std::int8_t> status(static_cast<py::ssize_t>(n));
    py::array_t<bool> terminated(static_cast<py::ssize_t>(n));
    py::array_t<bool> truncated(static_cast<py::ssize_t>(n));
    py::array_t<std::int32_t> goals(static_cast<py::ssize_t>(n));
    double* r = reward.mutable_data();
    double* pr = progress.mutable_data();
    double* di = distance.mutable_data();
    std::int8_t* st = status.mutable_data();
    bool* te = terminated.mutable_data();
    bool* tr = truncated.mutable_data();
    std::int32_t* go = goals.mutable_data();
    {
      py::gil_scoped_release nogil;
      vec_.step(commands_, [&](std::size_t i) {
        const RobotAgent& a = vec_.agent(i);
        const auto& goal_list = vec_.task(i).goals;
        // Progress towards the goal that was current when the step began.
        const Vec2 goal_before = goal_list[std::min(step_goal_[i], goal_list.size() - 1)];
        const double d_after = (goal_before - a.pose().position).norm();
        const int reached = a.result().goals_reached - goals_[i];
        const std::int8_t code = status_code(a);
        if (ended_[i]) {  // not stepped: nothing happened to reward
          pr[i] = 0.0;
          r[i] = 0.0;
        } else {
          pr[i] = distance_[i] - d_after;
          r[i] = reward_.progress * pr[i] + reward_.goal * reached -
                 (code == 2 ? reward_.collision : 0.0) - reward_.time * dt_of(i);
        }
        st[i] = code;
        te[i] = code == 1 || code == 2;
        tr[i] = code == 3 || code == 4;
        go[i] = a.result().goals_reached;
        write_observation(i, b);
        di[i] = distance_[i];
      });
    }
    py::dict info;
    info["status"] = status;
    info["progress"] = progress;
    info["goal_distance"] = distance;
    info["goals_reached"] = goals;
    info["default_reward"] = reward;
    py::dict obs = b.dict();
    if (autoreset) {
      py::object final_obs = restart_ended(obs, terminated, truncated);
      if (!final_obs.is_none()) {
        info["final_obs"] = final_obs;
        info["_final_obs"] = ended_mask(terminated, truncated);
      }
    }
    return py::make_tuple(obs, reward, terminated, truncated, info);
  }

  /// Restarts the copies marked in `ended` (each with its next seed), writing their first
  /// observation into `obs` in place; returns the final observations (rows of `ended`; zeros
  /// elsewhere), or None when none ended.
  py::object reset_ended(py::dict obs, const py::array_t<bool>& terminated,
                         const py::array_t<bool>& truncated) {
    const Busy busy(busy_);
    return restart_ended(obs, terminated, truncated);
  }

 private:
  py::object restart_ended(py::dict obs, const py::array_t<bool>& terminated,
                           const py::array_t<bool>& truncated) {
    const std::size_t n = size();
    if (static_cast<std::size_t>(terminated.size()) != n ||
        static_cast<std::size_t>(truncated.size()) != n)
      throw py::value_error(fmt::format("terminated and truncated need {} entries", n));
    const bool* te = terminated.data();
    const bool* tr = truncated.data();
    std::vector<std::size_t> which;
    for (std::size_t i = 0; i < n; ++i)
      if (te[i] || tr[i]) which.push_back(i);
    if (which.empty()) return py::none();
    // The arrays of the last step, whatever the caller did to the dict it was handed.
    if (!last_) throw py::value_error("no step to restart copies after");
    Buffers b = *last_;
    const py::dict arrays = b.dict();
    for (const char* key : {"t", "pose", "goal", "goal_index", "ranges", "points"})
      if (!obs.contains(key) || !obs[key].is(arrays[key]))
        throw py::value_error(
            fmt::format("obs['{}'] is not the array the last step returned", key));
    const py::module_ np = py::module_::import("numpy");
    py::dict final_obs;
    for (auto item : arrays) {
      const py::array a = py::reinterpret_borrow<py::array>(item.second);
      py::array f = np.attr("zeros_like")(a);
      const std::size_t row = static_cast<std::size_t>(a.nbytes()) / n;
      const auto* src = static_cast<const char*>(a.data());
      auto* dst = static_cast<char*>(f.mutable_data());
      for (std::size_t i : which) std::memcpy(dst + i * row, src + i * row, row);
      final_obs[item.first] = f;
    }
    std::vector<std::uint64_t> seeds;
    for (std::size_t i : which) {
      ++episode_[i];
      seeds.push_back(seed_of(i));
    }
    {
      py::gil_scoped_release nogil;
      reset_copies(which, seeds, b);
    }
    return final_obs;
  }

 public:
  py::array_t<bool> ended_mask(const py::array_t<bool>& terminated,
                               const py::array_t<bool>& truncated) const {
    py::array_t<bool> m(static_cast<py::ssize_t>(size()));
    for (std::size_t i = 0; i < size(); ++i)
      m.mutable_data()[i] = terminated.data()[i] || truncated.data()[i];
    return m;
  }

  /// Where each copy is now: status codes (0 running, 1 reached, 2 collision, 3 timeout, 4 stuck).
  py::array_t<std::int8_t> statuses() const {
    py::array_t<std::int8_t> s(static_cast<py::ssize_t>(size()));
    for (std::size_t i = 0; i < size(); ++i) s.mutable_data()[i] = status_code(vec_.agent(i));
    return s;
  }

  std::uint64_t seed_of(std::size_t i) const {
    return base_seed_ + i + static_cast<std::uint64_t>(size()) * episode_[i];
  }
  py::list seeds() const {
    py::list out;
    for (std::size_t i = 0; i < size(); ++i) out.append(seed_of(i));
    return out;
  }

 private:
  // The observation arrays (one set per step, or one set for the whole life with copy=False).
  struct Buffers {
    py::array t, pose, goal, goal_index, ranges, points;
    double *t_, *pose_, *goal_, *ranges_, *points_;
    std::int32_t* goal_index_;
    py::dict dict() const {
      py::dict d;
      d["t"] = t;
      d["pose"] = pose;
      d["goal"] = goal;
      d["goal_index"] = goal_index;
      d["ranges"] = ranges;
      d["points"] = points;
      return d;
    }
    void bind() {
      t_ = data_of<double>(t);
      pose_ = data_of<double>(pose);
      goal_ = data_of<double>(goal);
      goal_index_ = data_of<std::int32_t>(goal_index);
      ranges_ = data_of<double>(ranges);
      points_ = data_of<double>(points);
    }
  };

  Buffers buffers() {
    if (!copy_ && persistent_) return *persistent_;
    const auto n = static_cast<py::ssize_t>(size());
    const auto beams = static_cast<py::ssize_t>(beams_);
    Buffers b;
    b.t = py::array_t<double>(n);
    b.pose = py::array_t<double>({n, py::ssize_t{3}});
    b.goal = py::array_t<double>({n, py::ssize_t{2}});
    b.goal_index = py::array_t<std::int32_t>(n);
    b.ranges = py::array_t<double>({n, beams});
    b.points = py::array_t<double>({n, beams, py::ssize_t{2}});
    b.bind();
    if (!copy_) persistent_ = b;
    return b;
  }

  double dt_of(std::size_t i) const { return scenarios_[i]->scenario.sim.dt; }

  // Copy i's next episode on a floor of its own, generated from its scenario (the template) for
  // the floor this episode's seed draws. Runs on the stepping threads, one copy each.
  VecCopy next_floor(std::size_t i, std::uint64_t seed) {
    const PyScenario& base = *scenarios_[i];
    const std::uint64_t floor = floor_draw_.pick(seed);
    auto s =
        std::make_shared<const Scenario>(make_generated_floor(base.scenario, floor, base.source));
    floors_[i] = s;  // the previous floor goes (the episode on it has)
    floor_seeds_[i] = floor;
    return {s->world.get(), &s->robot(), &s->sim, s->name, &s->crowd};
  }

 public:
  /// The floor each copy is on (its generator seed; randomize["floor"] only).
  py::object floor_seeds() const {
    if (!floor_draw_.any()) return py::none();
    py::array_t<std::uint64_t> out(static_cast<py::ssize_t>(size()));
    std::copy(floor_seeds_.begin(), floor_seeds_.end(), out.mutable_data());
    return out;
  }

 private:
  // Copy i's observation into row i of the arrays, and what the next step's reward starts from.
  void write_observation(std::size_t i, Buffers& b) {
    const RobotAgent& a = vec_.agent(i);
    const Observation obs = vec_.observe(i);
    b.t_[i] = obs.t;
    b.pose_[3 * i] = obs.pose.position.x();
    b.pose_[3 * i + 1] = obs.pose.position.y();
    b.pose_[3 * i + 2] = obs.pose.theta;
    b.goal_[2 * i] = obs.goal.x();
    b.goal_[2 * i + 1] = obs.goal.y();
    b.goal_index_[i] = obs.goal_index;
    std::memcpy(b.ranges_ + i * beams_, obs.ranges.data(), beams_ * sizeof(double));
    beam_points(obs, b.points_ + 2 * i * beams_);
    distance_[i] = (obs.goal - obs.pose.position).norm();
    goals_[i] = a.result().goals_reached;
    step_goal_[i] = a.goal_index();
    ended_[i] = a.finished() ? 1 : 0;
  }

  void after_reset(std::size_t i, Buffers& b) { write_observation(i, b); }

  // vec_.reset, a draw that found no free pose raised as the InputError of the copy's scenario.
  void reset_copies(std::span<const std::size_t> which, std::span<const std::uint64_t> seeds,
                    Buffers& b) {
    try {
      vec_.reset(which, seeds, [&](std::size_t i) { after_reset(i, b); });
    } catch (const DrawError& e) {
      const std::string source = scenarios_.front()->source;
      throw InputError(source, "randomize", e.what());
    }
  }

  void read_actions(py::handle actions) {
    commands_.clear();
    if (actions.is_none()) return;  // the controllers drive
    if (!py::isinstance<py::array>(actions)) {
      const py::module_ np = py::module_::import("numpy");
      py::object a = np.attr("asarray")(actions);
      return read_array(py::reinterpret_borrow<py::array>(a));
    }
    read_array(py::reinterpret_borrow<py::array>(actions));
  }

  void read_array(const py::array& a) {
    const std::size_t n = size();
    if (a.dtype().kind() != 'f')
      throw py::value_error(
          fmt::format("actions must be a float array of shape ({}, 2) of (v, omega); got dtype {}",
                      n, py::str(a.dtype()).cast<std::string>()));
    if (a.ndim() != 2 || static_cast<std::size_t>(a.shape(0)) != n || a.shape(1) != 2)
      throw py::value_error(
          fmt::format("actions must have shape ({}, 2): one (v, omega) per copy; got shape {}", n,
                      py::str(py::getattr(a, "shape")).cast<std::string>()));
    const auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    const double* v = d.data();
    commands_.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      if (!std::isfinite(v[2 * i]) || !std::isfinite(v[2 * i + 1]))
        throw py::value_error(
            fmt::format("actions[{}] = ({}, {}) is not finite", i, v[2 * i], v[2 * i + 1]));
      commands_.push_back(Command::unicycle(v[2 * i], v[2 * i + 1]));
    }
  }

  static bool python_controller(const std::vector<ScenarioPtr>& s) {
    for (const auto& x : s)
      if (x->python_controller) return true;
    return false;
  }

  static std::vector<VecCopy> copies_of(const std::vector<ScenarioPtr>& scenarios) {
    if (scenarios.empty()) throw py::value_error("a VecEnv needs at least one copy");
    std::vector<VecCopy> out;
    for (const auto& s : scenarios) {
      if (!s) throw py::value_error("a VecEnv scenario is None");
      if (s->scenario.robots.size() != 1)
        throw InputError(s->source, "robots",
                         fmt::format("{} robots: a VecEnv steps copies of one robot (use "
                                     "floornav.ParallelEnv to step a fleet)",
                                     s->scenario.robots.size()));
      out.push_back({s->scenario.world.get(), &s->scenario.robot(), &s->scenario.sim,
                     s->scenario.name, &s->scenario.crowd});
    }
    return out;
  }

 public:
  /// Frames of the copies `which` (all: None) as uint8 (k, height, width, 3), drawn on the
  /// stepping threads with the GIL released.
  py::array render(py::object which, int height, int width) {
    const Busy busy(busy_);
    std::vector<std::size_t> ids;
    if (which.is_none()) {
      for (std::size_t i = 0; i < size(); ++i) ids.push_back(i);
    } else {
      for (py::handle h : which) {
        const long long i = h.cast<long long>();
        if (i < 0 || static_cast<std::size_t>(i) >= size())
          throw py::value_error(fmt::format("render: copy {} of {}", i, size()));
        ids.push_back(static_cast<std::size_t>(i));
      }
    }
    for (std::size_t i : ids)
      if (!started_[i]) throw py::value_error("render: call reset() first");
    std::vector<const FrameRaster*> rasters(ids.size());
    for (std::size_t k = 0; k < ids.size(); ++k) rasters[k] = &raster_for(ids[k], height, width);
    const std::size_t bytes = rasters.empty() ? 0 : rasters.front()->bytes();
    py::array_t<std::uint8_t> frames({static_cast<py::ssize_t>(ids.size()),
                                      static_cast<py::ssize_t>(height),
                                      static_cast<py::ssize_t>(width), py::ssize_t{3}});
    std::uint8_t* out = frames.mutable_data();
    {
      py::gil_scoped_release nogil;
      vec_.pool().run(ids.size(), 8, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k)
          draw_copy(ids[k], *rasters[k], std::span<std::uint8_t>(out + k * bytes, bytes));
      });
    }
    return frames;
  }

 private:
  // The raster of copy i's world now. A raster keeps the scenario that owns its world alive, so
  // that its address names no other world; rasters of floors no copy is on any longer go.
  const FrameRaster& raster_for(std::size_t i, int height, int width) {
    std::shared_ptr<const void> owner = floors_.empty() || !floors_[i]
                                            ? std::shared_ptr<const void>(scenarios_[i])
                                            : std::shared_ptr<const void>(floors_[i]);
    const World* world = vec_.copy(i).world;
    std::erase_if(rasters_, [](const Raster& r) { return r.owner.use_count() == 1; });
    for (const auto& r : rasters_)
      if (r.world == world && r.raster->height() == height && r.raster->width() == width)
        return *r.raster;
    std::unique_ptr<FrameRaster> raster;
    {
      py::gil_scoped_release nogil;
      raster = std::make_unique<FrameRaster>(*world, height, width);
    }
    rasters_.push_back({std::move(owner), world, std::move(raster)});
    return *rasters_.back().raster;
  }

  void draw_copy(std::size_t i, const FrameRaster& raster, std::span<std::uint8_t> rgb) const {
    const RobotAgent& a = vec_.agent(i);
    const Observation obs = vec_.observe(i);
    FrameRobot robot;
    robot.pose = a.pose();
    robot.radius = a.robot().body_radius;
    robot.footprint = a.robot().footprint;
    if (obs.goal_index < obs.goal_count) robot.goal = obs.goal;
    robot.returns = obs.sensed;
    robot.colour = colour_;
    const Crowd* crowd = vec_.crowd(i);
    raster.draw(rgb, {&robot, 1}, crowd ? crowd->people() : std::span<const Circle>{},
                crowd ? crowd->forklifts() : std::span<const OrientedBox>{});
  }

  struct Raster {
    std::shared_ptr<const void> owner;  ///< the scenario whose world it is
    const World* world;
    std::unique_ptr<FrameRaster> raster;
  };
  std::vector<Raster> rasters_;
  Rgb colour_{rgb_of(robot_color(0))};

  std::vector<ScenarioPtr> scenarios_;
  VecSimulation vec_;
  bool copy_;
  RewardParams reward_;
  FloorDraw floor_draw_;
  std::vector<std::shared_ptr<const Scenario>> floors_;  ///< per copy: its episode's floor
  std::vector<std::uint64_t> floor_seeds_;               ///< per copy: that floor's seed
  std::size_t beams_{0};
  std::uint64_t base_seed_{0};
  std::vector<std::uint64_t> episode_;
  std::vector<std::uint8_t> started_;   ///< reset at least once
  std::vector<double> distance_;        ///< to the current goal, at the current observation
  std::vector<int> goals_;              ///< goals reached, at the current observation
  std::vector<std::size_t> step_goal_;  ///< the goal index when the step began
  std::vector<std::uint8_t> ended_;     ///< the run had ended before this step (no reward)
  std::vector<Command> commands_;
  std::optional<Buffers> persistent_;
  std::optional<Buffers> last_;  ///< the arrays the last step wrote
  std::atomic<bool> busy_{false};
};

}  // namespace

/// A weight that is NaN or infinite would make every reward NaN or infinite: refused.
void check_reward(const RewardParams& r) {
  const std::pair<const char*, double> weights[] = {
      {"progress", r.progress}, {"goal", r.goal}, {"collision", r.collision}, {"time", r.time}};
  for (const auto& [name, v] : weights)
    if (!std::isfinite(v) || std::abs(v) > 1e9)
      throw py::value_error(
          fmt::format("RewardParams {}={}: a reward weight is a finite number of magnitude at "
                      "most 1e9",
                      name, v));
}

void bind_vec_env(py::module_& m) {
  py::class_<RewardParams>(m, "RewardParams",
                           "The default VecEnv reward per copy and step: progress * (d_before - "
                           "d_after) + goal * (goals reached) - collision * (collided) - time * "
                           "dt, d being the distance to the goal current when the step began.")
      .def(py::init([](double progress, double goal, double collision, double time) {
             const RewardParams r{progress, goal, collision, time};
             check_reward(r);
             return r;
           }),
           py::arg("progress") = 1.0, py::arg("goal") = 1.0, py::arg("collision") = 1.0,
           py::arg("time") = 0.0)
      .def_property(
          "progress", [](const RewardParams& r) { return r.progress; },
          [](RewardParams& r, double v) {
            RewardParams changed = r;
            changed.progress = v;
            check_reward(changed);
            r = changed;
          })
      .def_property(
          "goal", [](const RewardParams& r) { return r.goal; },
          [](RewardParams& r, double v) {
            RewardParams changed = r;
            changed.goal = v;
            check_reward(changed);
            r = changed;
          })
      .def_property(
          "collision", [](const RewardParams& r) { return r.collision; },
          [](RewardParams& r, double v) {
            RewardParams changed = r;
            changed.collision = v;
            check_reward(changed);
            r = changed;
          })
      .def_property(
          "time", [](const RewardParams& r) { return r.time; },
          [](RewardParams& r, double v) {
            RewardParams changed = r;
            changed.time = v;
            check_reward(changed);
            r = changed;
          })
      .def("__repr__", [](const RewardParams& r) {
        return fmt::format("RewardParams(progress={}, goal={}, collision={}, time={})", r.progress,
                           r.goal, r.collision, r.time);
      });

  py::class_<EpisodeDraw>(m, "_EpisodeDraw")
      .def(py::init<>())
      .def_readwrite("start", &EpisodeDraw::start)
      .def_readwrite("goal", &EpisodeDraw::goal)
      .def_property(
          "start_region", [](const EpisodeDraw&) { return py::none(); },
          [](EpisodeDraw& d, const std::vector<double>& b) {
            d.start_region = Box2{{b.at(0), b.at(1)}, {b.at(2), b.at(3)}};
          })
      .def_property(
          "goal_region", [](const EpisodeDraw&) { return py::none(); },
          [](EpisodeDraw& d, const std::vector<double>& b) {
            d.goal_region = Box2{{b.at(0), b.at(1)}, {b.at(2), b.at(3)}};
          })
      .def_readwrite("clearance", &EpisodeDraw::clearance)
      .def_readwrite("min_goal_distance", &EpisodeDraw::min_goal_distance)
      .def_readwrite("max_goal_distance", &EpisodeDraw::max_goal_distance)
      .def_readwrite("max_tries", &EpisodeDraw::max_tries);

  py::class_<FloorDraw>(m, "_FloorDraw")
      .def(py::init<>())
      .def_readwrite("generator", &FloorDraw::generator)
      .def_readwrite("seeds", &FloorDraw::seeds)
      .def_readwrite("start", &FloorDraw::start)
      .def_readwrite("step", &FloorDraw::step)
      .def_readwrite("count", &FloorDraw::count)
      .def("pick", &FloorDraw::pick, py::arg("seed"));

  py::class_<VecCore>(m, "_VecCore")
      .def(py::init<std::vector<ScenarioPtr>, int, bool, RewardParams, EpisodeDraw, FloorDraw>(),
           py::arg("scenarios"), py::arg("threads"), py::arg("copy"), py::arg("reward"),
           py::arg("draw"), py::arg("floors") = FloorDraw{})
      .def("render", &VecCore::render, py::arg("which"), py::arg("height"), py::arg("width"))
      .def("reset", &VecCore::reset, py::arg("seed") = py::none())
      .def("step", &VecCore::step, py::arg("actions"), py::arg("autoreset") = true)
      .def("reset_ended", &VecCore::reset_ended, py::arg("obs"), py::arg("terminated"),
           py::arg("truncated"))
      .def("ended_mask", &VecCore::ended_mask)
      .def("statuses", &VecCore::statuses)
      .def("seeds", &VecCore::seeds)
      .def("floor_seeds", &VecCore::floor_seeds)
      .def_property_readonly("n_envs", &VecCore::size)
      .def_property_readonly("beam_count", &VecCore::beams)
      .def_property_readonly("threads", &VecCore::threads);
}

}  // namespace floornav::python
