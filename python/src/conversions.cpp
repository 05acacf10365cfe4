// Conversions between floornav's C++ values and Python objects.

#include <fmt/format.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "bindings.hpp"
#include "floornav/core/input_error.hpp"
#include "floornav/kinematics/differential_drive.hpp"

namespace floornav::python {

PyRef::PyRef(py::object o)
    : object_(new py::object(std::move(o)), [](py::object* p) {
        // The last copy may be dropped on a worker thread: take the GIL to release the object.
        if (Py_IsInitialized()) {
          py::gil_scoped_acquire gil;
          delete p;
        } else {
          p->release();  // the interpreter is gone; nothing left to release into
          delete p;
        }
      }) {}

py::object json_to_python(const nlohmann::ordered_json& j) {
  using V = nlohmann::ordered_json::value_t;
  switch (j.type()) {
    case V::null:
    case V::discarded:
      return py::none();
    case V::boolean:
      return py::bool_(j.get<bool>());
    case V::number_integer:
      return py::int_(j.get<std::int64_t>());
    case V::number_unsigned:
      return py::int_(j.get<std::uint64_t>());
    case V::number_float:
      return py::float_(j.get<double>());
    case V::string:
      return py::str(j.get_ref<const std::string&>());
    case V::array: {
      py::list out(j.size());
      std::size_t i = 0;
      for (const auto& item : j) out[i++] = json_to_python(item);
      return out;
    }
    case V::object: {
      py::dict out;
      for (const auto& [k, v] : j.items()) out[py::str(k)] = json_to_python(v);
      return out;
    }
    case V::binary:
      break;
  }
  return py::none();
}

namespace {
bool is_number(py::handle h) {
  return PyFloat_Check(h.ptr()) || (PyLong_Check(h.ptr()) && !PyBool_Check(h.ptr())) ||
         py::isinstance<py::float_>(h) || PyObject_HasAttrString(h.ptr(), "__float__") != 0;
}

double number(py::handle h, const char* what) {
  if (PyFloat_Check(h.ptr())) return PyFloat_AS_DOUBLE(h.ptr());
  if (PyBool_Check(h.ptr()) || !is_number(h))
    throw py::value_error(fmt::format("{}: expected a number, got {}", what,
                                      py::str(py::repr(h)).cast<std::string>()));
  const double v = PyFloat_AsDouble(h.ptr());
  if (v == -1.0 && PyErr_Occurred()) throw py::error_already_set();
  return v;
}

Vec2 pair_of(py::handle h, const char* what, bool* ok) {
  *ok = false;
  if (PyTuple_Check(h.ptr()) && PyTuple_GET_SIZE(h.ptr()) == 2) {
    *ok = true;
    return {number(PyTuple_GET_ITEM(h.ptr(), 0), what), number(PyTuple_GET_ITEM(h.ptr(), 1), what)};
  }
  if (PyList_Check(h.ptr()) && PyList_GET_SIZE(h.ptr()) == 2) {
    *ok = true;
    return {number(PyList_GET_ITEM(h.ptr(), 0), what), number(PyList_GET_ITEM(h.ptr(), 1), what)};
  }
  if (py::isinstance<py::array>(h)) {
    const auto a = py::reinterpret_borrow<py::array>(h);
    if (a.ndim() == 1 && a.shape(0) == 2 &&
        (a.dtype().kind() == 'f' || a.dtype().kind() == 'i' || a.dtype().kind() == 'u')) {
      const auto d = py::array_t<double, py::array::forcecast>::ensure(h);
      *ok = true;
      return {d.at(0), d.at(1)};
    }
  }
  return Vec2::Zero();
}
}  // namespace

Vec2 to_vec2(py::handle h, const char* what) {
  bool ok = false;
  const Vec2 v = pair_of(h, what, &ok);
  if (!ok)
    throw py::value_error(fmt::format("{}: expected two numbers (x, y), got {}", what,
                                      py::str(py::repr(h)).cast<std::string>()));
  return v;
}

namespace {
[[noreturn]] void bad_command(py::handle h) {
  throw py::value_error(fmt::format(
      "a command is (v, omega), {{'v': v, 'omega': omega}}, {{'u': (ux, uy)}}, "
      "{{'wheels': (left, right)}}, {{'goal_reached': True}} or a floornav.Command; got {}",
      py::str(py::repr(h)).cast<std::string>()));
}

Command checked(const Command& c, py::handle h) {
  if (!c.is_finite())
    throw py::value_error(fmt::format("the command {} is not finite (NaN or infinity)",
                                      py::str(py::repr(h)).cast<std::string>()));
  return c;
}
}  // namespace

Command to_command(py::handle h) {
  bool ok = false;
  const Vec2 vw = pair_of(h, "command", &ok);  // the common case first: (v, omega)
  if (ok) return checked(Command::unicycle(vw.x(), vw.y()), h);
  if (py::isinstance<Command>(h)) return checked(h.cast<Command>(), h);
  if (PyDict_Check(h.ptr())) {
    const auto d = py::reinterpret_borrow<py::dict>(h);
    auto only = [&](std::initializer_list<const char*> keys) {
      if (d.size() != keys.size()) bad_command(h);
      for (const char* k : keys)
        if (!d.contains(k)) bad_command(h);
    };
    if (d.contains("v") || d.contains("omega")) {
      only({"v", "omega"});
      return checked(
          Command::unicycle(number(d["v"], "command v"), number(d["omega"], "command omega")), h);
    }
    if (d.contains("u")) {
      only({"u"});
      return checked(Command::velocity(to_vec2(d["u"], "command u")), h);
    }
    if (d.contains("wheels")) {
      only({"wheels"});
      const Vec2 w = to_vec2(d["wheels"], "command wheels");
      return checked(Command::wheels(w.x(), w.y()), h);
    }
    if (d.contains("goal_reached")) {
      only({"goal_reached"});
      if (!py::bool_(d["goal_reached"]))
        throw py::value_error("{'goal_reached': False} asks for nothing: give a motion command");
      return Command::goal_reached();
    }
  }
  bad_command(h);
}

std::span<const Vec2> to_points(py::handle h, std::vector<Vec2>& storage, const char* what) {
  static_assert(sizeof(Vec2) == 2 * sizeof(double));
  if (h.is_none()) return {};
  py::array_t<double, py::array::c_style | py::array::forcecast> a;
  try {
    a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(h);
  } catch (const py::error_already_set&) {
    a = {};
  }
  const bool pairs = a && a.ndim() == 2 && a.shape(1) == 2;
  const bool empty = a && a.ndim() == 1 && a.shape(0) == 0;
  if (!pairs && !empty) {
    PyErr_Clear();
    throw py::value_error(fmt::format("{}: expected an array of shape (k, 2), got {}", what,
                                      py::str(py::repr(h)).cast<std::string>()));
  }
  const std::size_t k = a.ndim() == 2 ? static_cast<std::size_t>(a.shape(0)) : 0;
  const double* data = a.data();
  // A view only when the array outlives the call: `a` may be a converted temporary.
  const bool same = a.ptr() == h.ptr();
  if (same && reinterpret_cast<std::uintptr_t>(data) % alignof(Vec2) == 0)
    return {reinterpret_cast<const Vec2*>(data), k};
  storage.resize(k);
  for (std::size_t i = 0; i < k; ++i) storage[i] = Vec2(data[2 * i], data[2 * i + 1]);
  return {storage.data(), k};
}

py::array new_float_array(std::initializer_list<py::ssize_t> shape) {
  // Straight through NumPy's C API: py::array_t's constructor builds shape and stride vectors
  // and looks the dtype up on every call, which costs more than the data in an observation.
  const auto& api = py::detail::npy_api::get();
  PyObject* descr = api.PyArray_DescrFromType_(py::detail::npy_api::NPY_DOUBLE_);
  if (!descr) throw py::error_already_set();
  std::array<Py_intptr_t, 3> dims{};
  std::size_t nd = 0;
  for (py::ssize_t d : shape) dims[nd++] = d;
  PyObject* a = api.PyArray_NewFromDescr_(api.PyArray_Type_, descr, static_cast<int>(nd),
                                          dims.data(), nullptr, nullptr, 0, nullptr);
  if (!a) throw py::error_already_set();
  return py::reinterpret_steal<py::array>(a);
}

py::array_t<double> make_array(std::span<const double> values) {
  py::array a = new_float_array({static_cast<py::ssize_t>(values.size())});
  if (!values.empty()) std::memcpy(a.mutable_data(), values.data(), values.size_bytes());
  return py::reinterpret_steal<py::array_t<double>>(a.release());
}

py::array_t<double> make_points(std::span<const Vec2> points) {
  py::array a = new_float_array({static_cast<py::ssize_t>(points.size()), py::ssize_t{2}});
  auto* out = static_cast<double*>(a.mutable_data());
  for (std::size_t i = 0; i < points.size(); ++i) {
    out[2 * i] = points[i].x();
    out[2 * i + 1] = points[i].y();
  }
  return py::reinterpret_steal<py::array_t<double>>(a.release());
}

const DictKeys& dict_keys() {
  static const DictKeys* k = new DictKeys();  // leaked on purpose: interned for the process's life
  return *k;
}

void set_item(PyObject* dict, PyObject* key, PyObject* value) {
  if (!value) throw py::error_already_set();
  const int rc = PyDict_SetItem(dict, key, value);
  Py_DECREF(value);
  if (rc != 0) throw py::error_already_set();
}

void beam_points(const Observation& obs, double* out) {
  for (std::size_t j = 0; j < obs.beams.size(); ++j) {
    const Vec2 p = obs.beams[j].origin + obs.ranges[j] * obs.beams[j].dir;
    out[2 * j] = p.x();
    out[2 * j + 1] = p.y();
  }
}

py::dict observation_dict(const Observation& obs, std::string_view status, py::handle robot,
                          py::handle params) {
  const DictKeys& k = dict_keys();
  py::dict d;
  PyObject* p = d.ptr();
  set_item(p, k.t, PyFloat_FromDouble(obs.t));
  set_item(p, k.dt, PyFloat_FromDouble(obs.dt));
  py::array pose = new_float_array({3});
  auto* x = static_cast<double*>(pose.mutable_data());
  x[0] = obs.pose.position.x();
  x[1] = obs.pose.position.y();
  x[2] = obs.pose.theta;
  set_item(p, k.pose, pose.release().ptr());
  py::array goal = new_float_array({2});
  auto* g = static_cast<double*>(goal.mutable_data());
  g[0] = obs.goal.x();
  g[1] = obs.goal.y();
  set_item(p, k.goal, goal.release().ptr());
  set_item(p, k.goal_index, PyLong_FromLong(obs.goal_index));
  set_item(p, k.goal_count, PyLong_FromLong(obs.goal_count));
  set_item(p, k.ranges, make_array(obs.ranges).release().ptr());
  py::array points = new_float_array({static_cast<py::ssize_t>(obs.beams.size()), 2});
  beam_points(obs, static_cast<double*>(points.mutable_data()));
  set_item(p, k.points, points.release().ptr());
  set_item(p, k.obstacles, make_points(obs.points).release().ptr());
  set_item(p, k.sensed, make_points(obs.sensed).release().ptr());
  set_item(p, k.status,
           PyUnicode_FromStringAndSize(status.data(), static_cast<Py_ssize_t>(status.size())));
  if (robot) set_item(p, k.robot, py::reinterpret_borrow<py::object>(robot).release().ptr());
  if (params) set_item(p, k.params, py::reinterpret_borrow<py::object>(params).release().ptr());
  return d;
}

std::string_view status_name(bool finished, RunStatus status) {
  return finished ? to_string(status) : std::string_view("running");
}

py::object robot_info(const RobotSpec& r, std::string_view name) {
  py::dict d;
  d["name"] = std::string(name);
  d["preset"] = r.preset;
  d["body_radius"] = r.body_radius;
  d["wheel_radius"] = r.drive.wheel_radius;
  d["track_width"] = r.drive.track_width;
  d["max_wheel_speed"] = r.drive.max_wheel_speed;
  d["max_speed"] = max_forward_speed(r.drive);
  d["max_turn_rate"] = max_turn_rate(r.drive);
  d["sensor_count"] = r.sensors.size();
  std::vector<Vec2> fp(r.footprint.begin(), r.footprint.end());
  d["footprint"] = fp.empty() ? py::object(py::none()) : py::object(make_points(fp));
  py::list mounts;
  for (const RangeSensorSpec& s : r.sensors)
    mounts.append(py::make_tuple(s.mount.position.x(), s.mount.position.y(), s.mount.theta,
                                 s.min_range, s.max_range));
  d["sensors"] = mounts;
  const py::module_ types = py::module_::import("types");
  return types.attr("SimpleNamespace")(**d);
}

std::uint64_t to_seed(py::handle h, const char* what) {
  const bool integer =
      PyLong_Check(h.ptr()) || py::isinstance(h, py::module_::import("numbers").attr("Integral"));
  if (!integer || PyBool_Check(h.ptr()))
    throw py::value_error(fmt::format("{} must be a non-negative integer, got {}", what,
                                      py::repr(h).cast<std::string>()));
  const py::int_ v = py::reinterpret_borrow<py::object>(h);
  int overflow = 0;
  const long long small = PyLong_AsLongLongAndOverflow(v.ptr(), &overflow);
  if (overflow < 0 || (overflow == 0 && small < 0))
    throw py::value_error(fmt::format("{} must be a non-negative integer, got {}", what,
                                      py::repr(h).cast<std::string>()));
  const unsigned long long out = PyLong_AsUnsignedLongLong(v.ptr());
  if (out == static_cast<unsigned long long>(-1) && PyErr_Occurred()) {
    PyErr_Clear();
    throw py::value_error(
        fmt::format("{} must be below 2**64, got {}", what, py::repr(h).cast<std::string>()));
  }
  return static_cast<std::uint64_t>(out);
}

}  // namespace floornav::python
