// floornav's generic HybridAutomaton engine (automaton/hybrid_automaton.hpp) with Python flows,
// guards and resets: the input, the memory and the output are any Python objects.

#include <fmt/format.h>
#include <pybind11/stl.h>

#include <stdexcept>
#include <variant>

#include "bindings.hpp"
#include "floornav/automaton/hybrid_automaton.hpp"

namespace floornav::python {

namespace {

using PyAutomaton = HybridAutomaton<py::object, py::object, py::object>;

/// A transition as Python sees it: the engine's, with the guard's name.
struct PyTransition {
  double time{0.0};
  int from{-1};
  int to{-1};
  int edge{-1};
  std::string guard;
};

/// The engine's state plus the transition log of the run.
struct PyState {
  PyAutomaton::State state;
  std::vector<PyTransition> log;
};

/// Builder with modes named as well as numbered (edges may name their modes).
class PyBuilder {
 public:
  int add_mode(const std::string& name, py::object flow, bool terminal) {
    if (!PyCallable_Check(flow.ptr()))
      throw py::type_error(fmt::format("the flow of mode '{}' is not callable", name));
    for (const auto& n : names_)
      if (n == name) throw py::value_error(fmt::format("a mode '{}' exists already", name));
    names_.push_back(name);
    return builder_.add_mode(
        name, [flow](const py::object& in, const py::object& mem) { return flow(in, mem); },
        terminal);
  }

  void add_edge(py::handle from, py::handle to, const std::string& guard_name, py::object guard,
                py::object reset, double min_dwell) {
    builder_.add_edge(mode(from), mode(to), guard_name, wrap_guard(guard_name, guard),
                      wrap_reset(guard_name, reset), min_dwell);
  }

  void add_edge_from_every_mode(py::handle to, const std::string& guard_name, py::object guard,
                                py::object reset) {
    builder_.add_edge_from_every_mode(mode(to), guard_name, wrap_guard(guard_name, guard),
                                      wrap_reset(guard_name, reset));
  }

  void set_initial(py::handle m) { builder_.set_initial(mode(m)); }
  void set_chatter_rule(int switches, double window) {
    if (switches < 1 || !(window > 0.0))
      throw py::value_error("a chatter rule needs switches >= 1 and a window > 0 s");
    builder_.set_chatter_rule(switches, window);
  }

  PyAutomaton build() const {
    try {
      return builder_.build();
    } catch (const std::logic_error& e) {
      throw py::value_error(e.what());
    }
  }

 private:
  int mode(py::handle h) const {
    if (py::isinstance<py::str>(h)) {
      const std::string name = h.cast<std::string>();
      for (std::size_t i = 0; i < names_.size(); ++i)
        if (names_[i] == name) return static_cast<int>(i);
      throw py::value_error(fmt::format("no mode '{}' (add it first)", name));
    }
    return h.cast<int>();  // an unknown index is refused by build()
  }

  static PyAutomaton::Guard wrap_guard(const std::string& name, const py::object& guard) {
    if (!PyCallable_Check(guard.ptr()))
      throw py::type_error(fmt::format("the guard '{}' is not callable", name));
    return [guard](const py::object& in, const py::object& mem) {
      const int truth = PyObject_IsTrue(guard(in, mem).ptr());
      if (truth < 0) throw py::error_already_set();
      return truth != 0;
    };
  }

  // A reset may change the memory in place (and return None) or return the new memory.
  static PyAutomaton::Reset wrap_reset(const std::string& name, const py::object& reset) {
    if (reset.is_none()) return {};
    if (!PyCallable_Check(reset.ptr()))
      throw py::type_error(fmt::format("the reset of '{}' is not callable", name));
    return [reset](const py::object& in, py::object& mem) {
      py::object out = reset(in, mem);
      if (!out.is_none()) mem = std::move(out);
    };
  }

