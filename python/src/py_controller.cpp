#include "py_controller.hpp"

#include <fmt/format.h>
#include <pybind11/stl.h>

#include <memory>

#include "floornav/nav/navigation_params.hpp"

namespace floornav::python {

namespace {
py::object attribute_or_none(py::handle target, const char* name) {
  if (!PyObject_HasAttrString(target.ptr(), name)) return py::none();
  return target.attr(name);
}

std::vector<std::string> string_list(py::handle h, const char* what) {
  std::vector<std::string> out;
  for (py::handle item : h) {
    if (!py::isinstance<py::str>(item))
      throw py::value_error(fmt::format("a controller's {} are strings, got {}", what,
                                        py::str(py::repr(item)).cast<std::string>()));
    out.push_back(item.cast<std::string>());
  }
  return out;
}
}  // namespace

std::vector<std::string> PyController::declared_modes(py::handle target, const std::string& kind) {
  const py::object names = attribute_or_none(target, "mode_names");
  if (names.is_none()) return {kind};
  std::vector<std::string> out = string_list(names, "mode_names");
  if (out.empty()) throw py::value_error("a controller's mode_names may not be empty");
  return out;
}

std::vector<std::string> PyController::declared_guards(py::handle target) {
  const py::object names = attribute_or_none(target, "guard_names");
  return names.is_none() ? std::vector<std::string>{} : string_list(names, "guard_names");
}

PyController::PyController(py::object target, std::vector<std::string> mode_names,
                           std::vector<std::string> guard_names, py::object robot,
                           py::object params)
    : Controller(std::move(mode_names), std::move(guard_names)) {
  py::gil_scoped_acquire gil;
  target_ = std::move(target);
  robot_ = std::move(robot);
  params_ = std::move(params);
  const py::object decide = attribute_or_none(target_, "decide");
  if (!decide.is_none() && PyCallable_Check(decide.ptr()))
    decide_ = decide;
  else if (PyCallable_Check(target_.ptr()))
    decide_ = target_;
  else
    throw py::type_error(fmt::format(
        "a controller is a callable (observation -> command) or has decide(observation); got {}",
        py::str(py::repr(target_)).cast<std::string>()));
  const py::object reset = attribute_or_none(target_, "reset");
  if (!reset.is_none() && PyCallable_Check(reset.ptr())) reset_ = reset;
  has_mode_ = PyObject_HasAttrString(target_.ptr(), "mode") != 0;
}

PyController::~PyController() {
  if (!Py_IsInitialized()) {  // the interpreter is gone: nothing to give references back to
    for (py::object* o : {&target_, &decide_, &reset_, &robot_, &params_}) o->release();
    return;
  }
  py::gil_scoped_acquire gil;
  target_ = py::object();
  decide_ = py::object();
  reset_ = py::object();
  robot_ = py::object();
  params_ = py::object();
}

int PyController::mode_index(py::handle mode) const {
  const auto& names = mode_names();
  if (py::isinstance<py::str>(mode)) {
    const std::string name = mode.cast<std::string>();
    for (std::size_t i = 0; i < names.size(); ++i)
      if (names[i] == name) return static_cast<int>(i);
    throw py::value_error(
        fmt::format("the controller reported mode '{}', which is not one of "
                    "its mode_names {}",
                    name, py::str(py::cast(names)).cast<std::string>()));
  }
  if (!PyLong_Check(mode.ptr()) || PyBool_Check(mode.ptr()))
    throw py::value_error(fmt::format("a mode is an index or a name, got {}",
                                      py::str(py::repr(mode)).cast<std::string>()));
  const long i = mode.cast<long>();
  if (i < 0 || static_cast<std::size_t>(i) >= names.size())
    throw py::value_error(
        fmt::format("the controller reported mode {}, but has {} mode_names", i, names.size()));
  return static_cast<int>(i);
}

int PyController::guard_index(py::handle guard) const {
  if (guard.is_none()) return -1;
  const auto& names = guard_names();
  if (py::isinstance<py::str>(guard)) {
    const std::string name = guard.cast<std::string>();
    for (std::size_t i = 0; i < names.size(); ++i)
      if (names[i] == name) return static_cast<int>(i);
    throw py::value_error(
        fmt::format("the controller reported guard '{}', which is not one of "
                    "its guard_names {}",
                    name, py::str(py::cast(names)).cast<std::string>()));
  }
  if (!PyLong_Check(guard.ptr()) || PyBool_Check(guard.ptr()))
    throw py::value_error(fmt::format("a guard is an index, a name or None, got {}",
                                      py::str(py::repr(guard)).cast<std::string>()));
  const long i = guard.cast<long>();
  if (i == -1) return -1;
  if (i < 0 || static_cast<std::size_t>(i) >= names.size())
    throw py::value_error(
        fmt::format("the controller reported guard {}, but has {} guard_names", i, names.size()));
  return static_cast<int>(i);
}

Decision PyController::decide(const Observation& obs) {
  py::gil_scoped_acquire gil;
  const py::dict o = observation_dict(obs, "running", robot_, params_);
  const py::object result = decide_(o);
  Decision decision{Command::goal_reached()};
  if (py::isinstance<PyDecision>(result)) {
    const auto& d = result.cast<const PyDecision&>();
    last_mode_ = d.mode.is_none() ? mode() : mode_index(d.mode);
    decision = {d.command, last_mode_, guard_index(d.guard)};
  } else {
    const Command c = to_command(result);
    if (has_mode_) last_mode_ = mode();
    decision = {c, last_mode_, -1};
  }
  // Within controller.epsilon of the goal, the goal is reached, whatever motion the controller
  // still asks for: as the built-in kinds' STOP, and as a command given to Simulation.step.
  const Command::Kind kind = decision.command.kind();
  if (kind != Command::Kind::GoalReached && kind != Command::Kind::Stuck && obs.params &&
      obs.goal_distance() < obs.params->epsilon)
    decision.command = Command::goal_reached();
  return decision;
}

void PyController::reset() {
  py::gil_scoped_acquire gil;
  if (reset_) reset_();
  last_mode_ = has_mode_ ? mode() : 0;
}

int PyController::mode() const {
  if (!has_mode_) return last_mode_;
  py::gil_scoped_acquire gil;
  py::object m = target_.attr("mode");
  if (PyCallable_Check(m.ptr())) m = m();
  if (m.is_none()) return 0;
  return mode_index(m);
}

ControllerFactory make_python_factory(py::object callable, bool is_factory, std::string kind) {
  const PyRef ref(std::move(callable));
  return [ref, is_factory, kind](const ControllerContext& ctx) -> std::unique_ptr<Controller> {
    py::gil_scoped_acquire gil;
    py::object robot = robot_info(ctx.robot, ctx.robot_name);
    py::object params = py::cast(ctx.params);
    py::object target = ref.get();
    if (is_factory) {
      py::dict context;
      context["robot"] = robot;
      context["params"] = params;
      context["robot_name"] = std::string(ctx.robot_name);
      context["robot_index"] = ctx.robot_index;
      target = ref.get()(context);
      if (target.is_none())
        throw py::value_error("the controller factory returned None, not a controller");
    }
    return std::make_unique<PyController>(target, PyController::declared_modes(target, kind),
                                          PyController::declared_guards(target), robot, params);
  };
}

void bind_controllers(py::module_& m) {
  py::class_<Command>(m, "Command",
                      "What a controller asks for at one step. Every kind goes through the same "
                      "wheel mapping and saturation (eqs. 5.10/5.11); a velocity u first goes "
                      "through the heading PID of Fig 5.12.")
      .def_static(
          "velocity", [](py::handle u) { return Command::velocity(to_vec2(u, "u")); }, py::arg("u"),
          "u (m/s, world frame) for the point robot: theta_d = atan2(u), the heading "
          "PID, V = |u| capped at v0 (Fig 5.12).")
      .def_static("unicycle", &Command::unicycle, py::arg("v"), py::arg("omega"),
                  "(V, omega): m/s, rad/s.")
      .def_static("wheels", &Command::wheels, py::arg("left"), py::arg("right"),
                  "Wheel speeds, rad/s.")
      .def_static("goal_reached", &Command::goal_reached,
                  "The current goal is reached (STOP): the robot turns to the next goal.")
      .def_static("stuck", &Command::stuck,
                  "The controller gives up (nothing it tried helped): the run ends `stuck`.")
      .def_property_readonly("kind",
                             [](const Command& c) { return std::string(to_string(c.kind())); })
      .def_property_readonly(
          "values",
          [](const Command& c) {
            const Vec2 u = c.u();
            return py::make_tuple(u.x(), u.y());
          },
          "The command's two numbers: u, (v, omega) or (left, right); (0, 0) for goal_reached "
          "and stuck.")
      .def("__repr__", [](const Command& c) {
        const Vec2 u = c.u();
        switch (c.kind()) {
          case Command::Kind::Velocity:
            return fmt::format("Command.velocity(({}, {}))", u.x(), u.y());
          case Command::Kind::Unicycle:
            return fmt::format("Command.unicycle({}, {})", u.x(), u.y());
          case Command::Kind::Wheels:
            return fmt::format("Command.wheels({}, {})", u.x(), u.y());
          case Command::Kind::GoalReached:
            break;
          case Command::Kind::Stuck:
            return std::string("Command.stuck()");
        }
        return std::string("Command.goal_reached()");
      });

  py::class_<PyDecision>(m, "Decision",
                         "A command with the mode the controller is in and the guard that fired "
                         "at this step (indices into the controller's mode_names / guard_names, "
                         "or names). The simulator logs a transition when the mode changes or a "
                         "guard is given.")
      .def(py::init([](py::handle command, py::object mode, py::object guard) {
             return PyDecision{to_command(command), std::move(mode), std::move(guard)};
           }),
           py::arg("command"), py::arg("mode") = py::none(), py::arg("guard") = py::none())
      .def_readonly("command", &PyDecision::command)
      .def_readonly("mode", &PyDecision::mode)
      .def_readonly("guard", &PyDecision::guard)
      .def("__repr__", [](const PyDecision& d) {
        return fmt::format("Decision({}, mode={}, guard={})",
                           py::str(py::repr(py::cast(d.command))).cast<std::string>(),
                           py::str(py::repr(d.mode)).cast<std::string>(),
                           py::str(py::repr(d.guard)).cast<std::string>());
      });
}

}  // namespace floornav::python
