// floornav.Simulation: one robot stepped from Python (reset / step / observe), alone in its world
// or among the scenario's people and forklifts, and copied by replaying its commands.

#include <fmt/format.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>

#include "bindings.hpp"
#include "floornav/core/input_error.hpp"
#include "floornav/sim/simulation.hpp"

namespace floornav::python {

namespace {

// A command as pickle keeps it: (kind, a, b).
py::tuple command_state(const Command& c) {
  switch (c.kind()) {
    case Command::Kind::Velocity:
      return py::make_tuple(0, c.u().x(), c.u().y());
    case Command::Kind::Unicycle:
      return py::make_tuple(1, c.unicycle_command().v, c.unicycle_command().omega);
    case Command::Kind::Wheels:
      return py::make_tuple(2, c.wheel_speeds().left, c.wheel_speeds().right);
    case Command::Kind::GoalReached:
      return py::make_tuple(3, 0.0, 0.0);
    case Command::Kind::Stuck:
      break;
  }
  return py::make_tuple(4, 0.0, 0.0);
}

Command command_of_state(const py::tuple& t) {
  const int kind = t[0].cast<int>();
  const double a = t[1].cast<double>(), b = t[2].cast<double>();
  switch (kind) {
    case 0:
      return Command::velocity({a, b});
    case 1:
      return Command::unicycle(a, b);
    case 2:
      return Command::wheels(a, b);
    case 3:
      return Command::goal_reached();
    case 4:
      return Command::stuck();
    default:
      throw py::value_error(fmt::format("a pickled Simulation holds an unknown command {}", kind));
  }
}

class PySimulation {
 public:
  PySimulation(ScenarioPtr scenario, std::optional<bool> record)
      : scenario_(std::move(scenario)), sim_config_(scenario_->scenario.sim) {
    const Scenario& s = scenario_->scenario;
    if (s.robots.size() != 1)
      throw InputError(scenario_->source, "robots",
                       fmt::format("{} robots: a Simulation steps one robot (use "
                                   "floornav.ParallelEnv to step a fleet, or floornav.run)",
                                   s.robots.size()));
    if (record) sim_config_.record_trajectory = *record;
    const RobotTask& task = s.robot();
    robot_ = robot_info(task.robot, task.name);
    params_ = py::cast(task.controller.params);
    start();
  }

  /// A simulation of the same scenario, seed and settings, brought to the same state by
  /// replaying this one's steps.
  std::unique_ptr<PySimulation> copy() const {
    std::unique_ptr<PySimulation> c(new PySimulation(*this, Tag{}));
    c->replay(log_);
    return c;
  }

  py::dict reset(const py::object& seed) {
    refuse_inside_step("reset()");
    if (!seed.is_none()) sim_config_.seed = to_seed(seed, "seed");
    start();
    return observe();
  }

  py::dict step(py::handle command) {
    refuse_inside_step("step()");
    if (finished())
      throw py::value_error(
          fmt::format("the run has ended ({} at t = {} s): call reset() to start another",
                      to_string(agent().result().status), agent().time()));
    std::optional<Command> c;
    if (!command.is_none()) c = to_command(command);
    {
      // A Python controller runs inside this step: were it to reset() or step() this very
      // simulation, the run under way would be freed (or re-entered) beneath it.
      stepping_ = true;
      struct Done {
        bool& flag;
        ~Done() { flag = false; }
      } done{stepping_};
      advance(c);
    }
    return observe();
  }

  py::dict observe() {
    refuse_inside_step("observe()");
    const Observation obs = fleet_ ? fleet_->observe(0) : sim_->observe();
    return observation_dict(obs, status(), robot_, params_);
  }

  const RobotAgent& agent() const { return fleet_ ? fleet_->robot(0) : sim_->agent(); }
  bool finished() const { return agent().finished(); }
  std::string_view status() const { return status_name(finished(), agent().result().status); }
  const ScenarioPtr& scenario() const { return scenario_; }
  std::uint64_t seed() const { return sim_config_.seed; }
  bool record() const { return sim_config_.record_trajectory; }

  std::shared_ptr<PyRunResult> result() const {
    auto r = std::make_shared<PyRunResult>();
    r->scenario = scenario_;
    if (fleet_)
      r->fleet = fleet_->result();
    else
      r->run = sim_->result();
    return r;
  }

  /// (scenario, seed, record, commands): what pickle keeps; the commands are replayed.
  py::tuple state() const {
    py::list commands;
    for (const auto& c : log_) commands.append(c ? py::object(command_state(*c)) : py::none());
    return py::make_tuple(scenario_, sim_config_.seed, sim_config_.record_trajectory, commands);
  }

  static std::unique_ptr<PySimulation> from_state(const py::tuple& t) {
    if (t.size() != 4)
      throw py::value_error("a pickled Simulation is (scenario, seed, record, log)");
    auto s = std::make_unique<PySimulation>(t[0].cast<ScenarioPtr>(), t[2].cast<bool>());
    s->sim_config_.seed = t[1].cast<std::uint64_t>();
    s->start();
    std::vector<std::optional<Command>> log;
    for (py::handle c : t[3].cast<py::list>())
      log.push_back(c.is_none() ? std::nullopt
                                : std::optional<Command>(command_of_state(c.cast<py::tuple>())));
    s->replay(log);
    return s;
  }

 private:
  struct Tag {};
  // A fresh simulation of `other`'s scenario, seed and settings (no step taken).
  PySimulation(const PySimulation& other, Tag)
      : scenario_(other.scenario_),
        sim_config_(other.sim_config_),
        robot_(other.robot_),
        params_(other.params_) {
    start();
  }

