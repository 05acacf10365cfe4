// The chapter's behaviours (nav/behaviours.hpp), the supervisor's input
// (make_navigation_input) and its parameters, for controllers written in Python.

#include <fmt/format.h>
#include <pybind11/stl.h>

#include <concepts>
#include <optional>
#include <string>

#include "bindings.hpp"
#include "floornav/core/enum_names.hpp"
#include "floornav/core/param_fields.hpp"
#include "floornav/nav/behaviours.hpp"
#include "floornav/nav/controller_registry.hpp"
#include "floornav/nav/navigation_automaton.hpp"
#include "floornav/nav/navigation_params.hpp"
#include "floornav/sim/sim_config.hpp"

namespace floornav::python {

namespace {

// An enumeration field is a string in Python: its name as a scenario file spells it
// (core/enum_names.hpp).
template <NamedEnum E>
E enum_from(const std::string& text, const char* field) {
  if (const std::optional<E> value = parse_enum<E>(text)) return *value;
  throw py::value_error(
      fmt::format("{}: unknown value '{}' (expected {})", field, text, enum_choices<E>()));
}

// Binds every field of a parameter struct's listing (core/param_fields.hpp) as a Python property
// through its member pointer, so that a field added to the struct appears in Python without
// touching this file. `access` leads from the bound class to the struct whose fields are listed
// (itself, or a struct flattened into it).
template <class Owner, class Access>
class PropertyBinder {
 public:
  PropertyBinder(py::class_<Owner>& cls, std::vector<std::string>& names, Access access)
      : cls_(cls), names_(names), access_(access) {}

  template <class Holder, class T>
  void operator()(const char* name, T Holder::*member, const char* doc) {
    names_.push_back(name);
    const Access access = access_;
    if constexpr (NamedEnum<T>) {
      cls_.def_property(
          name,
          [access, member](const Owner& o) { return std::string(to_string(access(o).*member)); },
          [access, member, name](Owner& o, const std::string& value) {
            access(o).*member = enum_from<T>(value, name);
          },
          doc);
    } else {
      cls_.def_property(
          name, [access, member](const Owner& o) { return access(o).*member; },
          [access, member](Owner& o, T value) { access(o).*member = value; }, doc);
    }
  }
  template <class Holder, class Section>
  void section(const char* name, Section Holder::*member) {
    names_.push_back(name);
    const Access access = access_;
    cls_.def_property(
        name, [access, member](Owner& o) -> Section& { return access(o).*member; },
        [access, member](Owner& o, const Section& value) { access(o).*member = value; },
        py::return_value_policy::reference_internal);
  }
  template <class Holder, class Inner>
  void flatten(Inner Holder::*member) {
    const Access outer = access_;
    const auto access = [ outer, member ](auto& o) -> auto& {
      return outer(o).*member;
    };
    PropertyBinder<Owner, decltype(access)> inner(cls_, names_, access);
    Inner::fields(inner);
  }

 private:
  py::class_<Owner>& cls_;
  std::vector<std::string>& names_;
  Access access_;
};

// Reads the fields into a dict (sections as nested dicts).
class DictWriter {
 public:
  explicit DictWriter(py::dict& d) : d_(d) {}
  template <class T>
  void operator()(const char* name, const T& field, const char*) {
    if constexpr (NamedEnum<T>)
      d_[name] = std::string(to_string(field));
    else
      d_[name] = field;
  }
  template <class Section>
  void section(const char* name, const Section& field) {
    py::dict sub;
    DictWriter w(sub);
    visit_fields(field, w);
    d_[name] = sub;
  }

