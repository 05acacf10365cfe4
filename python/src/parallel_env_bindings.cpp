// The C++ side of floornav.ParallelEnv: a fleet (with its people and forklifts) stepped by
// per-robot commands from Python, PettingZoo's Parallel API shape: every dict keyed by robot name,
// built here without a Python loop. The physics is FleetSimulation's, robot for robot the run of
// `floornav run` (each robot acts on its own sensing, taken at the end of the step before).

#include <fmt/format.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstring>

#include "bindings.hpp"
#include "floornav/core/input_error.hpp"
#include "floornav/render/frame_raster.hpp"
#include "floornav/render/palette.hpp"
#include "floornav/sim/episode_draw.hpp"
#include "floornav/sim/fleet_simulation.hpp"
#include "status_code.hpp"

namespace floornav::python {

namespace {

double* doubles(py::array& a) {
  return static_cast<double*>(a.mutable_data());
}

/// The default reward's weights (as VecEnv's RewardParams).
struct Weights {
  double progress{1.0}, goal{1.0}, collision{1.0}, time{0.0};
};

class ParallelCore {
 public:
  ParallelCore(ScenarioPtr scenario, EpisodeDraw draw, Weights weights)
      : scenario_(std::move(scenario)),
        draw_(std::move(draw)),
        weights_(weights),
        sim_(scenario_->scenario.sim) {
    const Scenario& s = scenario_->scenario;
    sim_.record_trajectory = false;
    tasks_ = s.robots;
    const std::size_t n = tasks_.size();
    for (const RobotTask& t : tasks_) names_.push_back(py::str(t.name));
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < i; ++j)
        if (tasks_[i].name == tasks_[j].name)
          throw InputError(scenario_->source, fmt::format("robots[{}].name", i),
                           fmt::format("'{}' names two robots: ParallelEnv's agents need "
                                       "distinct names",
                                       tasks_[i].name));
    live_.assign(n, 0);
    commands_.resize(n);
    distance_.assign(n, 0.0);
    goals_.assign(n, 0);
    step_goal_.assign(n, 0);
    colours_.reserve(n);
    for (std::size_t i = 0; i < n; ++i) colours_.push_back(rgb_of(robot_color(i)));
    crowd_starts(s.crowd, keep_discs_, keep_boxes_);
  }

  py::list names() const {
    py::list out;
    for (const auto& n : names_) out.append(n);
    return out;
  }

  /// Starts an episode with sim.seed = `seed`; returns (observations, infos).
  py::tuple reset(std::uint64_t seed) {
    const Scenario& s = scenario_->scenario;
    sim_.seed = seed;
    fleet_.reset();  // the old episode's controllers go before the new ones are made
    tasks_ = s.robots;
    {
      py::gil_scoped_release nogil;
      if (draw_.any()) {
        Rng rng(episode_draw_seed(seed));
        try {
          draw_fleet_episode(draw_, *s.world, tasks_, {keep_discs_, keep_boxes_}, rng);
        } catch (const DrawError& e) {
          throw InputError(scenario_->source, "randomize", e.what());
        }
      }
      fleet_ = std::make_unique<FleetSimulation>(*s.world, tasks_, sim_, s.name, &s.crowd);
      fleet_->keep_sensing();
    }
    py::dict obs, infos;
    for (std::size_t i = 0; i < tasks_.size(); ++i) {
      live_[i] = 1;
      note(i);
      set_item(obs.ptr(), names_[i].ptr(), observation(i).release().ptr());
      set_item(infos.ptr(), names_[i].ptr(), info(i, 0.0).release().ptr());
    }
    return py::make_tuple(obs, infos);
  }

  /// One step: `actions` maps every live agent to (v, omega) or None (its controller drives).
  py::tuple step(py::handle actions) {
    if (!fleet_) throw py::value_error("call reset() before step()");
    read_actions(actions);
    {
      py::gil_scoped_release nogil;
      fleet_->step(commands_);
    }
    py::dict obs, rewards, terminations, truncations, infos;
    for (std::size_t i = 0; i < tasks_.size(); ++i) {
      if (!live_[i]) continue;
      const RobotAgent& a = fleet_->robot(i);
      const auto& goals = tasks_[i].goals;
      const Vec2 goal_before = goals[std::min(step_goal_[i], goals.size() - 1)];
      const double progress = distance_[i] - (goal_before - a.pose().position).norm();
      const int reached = a.result().goals_reached - goals_[i];
      const std::int8_t code = status_code(a);
      const double reward = weights_.progress * progress + weights_.goal * reached -
                            (code == 2 ? weights_.collision : 0.0) - weights_.time * sim_.dt;
      PyObject* name = names_[i].ptr();
      set_item(obs.ptr(), name, observation(i).release().ptr());
      set_item(rewards.ptr(), name, PyFloat_FromDouble(reward));
      set_item(terminations.ptr(), name, PyBool_FromLong(code == 1 || code == 2));
      set_item(truncations.ptr(), name, PyBool_FromLong(code == 3 || code == 4));
      set_item(infos.ptr(), name, info(i, progress).release().ptr());
      note(i);
      if (code != kRunning) live_[i] = 0;
    }
    return py::make_tuple(obs, rewards, terminations, truncations, infos);
  }

