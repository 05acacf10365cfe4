#pragma once
// A floornav Controller whose decisions come from Python: a callable (observation -> command) or
// an object with decide(observation), and optionally reset(), mode, mode_names, guard_names.

#include <string>
#include <vector>

#include "bindings.hpp"
#include "floornav/nav/controller.hpp"

namespace floornav::python {

/// What a Python controller may return besides a plain command: the command with the mode it
/// is in and the guard that fired (each an index into mode_names / guard_names, or a name).
struct PyDecision {
  Command command{Command::goal_reached()};
  py::object mode;   ///< None: the controller's current mode
  py::object guard;  ///< None: no guard fired
};

class PyController final : public Controller {
 public:
  /// `target` is the callable or controller object; `robot` and `params` are handed to it in
  /// every observation. Takes the GIL itself.
  PyController(py::object target, std::vector<std::string> mode_names,
               std::vector<std::string> guard_names, py::object robot, py::object params);
  ~PyController() override;

  Decision decide(const Observation& obs) override;
  void reset() override;
  int mode() const override;

  /// The mode and guard names a Python controller object declares (mode_names, guard_names),
  /// with `kind` as the one mode of a plain function.
  static std::vector<std::string> declared_modes(py::handle target, const std::string& kind);
  static std::vector<std::string> declared_guards(py::handle target);

 private:
  int mode_index(py::handle mode) const;
  int guard_index(py::handle guard) const;

  py::object target_;
  py::object decide_;
  py::object reset_;
  py::object robot_;
  py::object params_;
  bool has_mode_{false};
  int last_mode_{0};
};

/// A ControllerFactory that makes a PyController per robot: from `factory(context)` when
/// `is_factory`, else around `controller` itself (the same object for every robot).
ControllerFactory make_python_factory(py::object callable, bool is_factory, std::string kind);

}  // namespace floornav::python