  void refuse_inside_step(const char* what) const {
    if (stepping_)
      throw std::runtime_error(fmt::format(
          "Simulation.{} was called from inside this simulation's own step (by its controller): "
          "a controller cannot restart, step or sense the run it is part of",
          what));
  }

  void start() {
    const Scenario& s = scenario_->scenario;
    // The old run's controller goes before the new one is made.
    sim_.reset();
    fleet_.reset();
    log_.clear();
    if (s.is_fleet()) {  // among people or forklifts (or a `robots:` list of one): as `run` does
      fleet_ = std::make_unique<FleetSimulation>(*s.world, s.robots, sim_config_, s.name, &s.crowd);
      fleet_->keep_sensing();
    } else {
      sim_.emplace(*s.world, s.robot(), sim_config_, s.name);
    }
  }

  void advance(const std::optional<Command>& c) {
    if (fleet_)
      fleet_->step({&c, 1});
    else if (c)
      sim_->step(*c);
    else
      sim_->step();
    log_.push_back(c);
  }

  void replay(const std::vector<std::optional<Command>>& log) {
    for (const auto& c : log) {
      if (finished()) throw py::value_error("the replayed commands run past the end of the run");
      advance(c);
    }
  }

  ScenarioPtr scenario_;
  SimConfig sim_config_;  ///< the scenario's, with the seed of reset(seed)
  std::optional<Simulation> sim_;
  std::unique_ptr<FleetSimulation> fleet_;   ///< the robot among people and forklifts
  std::vector<std::optional<Command>> log_;  ///< every step's command (none: the controller's)
  bool stepping_{false};  ///< a step is under way (its controller may call back into Python)
  py::object robot_;
  py::object params_;
};

// A Scenario, or a path to load one from (as floornav.run takes either).
ScenarioPtr scenario_of(py::handle h) {
  if (py::isinstance<PyScenario>(h)) return h.cast<ScenarioPtr>();
  return py::module_::import("floornav").attr("load_scenario")(h).cast<ScenarioPtr>();
}

}  // namespace

void bind_simulation(py::module_& m) {
  py::class_<PySimulation>(
      m, "Simulation",
      "One robot stepped from Python: the scenario's robot in its world, among its people and "
      "forklifts (as `floornav run` moves them). reset() and step() return the observation dict "
      "(t, pose, goal, goal_index, ranges, points; dt, goal_count, obstacles, status, robot, "
      "params). step() lets the scenario's controller drive; step((v, omega)) drives the robot "
      "with that unicycle command through the same wheel mapping and saturation. The sensors are "
      "cast once per step: observe() and the step after it share one sensing. A fleet of several "
      "robots is an InputError (floornav.ParallelEnv steps fleets).")
      .def(py::init([](py::handle scenario, std::optional<bool> record) {
             return std::make_unique<PySimulation>(scenario_of(scenario), record);
           }),
           py::arg("scenario"), py::kw_only(), py::arg("record") = py::none(),
           "`scenario`: a Scenario or a path to a scenario file. `record` keeps the trajectory "
           "for `result` (default: the scenario's sim.record_trajectory).")
      .def("reset", &PySimulation::reset, py::arg("seed") = py::none(),
           "Starts the run again (with sim.seed = `seed` if given); returns the first "
           "observation.")
      .def("step", &PySimulation::step, py::arg("command") = py::none(),
           "One step: the controller's command (None), or (v, omega) in m/s and rad/s, "
           "{'u': (ux, uy)}, {'wheels': (l, r)}, {'goal_reached': True}, a floornav.Command. "
           "Returns the next observation. ValueError for a command that is not finite and "
           "once the run has ended.")
      .def("observe", &PySimulation::observe, "The observation now (no step).")
      .def("copy", &PySimulation::copy,
           "An independent simulation in the same state: its next steps, given the same "
           "commands, equal this one's bit for bit. It is made by replaying this run's steps "
           "from the start (a Python controller that drove them is called again).")
      .def("__copy__", &PySimulation::copy)
      .def("__deepcopy__", [](const PySimulation& s, py::handle) { return s.copy(); })
      .def(py::pickle([](const PySimulation& s) { return s.state(); },
                      [](const py::tuple& t) { return PySimulation::from_state(t); }))
      .def_property_readonly("t", [](const PySimulation& s) { return s.agent().time(); })
      .def_property_readonly("pose",
                             [](const PySimulation& s) {
                               const Pose2& p = s.agent().pose();
                               return py::make_tuple(p.position.x(), p.position.y(), p.theta);
                             })
      .def_property_readonly("finished", &PySimulation::finished)
      .def_property_readonly("status", &PySimulation::status,
                             "running, reached, collision, timeout or stuck.")
      .def_property_readonly(
          "mode",
          [](const PySimulation& s) {
            const auto& names = s.agent().controller().mode_names();
            const int m = s.agent().mode();
            return m >= 0 && static_cast<std::size_t>(m) < names.size()
                       ? names[static_cast<std::size_t>(m)]
                       : std::string("mode_") + std::to_string(m);
          },
          "The controller's mode now.")
      .def_property_readonly("steps",
                             [](const PySimulation& s) { return s.agent().result().steps; })
      .def_property_readonly("seed", &PySimulation::seed)
      .def_property_readonly("scenario", &PySimulation::scenario)
      .def_property_readonly("result", &PySimulation::result,
                             "The run so far (the whole run once finished) as a RunResult: a "
                             "fleet's among people and forklifts, as floornav.run gives it.");
}

}  // namespace floornav::python