  /// Whether each agent is still in `agents` (robot order).
  py::list live() const {
    py::list out;
    for (std::size_t i = 0; i < live_.size(); ++i)
      if (live_[i]) out.append(names_[i]);
    return out;
  }

  /// The whole floor as uint8 (height, width, 3).
  py::array render(int height, int width) {
    if (!fleet_) throw py::value_error("call reset() before render()");
    if (!raster_ || raster_->height() != height || raster_->width() != width) {
      py::gil_scoped_release nogil;
      raster_ = std::make_unique<FrameRaster>(*scenario_->scenario.world, height, width);
    }
    py::array_t<std::uint8_t> frame(
        {static_cast<py::ssize_t>(height), static_cast<py::ssize_t>(width), py::ssize_t{3}});
    {
      py::gil_scoped_release nogil;
      std::vector<FrameRobot> robots(tasks_.size());
      for (std::size_t i = 0; i < tasks_.size(); ++i) {
        const RobotAgent& a = fleet_->robot(i);
        const Observation o = fleet_->observe(i);
        FrameRobot& r = robots[i];
        r.pose = a.pose();
        r.radius = a.robot().body_radius;
        r.footprint = a.robot().footprint;
        if (o.goal_index < o.goal_count) r.goal = o.goal;
        if (!a.finished()) r.returns = o.sensed;
        r.colour = colours_[i];
      }
      const Crowd* crowd = fleet_->crowd();
      raster_->draw(std::span<std::uint8_t>(frame.mutable_data(), raster_->bytes()), robots,
                    crowd ? crowd->people() : std::span<const Circle>{},
                    crowd ? crowd->forklifts() : std::span<const OrientedBox>{});
    }
    return frame;
  }

  /// The run so far as a fleet's RunResult (summary, per-robot runs, crowd).
  std::shared_ptr<PyRunResult> result() const {
    if (!fleet_) throw py::value_error("call reset() first");
    auto r = std::make_shared<PyRunResult>();
    r->scenario = scenario_;
    r->fleet = fleet_->result();
    return r;
  }

  double time() const { return fleet_ ? static_cast<double>(fleet_->steps()) * sim_.dt : 0.0; }
  std::size_t beams(std::size_t i) const { return tasks_.at(i).robot.sensors.size(); }

 private:
  // Where robot i's reward starts from at its next step.
  void note(std::size_t i) {
    const RobotAgent& a = fleet_->robot(i);
    const Observation o = fleet_->observe(i);
    distance_[i] = o.goal_distance();
    goals_[i] = a.result().goals_reached;
    step_goal_[i] = a.goal_index();
  }

  py::dict observation(std::size_t i) const {
    const DictKeys& k = dict_keys();
    const Observation o = fleet_->observe(i);
    py::dict d;
    PyObject* p = d.ptr();
    set_item(p, k.t, PyFloat_FromDouble(o.t));
    py::array pose = new_float_array({3});
    double* x = doubles(pose);
    x[0] = o.pose.position.x();
    x[1] = o.pose.position.y();
    x[2] = o.pose.theta;
    set_item(p, k.pose, pose.release().ptr());
    py::array goal = new_float_array({2});
    doubles(goal)[0] = o.goal.x();
    doubles(goal)[1] = o.goal.y();
    set_item(p, k.goal, goal.release().ptr());
    set_item(p, k.goal_index, PyLong_FromLong(o.goal_index));
    set_item(p, k.ranges, make_array(o.ranges).release().ptr());
    py::array points = new_float_array({static_cast<py::ssize_t>(o.beams.size()), 2});
    beam_points(o, doubles(points));
    set_item(p, k.points, points.release().ptr());
    return d;
  }

  py::dict info(std::size_t i, double progress) const {
    const DictKeys& k = dict_keys();
    const RobotAgent& a = fleet_->robot(i);
    py::dict d;
    PyObject* s = k.status_names[static_cast<std::size_t>(status_code(a))];
    Py_INCREF(s);
    set_item(d.ptr(), k.status, s);
    set_item(d.ptr(), k.goals_reached, PyLong_FromLong(a.result().goals_reached));
    set_item(d.ptr(), k.progress, PyFloat_FromDouble(progress));
    return d;
  }

  [[noreturn]] void bad_action(std::size_t i, const std::string& what) const {
    throw py::value_error(fmt::format("actions['{}']: {}", tasks_[i].name, what));
  }

