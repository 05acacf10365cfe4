// floornav.Simulation: one robot stepped from Python (reset / step / observe).

#include <fmt/format.h>
#include <pybind11/stl.h>

#include <optional>

#include "bindings.hpp"
#include "floornav/sim/simulation.hpp"

namespace floornav::python {

namespace {

class PySimulation {
 public:
  PySimulation(ScenarioPtr scenario, std::optional<bool> record)
      : scenario_(std::move(scenario)), sim_config_(scenario_->scenario.sim) {
    if (record) sim_config_.record_trajectory = *record;
    const RobotTask& task = scenario_->scenario.robot();
    robot_ = robot_info(task.robot, task.name);
    params_ = py::cast(task.controller.params);
    start();
  }

  py::dict reset(std::optional<std::uint64_t> seed) {
    if (seed) sim_config_.seed = *seed;
    start();
    return observe();
  }

  py::dict step(py::handle command) {
    if (sim_->finished())
      throw py::value_error(
          fmt::format("the run has ended ({} at t = {} s): call reset() to start another",
                      to_string(sim_->result().status), sim_->time()));
    if (command.is_none())
      sim_->step();
    else
      sim_->step(to_command(command));
    return observe();
  }

  py::dict observe() {
    const Observation obs = sim_->observe();
    return observation_dict(obs, status(), robot_, params_);
  }

  std::string_view status() const { return status_name(sim_->finished(), sim_->result().status); }
  const Simulation& sim() const { return *sim_; }
  const ScenarioPtr& scenario() const { return scenario_; }

  std::shared_ptr<PyRunResult> result() const {
    auto r = std::make_shared<PyRunResult>();
    r->scenario = scenario_;
    r->run = sim_->result();
    return r;
  }

 private:
  void start() {
    const Scenario& s = scenario_->scenario;
    sim_.reset();  // the old run's controller goes before the new one is made
    sim_.emplace(*s.world, s.robot(), sim_config_, s.name);
  }

  ScenarioPtr scenario_;
  SimConfig sim_config_;  ///< the scenario's, with the seed of reset(seed)
  std::optional<Simulation> sim_;
  py::object robot_;
  py::object params_;
};

}  // namespace

void bind_simulation(py::module_& m) {
  py::class_<PySimulation>(
      m, "Simulation",
      "One robot stepped from Python: the scenario's first robot alone in its world. "
      "reset() and step() return the observation dict (t, dt, pose, goal, goal_index, "
      "goal_count, ranges, points, sensed, status, robot, params). step() lets the scenario's "
      "controller drive; step((v, omega)) drives the robot with that unicycle command through "
      "the same wheel mapping and saturation. The sensors are cast once per step: observe() "
      "and the step after it share one sensing.")
      .def(py::init<ScenarioPtr, std::optional<bool>>(), py::arg("scenario"), py::kw_only(),
           py::arg("record") = py::none(),
           "`record` keeps the trajectory for `result` (default: the scenario's "
           "sim.record_trajectory).")
      .def("reset", &PySimulation::reset, py::arg("seed") = py::none(),
           "Starts the run again (with sim.seed = `seed` if given); returns the first "
           "observation.")
      .def("step", &PySimulation::step, py::arg("command") = py::none(),
           "One step: the controller's command (None), or (v, omega) in m/s and rad/s, "
           "{'u': (ux, uy)}, {'wheels': (l, r)}, {'goal_reached': True}, a floornav.Command. "
           "Returns the next observation. ValueError for a command that is not finite and "
           "once the run has ended.")
      .def("observe", &PySimulation::observe, "The observation now (no step).")
      .def_property_readonly("t", [](const PySimulation& s) { return s.sim().time(); })
      .def_property_readonly("pose",
                             [](const PySimulation& s) {
                               const Pose2& p = s.sim().pose();
                               return py::make_tuple(p.position.x(), p.position.y(), p.theta);
                             })
      .def_property_readonly("finished", [](const PySimulation& s) { return s.sim().finished(); })
      .def_property_readonly("status", &PySimulation::status,
                             "running, reached, collision, timeout or stuck.")
      .def_property_readonly(
          "mode",
          [](const PySimulation& s) {
            const auto& names = s.sim().agent().controller().mode_names();
            const int m = s.sim().agent().mode();
            return m >= 0 && static_cast<std::size_t>(m) < names.size()
                       ? names[static_cast<std::size_t>(m)]
                       : std::string("mode_") + std::to_string(m);
          },
          "The controller's mode now.")
      .def_property_readonly("steps", [](const PySimulation& s) { return s.sim().result().steps; })
      .def_property_readonly("scenario", &PySimulation::scenario)
      .def_property_readonly("result", &PySimulation::result,
                             "The run so far (the whole run once finished) as a RunResult.");
}

}  // namespace floornav::python