  PyAutomaton::Builder builder_;
  std::vector<std::string> names_;
};

}  // namespace

void bind_automaton(py::module_& m) {
  py::class_<PyTransition>(m, "Transition", "One mode change of a hybrid automaton.")
      .def_readonly("time", &PyTransition::time, "s")
      .def_readonly("from_mode", &PyTransition::from)
      .def_readonly("to_mode", &PyTransition::to)
      .def_readonly("edge", &PyTransition::edge, "index of the edge whose guard fired")
      .def_readonly("guard", &PyTransition::guard, "that edge's guard name")
      .def("__repr__", [](const PyTransition& t) {
        return fmt::format("Transition(time={}, from_mode={}, to_mode={}, edge={}, guard='{}')",
                           t.time, t.from, t.to, t.edge, t.guard);
      });

  py::class_<PyState>(m, "AutomatonState",
                      "Everything that changes while an automaton runs: the mode, the time in "
                      "it, the memory (any Python object, written by resets), the switch count, "
                      "the chatter monitor and the transition log. copy() snapshots it.")
      .def_property_readonly("mode", [](const PyState& s) { return s.state.mode; })
      .def_property_readonly("time_in_mode", [](const PyState& s) { return s.state.time_in_mode; })
      .def_property(
          "memory", [](const PyState& s) { return s.state.memory; },
          [](PyState& s, py::object m) { s.state.memory = std::move(m); })
      .def_property_readonly("switches", [](const PyState& s) { return s.state.switches; })
      .def_property_readonly("chatter_episodes",
                             [](const PyState& s) { return s.state.chatter.episodes; })
      .def_property_readonly("chattering", [](const PyState& s) { return s.state.chatter.active; })
      .def_property_readonly("first_chatter_time",
                             [](const PyState& s) -> py::object {
                               if (s.state.chatter.first_time < 0) return py::none();
                               return py::float_(s.state.chatter.first_time);
                             })
      .def_property_readonly(
          "transitions", [](const PyState& s) { return s.log; },
          "The transition log: every transition taken, in order.")
      .def(
          "copy",
          [](const PyState& s) {
            PyState c = s;
            const py::module_ copy = py::module_::import("copy");
            c.state.memory = copy.attr("deepcopy")(s.state.memory);
            return c;
          },
          "A snapshot (the memory deep-copied).");

  py::class_<PyAutomaton>(
      m, "HybridAutomaton",
      "A validated, frozen hybrid automaton (section 5.3.3): modes with flows, edges with "
      "guards and resets. Step order: step() evaluates the current mode's guards in the order "
      "they were added (an edge only once its min_dwell has passed), takes at most one "
      "transition (reset, mode change, log entry); flow() then gives the mode's output.")
      .def(
          "initial_state",
          [](const PyAutomaton& a, py::object memory) {
            return PyState{a.initial_state(std::move(memory)), {}};
          },
          py::arg("memory") = py::none(), "A fresh state in the initial mode.")
      .def(
          "step",
          [](const PyAutomaton& a, py::object in, PyState& s, double t,
             double dt) -> std::optional<PyTransition> {
            const auto tr = a.step(in, s.state, t, dt);
            if (!tr) return std::nullopt;
            PyTransition p{tr->time, tr->from, tr->to, tr->edge,
                           a.edges()[static_cast<std::size_t>(tr->edge)].guard_name};
            s.log.push_back(p);
            return p;
          },
          py::arg("input"), py::arg("state"), py::arg("t"), py::arg("dt"),
          "At most one guarded transition at time t, after the mode was held dt more seconds. "
          "Returns the Transition taken, or None.")
      .def(
          "flow",
          [](const PyAutomaton& a, py::object in, const PyState& s) { return a.flow(in, s.state); },
          py::arg("input"), py::arg("state"), "The current mode's flow (output).")
      .def(
          "is_terminal",
          [](const PyAutomaton& a, const PyState& s) { return a.is_terminal(s.state); },
          py::arg("state"))
      .def_property_readonly("mode_names",
                             [](const PyAutomaton& a) {
                               std::vector<std::string> n;
                               for (const auto& mo : a.modes()) n.push_back(mo.name);
                               return n;
                             })
      .def_property_readonly(
          "guard_names",
          [](const PyAutomaton& a) {
            std::vector<std::string> n;
            for (const auto& e : a.edges()) n.push_back(e.guard_name);
            return n;
          },
          "Each edge's guard name, by edge index.")
      .def_property_readonly("edges",
                             [](const PyAutomaton& a) {
                               py::list out;
                               for (const auto& e : a.edges()) {
                                 py::dict d;
                                 d["from"] = e.from;
                                 d["to"] = e.to;
                                 d["guard"] = e.guard_name;
                                 d["min_dwell"] = e.min_dwell;
                                 d["has_reset"] = static_cast<bool>(e.reset);
                                 out.append(d);
                               }
                               return out;
                             })
      .def_property_readonly("terminal_modes",
                             [](const PyAutomaton& a) {
                               std::vector<int> t;
                               for (int i = 0; i < a.mode_count(); ++i)
                                 if (a.modes()[static_cast<std::size_t>(i)].terminal)
                                   t.push_back(i);
                               return t;
                             })
      .def("find_mode", &PyAutomaton::find_mode, py::arg("name"), "Index of a mode, or -1.");

  py::class_<PyBuilder>(m, "AutomatonBuilder",
                        "Builds a HybridAutomaton: add modes and edges, set the initial mode, "
                        "build() validates (unknown or unreachable modes, no terminal STOP mode, "
                        "an edge leaving a terminal mode: ValueError) and freezes it.")
      .def(py::init<>())
      .def("add_mode", &PyBuilder::add_mode, py::arg("name"), py::arg("flow"),
           py::arg("terminal") = false,
           "A mode with its flow(input, memory) -> output; returns its index.")
      .def("add_edge", &PyBuilder::add_edge, py::arg("source"), py::arg("target"),
           py::arg("guard_name"), py::arg("guard"), py::arg("reset") = py::none(),
           py::arg("min_dwell") = 0.0,
           "An edge (modes by index or name) with guard(input, memory) -> bool and an optional "
           "reset(input, memory) that changes the memory in place or returns the new memory. "
           "A mode's edges are tried in the order they are added.")
      .def("add_edge_from_every_mode", &PyBuilder::add_edge_from_every_mode, py::arg("target"),
           py::arg("guard_name"), py::arg("guard"), py::arg("reset") = py::none(),
           "The same edge from every non-terminal mode added so far (e.g. any -> STOP).")
      .def("set_initial", &PyBuilder::set_initial, py::arg("mode"))
      .def("set_chatter_rule", &PyBuilder::set_chatter_rule, py::arg("switches"), py::arg("window"),
           "`switches` transitions within `window` seconds count as a chatter (Zeno) episode.")
      .def("build", &PyBuilder::build);
}

}  // namespace floornav::python