  void read_actions(py::handle actions) {
    if (!PyDict_Check(actions.ptr()))
      throw py::value_error(
          fmt::format("actions must be a dict of agent name -> (v, omega) (or None: its controller "
                      "drives), got {}",
                      py::str(py::type::of(actions).attr("__name__")).cast<std::string>()));
    const py::dict a = py::reinterpret_borrow<py::dict>(actions);
    std::size_t given = 0;
    for (std::size_t i = 0; i < tasks_.size(); ++i) {
      PyObject* value = PyDict_GetItemWithError(a.ptr(), names_[i].ptr());
      if (!value && PyErr_Occurred()) throw py::error_already_set();
      commands_[i].reset();
      if (!value) {
        if (live_[i])
          throw py::value_error(fmt::format(
              "actions has no entry for agent '{}' (every agent in env.agents needs one; None "
              "lets its controller drive)",
              tasks_[i].name));
        continue;
      }
      ++given;
      if (!live_[i])
        throw py::value_error(fmt::format(
            "actions['{}']: that agent has finished ({} at t = {} s) and left env.agents",
            tasks_[i].name, to_string(fleet_->robot(i).result().status), fleet_->robot(i).time()));
      if (value == Py_None) continue;
      commands_[i] = read_pair(i, py::handle(value));
    }
    if (given != static_cast<std::size_t>(a.size())) {  // keys that name no agent
      for (auto item : a) {
        bool known = false;
        for (const auto& n : names_) known = known || item.first.equal(n);
        if (!known)
          throw py::value_error(
              fmt::format("actions: unknown agent {} (the agents are env.possible_agents)",
                          py::str(py::repr(item.first)).cast<std::string>()));
      }
    }
  }

  Command read_pair(std::size_t i, py::handle h) const {
    double v = 0.0, w = 0.0;
    if (py::isinstance<py::array>(h)) {
      const py::array arr = py::reinterpret_borrow<py::array>(h);
      if (arr.dtype().kind() != 'f')
        bad_action(i, fmt::format("a float array of shape (2,) of (v, omega), got dtype {}",
                                  py::str(arr.dtype()).cast<std::string>()));
      if (arr.ndim() != 1 || arr.shape(0) != 2)
        bad_action(i, fmt::format("shape (2,) of (v, omega), got shape {}",
                                  py::str(py::getattr(arr, "shape")).cast<std::string>()));
      const auto d = py::array_t<double, py::array::forcecast>::ensure(arr);
      v = d.at(0);
      w = d.at(1);
    } else if (PyTuple_Check(h.ptr()) || PyList_Check(h.ptr())) {
      const py::sequence seq = py::reinterpret_borrow<py::sequence>(h);
      if (seq.size() != 2)
        bad_action(i, fmt::format("(v, omega): two numbers, got {}", seq.size()));
      for (std::size_t k = 0; k < 2; ++k) {
        const py::handle x = seq[k];
        if (PyBool_Check(x.ptr()) ||
            !(PyFloat_Check(x.ptr()) || PyLong_Check(x.ptr()) || py::isinstance<py::float_>(x)))
          bad_action(i, fmt::format("(v, omega) are numbers, got {}",
                                    py::str(py::repr(x)).cast<std::string>()));
      }
      v = seq[0].cast<double>();
      w = seq[1].cast<double>();
    } else {
      bad_action(i, fmt::format("(v, omega) as a float array of shape (2,), a tuple or None, "
                                "got {}",
                                py::str(py::repr(h)).cast<std::string>()));
    }
    if (!std::isfinite(v) || !std::isfinite(w))
      bad_action(i, fmt::format("({}, {}) is not finite", v, w));
    return Command::unicycle(v, w);
  }

  ScenarioPtr scenario_;
  EpisodeDraw draw_;
  Weights weights_;
  SimConfig sim_;
  std::vector<RobotTask> tasks_;  ///< the episode's: the scenario's, starts and goals drawn
  std::unique_ptr<FleetSimulation> fleet_;
  std::vector<py::str> names_;
  std::vector<std::uint8_t> live_;
  std::vector<std::optional<Command>> commands_;
  std::vector<double> distance_;
  std::vector<int> goals_;
  std::vector<std::size_t> step_goal_;
  std::vector<Rgb> colours_;
  std::vector<Circle> keep_discs_;
  std::vector<OrientedBox> keep_boxes_;
  std::unique_ptr<FrameRaster> raster_;
};

}  // namespace

void bind_parallel_env(py::module_& m) {
  py::class_<ParallelCore>(m, "_ParallelCore")
      .def(py::init([](ScenarioPtr s, EpisodeDraw draw, py::object reward) {
             Weights w;
             if (!reward.is_none()) {
               w.progress = reward.attr("progress").cast<double>();
               w.goal = reward.attr("goal").cast<double>();
               w.collision = reward.attr("collision").cast<double>();
               w.time = reward.attr("time").cast<double>();
             }
             return std::make_unique<ParallelCore>(std::move(s), std::move(draw), w);
           }),
           py::arg("scenario"), py::arg("draw"), py::arg("reward"))
      .def("names", &ParallelCore::names)
      .def("reset", &ParallelCore::reset, py::arg("seed"))
      .def("step", &ParallelCore::step, py::arg("actions"))
      .def("live", &ParallelCore::live)
      .def("render", &ParallelCore::render, py::arg("height"), py::arg("width"))
      .def("result", &ParallelCore::result)
      .def_property_readonly("t", &ParallelCore::time);
}

}  // namespace floornav::python
