// Scenarios: loading (with --set overrides), the InputError exception, what a scenario holds,
// and giving its robots a Python controller.

#include <fmt/format.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "bindings.hpp"
#include "floornav/core/input_error.hpp"
#include "floornav/core/output_error.hpp"
#include "floornav/io/scenario_file.hpp"
#include "floornav/io/scenario_writer.hpp"
#include "floornav/scenario/factory_floor.hpp"
#include "floornav/scenario/shared_floor.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "py_controller.hpp"

namespace floornav::python {

namespace {

py::object g_input_error;  // floornav.InputError, set once at import

// The CLI prints "floornav: error: <what>" (app/main.cpp): the exception's message is that line.
constexpr const char* kCliPrefix = "floornav: error: ";

py::dict world_dict(const World& w) {
  py::dict d;
  if (w.bounds())
    d["bounds"] = py::make_tuple(w.bounds()->min.x(), w.bounds()->min.y(), w.bounds()->max.x(),
                                 w.bounds()->max.y());
  else
    d["bounds"] = py::none();
  py::list circles;
  for (const Circle& c : w.circles())
    circles.append(py::make_tuple(c.center.x(), c.center.y(), c.radius));
  d["circles"] = circles;
  py::list polygons;
  for (const auto& p : w.polygons()) polygons.append(make_points(p));
  d["polygons"] = polygons;
  const auto segs = w.segments();
  py::array_t<double> s({static_cast<py::ssize_t>(segs.size()), py::ssize_t{4}});
  double* out = s.mutable_data();
  for (std::size_t i = 0; i < segs.size(); ++i) {
    out[4 * i] = segs[i].a.x();
    out[4 * i + 1] = segs[i].a.y();
    out[4 * i + 2] = segs[i].b.x();
    out[4 * i + 3] = segs[i].b.y();
  }
  d["segments"] = s;
  const Box2& e = w.extent();
  d["extent"] = py::make_tuple(e.min.x(), e.min.y(), e.max.x(), e.max.y());
  if (const OccupancyGrid* g = w.grid()) {
    py::array_t<bool> cells(
        {static_cast<py::ssize_t>(g->height()), static_cast<py::ssize_t>(g->width())});
    auto c = cells.mutable_unchecked<2>();
    for (int iy = 0; iy < g->height(); ++iy)
      for (int ix = 0; ix < g->width(); ++ix) c(iy, ix) = g->occupied(ix, iy);
    py::dict grid;
    grid["occupied"] = cells;  // row iy, column ix: cell (ix, iy) in the grid's frame
    grid["resolution"] = g->resolution();
    grid["origin"] =
        py::make_tuple(g->origin().position.x(), g->origin().position.y(), g->origin().theta);
    d["grid"] = grid;
  } else {
    d["grid"] = py::none();
  }
  return d;
}

py::dict robot_dict(const RobotTask& t) {
  py::dict d;
  d["name"] = t.name;
  d["preset"] = t.robot.preset;
  d["start"] = py::make_tuple(t.start.position.x(), t.start.position.y(), t.start.theta);
  py::list goals;
  for (const Vec2& g : t.goals) goals.append(vec2_tuple(g));
  d["goals"] = goals;
  d["controller"] = t.controller.kind;
  d["body_radius"] = t.robot.body_radius;
  d["max_speed"] = max_forward_speed(t.robot.drive);
  d["max_turn_rate"] = max_turn_rate(t.robot.drive);
  d["sensor_count"] = t.robot.sensors.size();
  std::vector<Vec2> fp(t.robot.footprint.begin(), t.robot.footprint.end());
  d["footprint"] = fp.empty() ? py::object(py::none()) : py::object(make_points(fp));
  py::list mounts;
  for (const RangeSensorSpec& s : t.robot.sensors)
    mounts.append(py::make_tuple(s.mount.position.x(), s.mount.position.y(), s.mount.theta,
                                 s.min_range, s.max_range));
  d["sensors"] = mounts;
  return d;
}

ScenarioPtr load(const std::string& path, const std::vector<std::string>& overrides) {
  auto s = std::make_shared<PyScenario>();
  {
    py::gil_scoped_release nogil;  // maps can be large
    s->scenario = load_scenario_file(path, overrides);
  }
  s->source = path;
  s->overrides = overrides;
  // The text as loaded, for pickle (read again: load_scenario_file does not hand it out).
  std::ifstream in(path, std::ios::binary);
  s->text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  s->origin = std::filesystem::absolute(path).string();
  return s;
}

ScenarioPtr parse(const std::string& text, const std::string& origin,
                  const std::vector<std::string>& overrides) {
  auto s = std::make_shared<PyScenario>();
  s->scenario = load_scenario_text(text, origin, overrides);
  s->source = origin;
  s->overrides = overrides;
  s->text = text;
  s->origin = std::filesystem::absolute(origin).string();
  return s;
}

// The template `base` on generated floor `seed` of `generator` (a new scenario; the same floor
// as `floornav batch --floors` / `--shared-floors` draws for that seed).
ScenarioPtr generated_floor(const PyScenario& base, const std::string& generator,
                            std::uint64_t seed) {
  if (!base.generator.empty())
    throw py::value_error(fmt::format("scenario '{}' is already generated floor {} of {}",
                                      base.scenario.name, base.floor_seed, base.generator));
  auto s = std::make_shared<PyScenario>(base);
  s->generator = generator;
  s->floor_seed = seed;
  py::gil_scoped_release nogil;
  if (generator == "factory_floor")
    s->scenario = make_generated_floor(base.scenario, seed, base.source);
  else if (generator == "shared_floor")
    s->scenario = make_shared_floor_case(base.scenario, seed, base.source);
  else
    throw std::invalid_argument("unknown floor generator " + generator);
  return s;
}

}  // namespace

// The scenario's fields as pickle keeps them (a Python controller is not among them).
py::tuple scenario_fields(const PyScenario& s) {
  return py::make_tuple(s.text, s.origin, s.source, s.overrides, s.scenario.sim.seed, s.generator,
                        s.floor_seed);
}

ScenarioPtr scenario_of_fields(const py::tuple& t) {
  if (t.size() != 7)
    throw py::value_error(
        "a pickled Scenario is (text, origin, source, overrides, seed, generator, floor seed)");
  auto s = parse(t[0].cast<std::string>(), t[1].cast<std::string>(),
                 t[3].cast<std::vector<std::string>>());
  s->source = t[2].cast<std::string>();
  const auto generator = t[5].cast<std::string>();
  if (!generator.empty()) s = generated_floor(*s, generator, t[6].cast<std::uint64_t>());
  s->scenario.sim.seed = t[4].cast<std::uint64_t>();
  return s;
}

ScenarioPtr with_unpickled_controller(const PyScenario& base, const std::string& kind) {
  auto s = std::make_shared<PyScenario>(base);
  const std::string name = s->scenario.name;
  s->scenario.set_controller(
      kind, [name, kind](const ControllerContext&) -> std::unique_ptr<Controller> {
        throw std::invalid_argument(fmt::format(
            "scenario '{}' came out of a pickled RunResult without its Python controller '{}': "
            "call with_controller again to run it",
            name, kind));
      });
  s->python_controller = true;
  return s;
}

namespace {

// pickle: (text, origin, source, overrides, seed, generator, floor seed); a Python controller is
// not kept.
py::tuple scenario_state(const PyScenario& s) {
  if (s.python_controller)
    throw py::type_error(fmt::format(
        "cannot pickle scenario '{}': it has a Python controller (pickle the scenario before "
        "with_controller, and call with_controller again after loading it)",
        s.scenario.name));
  return scenario_fields(s);
}

ScenarioPtr scenario_of_state(const py::tuple& t) {
  return scenario_of_fields(t);
}

ScenarioPtr with_controller(const PyScenario& base, py::object controller, py::object factory,
                            const std::string& kind) {
  if (controller.is_none() == factory.is_none())
    throw py::value_error("give either a controller or a factory (one per robot)");
  if (kind.empty()) throw py::value_error("a controller kind needs a name");
  auto s = std::make_shared<PyScenario>(base);
  const bool is_factory = !factory.is_none();
  py::object target = is_factory ? factory : controller;
  if (!PyCallable_Check(target.ptr()) && !PyObject_HasAttrString(target.ptr(), "decide"))
    throw py::type_error(fmt::format("{} is neither callable nor has a decide(observation) method",
                                     py::str(py::repr(target)).cast<std::string>()));
  s->scenario.set_controller(kind, make_python_factory(target, is_factory, kind));
  s->python_controller = true;
  return s;
}

}  // namespace

void bind_scenario(py::module_& m) {
  g_input_error = py::reinterpret_steal<py::object>(PyErr_NewExceptionWithDoc(
      "floornav.InputError",
      "Bad input: a scenario file, a map, an override. The message is the line the command-line "
      "tool prints (\"floornav: error: FILE:WHERE: WHAT\"); `file`, `where` and `detail` hold "
      "its parts.",
      PyExc_ValueError, nullptr));
  m.attr("InputError") = g_input_error;
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const OutputError& e) {
      // An output that cannot be written is the system's error, not the input's: OSError.
      PyErr_SetString(PyExc_OSError, e.what());
    } catch (const InputError& e) {
      const std::string line = std::string(kCliPrefix) + e.what();
      py::object exc = g_input_error(line);
      // The parts as the input had them: bytes that are not UTF-8 come back as the surrogate
      // escapes they came in as (os.fsdecode's), never as a UnicodeDecodeError.
      const auto text = [](const std::string& s) {
        return py::reinterpret_steal<py::str>(
            PyUnicode_DecodeUTF8(s.data(), static_cast<Py_ssize_t>(s.size()), "surrogateescape"));
      };
      exc.attr("file") = text(e.file);
      exc.attr("where") = text(e.where);
      exc.attr("detail") = text(e.detail);
      PyErr_SetObject(g_input_error.ptr(), exc.ptr());
    }
  });

  py::class_<PyScenario, std::shared_ptr<PyScenario>>(
      m, "Scenario",
      "A loaded scenario: the world, its robots (body, start, route, controller) and the "
      "simulation settings. Immutable: the with_* methods return changed copies. Make one "
      "with floornav.load_scenario.")
      .def_property_readonly("name", [](const PyScenario& s) { return s.scenario.name; })
      .def_property_readonly(
          "source", [](const PyScenario& s) { return s.source; },
          "The file it was loaded from, as given (a batch line's `source`).")
      .def_property_readonly(
          "overrides", [](const PyScenario& s) { return s.overrides; },
          "The overrides applied, as the CLI's --set KEY=VALUE texts.")
      .def_property_readonly(
          "input_files", [](const PyScenario& s) { return s.scenario.input_files; },
          "Every file read to make it (the scenario file, its map and the map's image, its "
          "people_file), in the order read.")
      .def_property_readonly(
          "_config_yaml", [](const PyScenario& s) { return scenario_to_yaml(s.scenario); },
          "The resolved scenario as YAML (what --config-out writes).")
      .def_property_readonly(
          "is_fleet", [](const PyScenario& s) { return s.scenario.is_fleet(); },
          "True for a `robots:` list (run as a fleet).")
      .def_property_readonly("controller_kind",
                             [](const PyScenario& s) { return s.scenario.robot().controller.kind; })
      .def_property_readonly(
          "python_controller", [](const PyScenario& s) { return s.python_controller; },
          "A Python controller drives its robots (runs hold the GIL).")
      .def_property_readonly("dt", [](const PyScenario& s) { return s.scenario.sim.dt; })
      .def_property_readonly("t_max", [](const PyScenario& s) { return s.scenario.sim.t_max; })
      .def_property_readonly("seed", [](const PyScenario& s) { return s.scenario.sim.seed; })
      .def_property_readonly(
          "robots",
          [](const PyScenario& s) {
            py::list out;
            for (const RobotTask& t : s.scenario.robots) out.append(robot_dict(t));
            return out;
          },
          "Each robot: name, preset, start, goals, controller, body_radius, "
          "max_speed, max_turn_rate, sensor_count, footprint, sensors (x, y, theta, min "
          "range, max range per beam).")
      .def_property_readonly(
          "params", [](const PyScenario& s) { return s.scenario.robot().controller.params; },
          "The first robot's controller parameters, the chapter's keys (a copy).")
      .def_property_readonly(
          "controller", [](const PyScenario& s) { return s.scenario.robot().controller; },
          "The first robot's whole controller section (a copy): kind, the chapter's and the "
          "robot_avoidance keys, the planner, dwa and safety sections.")
      .def_property_readonly(
          "world", [](const PyScenario& s) { return world_dict(*s.scenario.world); },
          "The world: bounds, circles (x, y, r), polygons, segments (n, 4), "
          "extent, grid (occupancy map or None).")
      .def(
          "with_controller",
          [](const PyScenario& s, py::object controller, py::object factory,
             const std::string& kind) { return with_controller(s, controller, factory, kind); },
          py::arg("controller") = py::none(), py::kw_only(), py::arg("factory") = py::none(),
          py::arg("kind") = "python",
          "A copy whose robots are driven by a Python controller: `controller` (a callable "
          "observation -> command, or an object with decide(observation)) for every robot, or "
          "`factory(context) -> controller` called once per robot and run (context: robot, "
          "params, robot_name, robot_index). `kind` names it in summaries (`controller`).")
      .def(
          "with_seed",
          [](const PyScenario& s, const py::object& seed) {
            auto c = std::make_shared<PyScenario>(s);
            c->scenario.sim.seed = to_seed(seed, "seed");
            return c;
          },
          py::arg("seed"), "A copy with another sim.seed (sensor noise).")
      .def(py::pickle(&scenario_state, &scenario_of_state))
      .def("__copy__", [](const ScenarioPtr& s) { return s; })  // immutable: itself
      .def("__deepcopy__", [](const ScenarioPtr& s, py::handle) { return s; })
      .def("__repr__", [](const PyScenario& s) {
        return fmt::format("<floornav.Scenario '{}': {} robot{}, controller {}, dt {} s>",
                           s.scenario.name, s.scenario.robots.size(),
                           s.scenario.robots.size() == 1 ? "" : "s",
                           s.scenario.robot().controller.kind, s.scenario.sim.dt);
      });

  m.def("_load_scenario", &load, py::arg("path"), py::arg("overrides"));
  m.def("_parse_scenario", &parse, py::arg("text"), py::arg("origin"), py::arg("overrides"));
  m.def(
      "_generated_floor",
      [](const ScenarioPtr& base, const std::string& generator, const py::object& seed) {
        return generated_floor(*base, generator, to_seed(seed, "seed"));
      },
      py::arg("template"), py::arg("generator"), py::arg("seed"));
}

}  // namespace floornav::python
