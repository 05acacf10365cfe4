#pragma once
// Shared pieces of the `_floornav` extension: the Python-side scenario, conversions between
// floornav's C++ values and Python objects, and the bind_* functions of each file.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "floornav/geometry/vec2.hpp"
#include "floornav/nav/controller.hpp"
#include "floornav/runner/run_summary.hpp"
#include "floornav/scenario/scenario.hpp"
#include "floornav/sim/fleet_simulation.hpp"
#include "floornav/sim/run_result.hpp"

namespace floornav::python {

namespace py = pybind11;

/// A scenario as Python holds it: the C++ scenario, where it came from (a batch line's `source`),
/// and whether a Python controller drives one of its robots (such runs hold the GIL per step, so
/// batches and vector environments run them on one thread).
struct PyScenario {
  Scenario scenario;
  std::string source;
  std::vector<std::string> overrides;  ///< as given, "key=value"
  bool python_controller{false};
  // What pickle keeps: the YAML text as read and where it was read from (an absolute path, which
  // anchors the relative paths in it), from which load_scenario_text rebuilds the scenario.
  std::string text;
  std::string origin;
  // A generated floor: the scenario of `text` as template on floor `floor_seed` of `generator`
  // ("factory_floor" or "shared_floor"), made again from them by pickle; empty when as read.
  std::string generator;
  std::uint64_t floor_seed{0};
};
using ScenarioPtr = std::shared_ptr<PyScenario>;  // never changed once made

/// A finished run, of one robot or of a fleet, with the scenario it came from.
struct PyRunResult {
  ScenarioPtr scenario;
  std::optional<RunResult> run;
  std::optional<FleetResult> fleet;
  py::object summary;  ///< built on first use
  /// What the summary and write() add to the run (the grid optimum): computed once, on first use.
  std::optional<RunContext> context;
  py::object trajectory;  ///< built on first use
};

/// A Python object that may be copied and dropped without the GIL (inside std::function objects
/// that C++ worker threads copy): its reference count is touched only under the GIL.
class PyRef {
 public:
  PyRef() = default;
  explicit PyRef(py::object o);
  const py::object& get() const { return *object_; }
  explicit operator bool() const { return object_ && *object_; }

 private:
  std::shared_ptr<py::object> object_;
};

// --- conversions ----------------------------------------------------------------------------

/// nlohmann JSON -> dict / list / float / int / bool / str / None (key order kept).
py::object json_to_python(const nlohmann::ordered_json& j);

/// Two numbers (a tuple, a list, a numpy array of shape (2,)) -> Vec2; ValueError naming `what`
/// otherwise.
Vec2 to_vec2(py::handle h, const char* what);

/// A seed: a Python int (not a bool) in [0, 2^64); anything else, a float, a negative number or
/// one of 2^64 or more, is a ValueError naming `what` (never pybind11's TypeError about
/// "incompatible function arguments", nor an OverflowError).
std::uint64_t to_seed(py::handle h, const char* what);
inline py::tuple vec2_tuple(const Vec2& v) {
  return py::make_tuple(v.x(), v.y());
}

/// A command from Python: (v, omega), {"v":, "omega":}, {"u": (ux, uy)}, {"wheels": (l, r)},
/// {"goal_reached": True}, or a floornav.Command. ValueError for anything else, and for a
/// command that is not finite.
Command to_command(py::handle h);

/// Points (k, 2) as floornav's Vec2 span: a view of a C-contiguous float64 array when it is
/// aligned for Vec2, else a copy into `storage`.
std::span<const Vec2> to_points(py::handle h, std::vector<Vec2>& storage, const char* what);

/// The keys of the observation and info dicts (Simulation, Python controllers, ParallelEnv),
/// interned once for the process's life.
struct DictKeys {
  PyObject* t = PyUnicode_InternFromString("t");
  PyObject* dt = PyUnicode_InternFromString("dt");
  PyObject* pose = PyUnicode_InternFromString("pose");
  PyObject* goal = PyUnicode_InternFromString("goal");
  PyObject* goal_index = PyUnicode_InternFromString("goal_index");
  PyObject* goal_count = PyUnicode_InternFromString("goal_count");
  PyObject* ranges = PyUnicode_InternFromString("ranges");
  PyObject* points = PyUnicode_InternFromString("points");
  PyObject* obstacles = PyUnicode_InternFromString("obstacles");
  PyObject* sensed = PyUnicode_InternFromString("sensed");
  PyObject* status = PyUnicode_InternFromString("status");
  PyObject* robot = PyUnicode_InternFromString("robot");
  PyObject* params = PyUnicode_InternFromString("params");
  PyObject* goals_reached = PyUnicode_InternFromString("goals_reached");
  PyObject* progress = PyUnicode_InternFromString("progress");
  /// RunStatus's names after "running", in status_code.hpp's order.
  std::array<PyObject*, 5> status_names{
      PyUnicode_InternFromString("running"), PyUnicode_InternFromString("reached"),
      PyUnicode_InternFromString("collision"), PyUnicode_InternFromString("timeout"),
      PyUnicode_InternFromString("stuck")};
};
const DictKeys& dict_keys();

/// dict[key] = value, stealing `value`; a null `value` (a failed Python call) raises its error.
void set_item(PyObject* dict, PyObject* key, PyObject* value);

/// A new uninitialised float64 array of `shape` (at most 3 dimensions).
py::array new_float_array(std::initializer_list<py::ssize_t> shape);
py::array_t<double> make_array(std::span<const double> values);
py::array_t<double> make_points(std::span<const Vec2> points);

/// Where each beam of `obs` ends in the world frame, (x, y) per beam into `out`: its return, or
/// the end of its range when it saw nothing (observations' `points`).
void beam_points(const Observation& obs, double* out);

/// The observation dict of Simulation.observe() and of Python controllers: the fields every
/// observation has (t, pose, goal, goal_index, ranges, points) and the extras (dt, goal_count,
/// obstacles, sensed, status, robot, params).
py::dict observation_dict(const Observation& obs, std::string_view status, py::handle robot,
                          py::handle params);

/// A Python view of a robot's body (name, preset, body radius, footprint, sensors, limits).
py::object robot_info(const RobotSpec& robot, std::string_view name);

/// "running" or the run's status.
std::string_view status_name(bool finished, RunStatus status);

// --- pickle ----------------------------------------------------------------------------------

/// A scenario's fields as pickle keeps them (text, origin, source, overrides, seed, generator,
/// floor seed) and the scenario made again from them; a Python controller is not among them.
py::tuple scenario_fields(const PyScenario& s);
ScenarioPtr scenario_of_fields(const py::tuple& t);
/// A copy of `base` whose controller, reported as `kind`, was a Python controller that pickle did
/// not keep: running it raises ValueError saying so.
ScenarioPtr with_unpickled_controller(const PyScenario& base, const std::string& kind);

/// A result's data (run or fleet run, the summary's context once computed unless `with_context`
/// is false) as CBOR bytes, every
/// value bit for bit; load_run_result_data fills a result from them (ValueError if unreadable).
py::bytes run_result_data(const PyRunResult& r, bool with_context = true);
void load_run_result_data(PyRunResult& r, const py::bytes& data);

// --- bind_* (one per file) -------------------------------------------------------------------

void bind_behaviours(py::module_& m);
void bind_automaton(py::module_& m);
void bind_controllers(py::module_& m);
void bind_scenario(py::module_& m);
void bind_run(py::module_& m);
void bind_simulation(py::module_& m);
void bind_vec_env(py::module_& m);
void bind_parallel_env(py::module_& m);

}  // namespace floornav::python