 private:
  py::dict& d_;
};

template <class Owner>
py::dict to_dict(const Owner& o) {
  py::dict d;
  DictWriter w(d);
  visit_fields(o, w);
  return d;
}

template <class Owner>
void bind_params(py::class_<Owner>& cls) {
  std::vector<std::string> names;
  const auto itself = [](auto& o) -> auto& {
    return o;
  };
  PropertyBinder<Owner, decltype(itself)> binder(cls, names, itself);
  Owner::fields(binder);
  cls.attr("fields") = py::tuple(py::cast(names));
  cls.def(py::init<>());
  cls.def("to_dict", &to_dict<Owner>);
  if constexpr (std::equality_comparable<Owner>)
    cls.def("__eq__", [](const Owner& a, const Owner& b) { return a == b; });
  cls.def("__copy__", [](const Owner& o) { return Owner(o); });
  cls.def("__deepcopy__", [](const Owner& o, py::dict) { return Owner(o); });
  cls.def("__repr__", [](const Owner& o) {
    std::string out = std::string(py::str(py::type::of(py::cast(o)).attr("__name__"))) + "(";
    bool first = true;
    for (auto item : to_dict(o)) {
      out += fmt::format("{}{}={}", first ? "" : ", ", py::str(item.first).cast<std::string>(),
                         py::str(py::repr(item.second)).cast<std::string>());
      first = false;
    }
    return out + ")";
  });
}

Turn turn_of(py::handle h) {
  if (py::isinstance<Turn>(h)) return h.cast<Turn>();
  if (py::isinstance<py::str>(h)) {
    const std::string s = h.cast<std::string>();
    if (s == "clockwise" || s == "cw") return Turn::Clockwise;
    if (s == "counter_clockwise" || s == "ccw") return Turn::CounterClockwise;
  }
  throw py::value_error(
      fmt::format("a turn is floornav.Turn.CLOCKWISE or COUNTER_CLOCKWISE "
                  "(or 'cw' / 'ccw'), got {}",
                  py::str(py::repr(h)).cast<std::string>()));
}

}  // namespace

void bind_behaviours(py::module_& m) {
  py::class_<PidGains> pid(m, "PidGains", "Heading PID gains (eqs. 5.12-5.15).");
  bind_params(pid);
  py::class_<PlannerParams> planner(
      m, "PlannerParams",
      "The planning layer's `controller.planner:` section (docs/SCENARIOS.md).");
  bind_params(planner);
  py::class_<DwaParams> dwa(m, "DwaParams",
                            "The `dwa` controller kind's `controller.dwa:` section.");
  bind_params(dwa);
  py::class_<SafetyParams> safety(
      m, "SafetyParams",
      "The safety layer's `controller.safety:` section (docs/SAFETY.md): on by default.");
  bind_params(safety);
  py::class_<RobotAvoidanceParams> avoidance(
      m, "RobotAvoidanceParams",
      "Robot-robot avoidance: the `robot_avoidance` and `avoidance_*` keys of a `controller:` "
      "section.");
  bind_params(avoidance);
  py::class_<NavigationParams> params(
      m, "NavigationParams",
      "The chapter's keys of a robot's `controller:` section: speeds, the switching distances of "
      "Fig 5.11, the goal radius, the heading PID (docs/SCENARIOS.md, same names and units).");
  bind_params(params);
  py::class_<ControllerConfig> controller(
      m, "ControllerConfig",
      "A robot's whole `controller:` section but `kind`: the chapter's keys and the "
      "robot_avoidance keys as attributes, and the planner, dwa and safety sections.");
  bind_params(controller);
  controller.def_property_readonly(
      "kind", [](const ControllerConfig& c) { return c.kind; },
      "controller.kind: a built-in kind (floornav.controller_kinds()) or a user's controller");
  m.def(
      "controller_kinds",
      [] {
        py::dict kinds;
        for (const BuiltinController& b : builtin_controllers())
          kinds[py::str(b.name.data(), b.name.size())] =
              py::str(b.summary.data(), b.summary.size());
        return kinds;
      },
      "The built-in controller kinds that `controller.kind` may name, each with a line saying what "
      "it is.");
  py::class_<SimConfig> sim(
      m, "SimConfig", "A scenario's `sim:` section: dt, t_max, seed, stuck detection, recording.");
  bind_params(sim);

  py::enum_<Turn>(m, "Turn", "Which way round an obstacle follow-boundary goes.")
      .value("CLOCKWISE", Turn::Clockwise)
      .value("COUNTER_CLOCKWISE", Turn::CounterClockwise);

  m.def(
      "go_to_goal_velocity",
      [](py::handle x, py::handle goal, double v0, double a) {
        return vec2_tuple(go_to_goal_velocity(to_vec2(x, "x"), to_vec2(goal, "goal"), v0, a));
      },
      py::arg("x"), py::arg("goal"), py::arg("v0"), py::arg("a"),
      "Go to goal (eqs. 5.16-5.19): u = K e, e = goal - x, K = v0 (1 - exp(-a |e|^2)) / |e|. "
      "Returns u (m/s) as (ux, uy).");
  m.def(
      "avoid_obstacle_velocity",
      [](py::handle x, py::handle points, double v0) {
        std::vector<Vec2> storage;
        return vec2_tuple(
            avoid_obstacle_velocity(to_vec2(x, "x"), to_points(points, storage, "points"), v0));
      },
      py::arg("x"), py::arg("points"), py::arg("v0"),
      "Avoid obstacle (eq. 5.20) from obstacle points (k, 2): the away-vectors weighted by "
      "1/(|x - x_o|^2 + eps), scaled to v0; (0, 0) without points.");
  m.def("blend_weight", &blend_weight, py::arg("clearance"), py::arg("d_near"), py::arg("d_far"),
        "sigma of eq. 5.21: 0 at clearance d_far rising (smoothstep) to 1 at d_near.");
  m.def(
      "blend_velocities",
      [](py::handle u_gtg, py::handle u_ao, double sigma) {
        return vec2_tuple(blend_velocities(to_vec2(u_gtg, "u_gtg"), to_vec2(u_ao, "u_ao"), sigma));
      },
      py::arg("u_gtg"), py::arg("u_ao"), py::arg("sigma"),
      "Blending (eq. 5.21): (1 - sigma) u_gtg + sigma u_ao.");
  m.def(
      "follow_boundary_velocity",
      [](py::handle away, double clearance, py::handle turn, double d_fb, double k_distance,
         double v0) {
        return vec2_tuple(follow_boundary_velocity(to_vec2(away, "away"), clearance, turn_of(turn),
                                                   d_fb, k_distance, v0));
      },
      py::arg("away"), py::arg("clearance"), py::arg("turn"), py::arg("d_fb"),
      py::arg("k_distance"), py::arg("v0"),
      "Follow boundary (eqs. 5.22-5.24): the unit away-vector rotated by -pi/2 (clockwise) or "
      "+pi/2, plus a correction holding the clearance at d_fb, scaled to v0.");
  m.def(
      "follow_boundary_tangent",
      [](py::handle u_ao, py::handle turn) {
        return vec2_tuple(follow_boundary_tangent(to_vec2(u_ao, "u_ao"), turn_of(turn)));
      },
      py::arg("u_ao"), py::arg("turn"), "The tangent R(-+pi/2) u_AO of eqs. 5.23/5.24.");
  m.def(
      "choose_turn",
      [](py::handle u_gtg, py::handle u_ao) {
        return choose_turn(to_vec2(u_gtg, "u_gtg"), to_vec2(u_ao, "u_ao"));
      },
      py::arg("u_gtg"), py::arg("u_ao"),
      "Eqs. 5.23/5.24: CLOCKWISE when <u_gtg, u_fb^c> > 0, else COUNTER_CLOCKWISE.");

  py::class_<NavigationInput>(
      m, "NavigationInput",
      "What the supervisor sees at one step (make_navigation_input): vectors as (x, y) tuples.")
      .def_property_readonly("x", [](const NavigationInput& i) { return vec2_tuple(i.x); })
      .def_property_readonly("goal", [](const NavigationInput& i) { return vec2_tuple(i.goal); })
      .def_property_readonly(
          "u_gtg", [](const NavigationInput& i) { return vec2_tuple(i.u_gtg); }, "eq. 5.18")
      .def_property_readonly(
          "u_ao", [](const NavigationInput& i) { return vec2_tuple(i.u_ao); },
          "eq. 5.20; (0, 0) when no obstacle is sensed")
      .def_property_readonly(
          "away", [](const NavigationInput& i) { return vec2_tuple(i.away); }, "u_ao normalised")
      .def_readonly("clearance", &NavigationInput::clearance,
                    "m from the body to the nearest sensed point (inf: none)")
      .def_readonly("goal_distance", &NavigationInput::goal_distance, "|x - x_g|, m")
      .def_readonly("obstacle_sensed", &NavigationInput::obstacle_sensed)
      .def_readonly("corridor_blocked", &NavigationInput::corridor_blocked,
                    "a sensed point lies in the corridor towards the goal (clear_shot_corridor)")
      .def("__repr__", [](const NavigationInput& i) {
        return fmt::format(
            "NavigationInput(x=({}, {}), goal_distance={}, clearance={}, obstacle_sensed={})",
            i.x.x(), i.x.y(), i.goal_distance, i.clearance, i.obstacle_sensed);
      });

  m.def(
      "make_navigation_input",
      [](py::handle x, py::handle goal, py::handle points, double body_radius,
         const NavigationParams& params, py::handle footprint, double heading) {
        std::vector<Vec2> storage, fp_storage;
        const auto pts = to_points(points, storage, "points");
        const auto fp = to_points(footprint, fp_storage, "footprint");
        const BodyShape shape{fp, heading};
        return make_navigation_input(to_vec2(x, "x"), to_vec2(goal, "goal"), pts, body_radius,
                                     params, fp.empty() ? nullptr : &shape);
      },
      py::arg("x"), py::arg("goal"), py::arg("points"), py::arg("body_radius"), py::arg("params"),
      py::arg("footprint") = py::none(), py::arg("heading") = 0.0,
      "The supervisor's input from the position, the goal and the sensed points (k, 2): u_gtg, "
      "u_ao, the clearance from the body disc (or from `footprint`, robot frame, at `heading`, "
      "when params.footprint_clearance), what the built-in kinds compute every step.");

  m.def(
      "navigation_input",
      [](const py::dict& obs) {
        const py::object robot = obs["robot"];
        const NavigationParams& p = obs["params"].cast<const NavigationParams&>();
        std::vector<Vec2> storage, fp_storage;
        const auto pts = to_points(obs["obstacles"], storage, "obstacles");
        const auto fp = to_points(robot.attr("footprint"), fp_storage, "footprint");
        const auto pose =
            py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(obs["pose"]);
        if (!pose || pose.size() != 3)
          throw py::value_error("observation['pose'] must hold (x, y, theta)");
        const BodyShape shape{fp, pose.at(2)};
        return make_navigation_input(Vec2(pose.at(0), pose.at(1)), to_vec2(obs["goal"], "goal"),
                                     pts, robot.attr("body_radius").cast<double>(), p,
                                     fp.empty() ? nullptr : &shape);
      },
      py::arg("observation"),
      "make_navigation_input from an observation dict (its pose, goal, obstacles, robot and "
      "params), exactly as the built-in controllers call it.");
}

}  // namespace floornav::python
