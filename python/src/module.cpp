// The `_floornav` extension module: floornav's C++ library for Python. The package `floornav`
// (python/floornav/__init__.py) wraps it; users import that.

#include "bindings.hpp"

PYBIND11_MODULE(_floornav, m) {
  using namespace floornav::python;
  m.doc() = "floornav's C++ core (use the floornav package).";
  m.attr("__version__") = FLOORNAV_VERSION;
  bind_behaviours(m);  // NavigationParams first: the others hand them out
  bind_automaton(m);
  bind_controllers(m);
  bind_scenario(m);
  bind_run(m);
  bind_simulation(m);
  bind_vec_env(m);
  bind_parallel_env(m);
}
