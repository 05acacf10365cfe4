#include "floornav/ompl/rrt_connect.hpp"

#include <dlfcn.h>

#include <mutex>
#include <stdexcept>
#include <string>

#include "floornav/nav/planner_params.hpp"
#include "floornav/nav/sampling_planner.hpp"

namespace floornav {

namespace {

// libompl brings Boost and ODE: loading and relocating them costs every process ~8 ms, about a
// third of a whole `floornav run`. So OMPL lives in a module (rrt_connect_module.cpp) that is
// loaded on the first search, not linked.
constexpr const char* kModule = "libfloornav_rrt_connect.so";

using ModuleAbi = const char* (*)();

// The directory of the program or shared object this code is linked into, with a trailing '/'.
std::string own_directory() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<const void*>(&own_directory), &info) == 0 || !info.dli_fname)
    return {};
  const std::string file = info.dli_fname;
  const std::size_t slash = file.rfind('/');
  return slash == std::string::npos ? std::string() : file.substr(0, slash + 1);
}

// Opens `path` and returns its search if it is the module of this very build; else nullptr,
// with why appended to `tried`.
SampledPathSearch open_module(const std::string& path, std::string& tried) {
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    tried += "\n  " + path + ": " + (why ? why : "cannot be loaded");
    return nullptr;
  }
  const auto abi = reinterpret_cast<ModuleAbi>(dlsym(handle, "floornav_rrt_connect_abi"));
  const auto search =
      reinterpret_cast<SampledPathSearch>(dlsym(handle, "floornav_rrt_connect_search"));
  if (abi && search && std::string(abi()) == FLOORNAV_RRT_CONNECT_ABI) return search;
  tried += "\n  " + path + ": " +
           (abi && search
                ? "built from floornav " + std::string(abi()) + ", not " + FLOORNAV_RRT_CONNECT_ABI
                : std::string("not floornav's rrt_connect module"));
  dlclose(handle);
  return nullptr;
}

// The module, in this order: beside this program or shared object (the Python package, the
// build tree's tool), then by its name alone, on this program's run path (set by floornav's
// CMake package and build tree, and by the installed tool's $ORIGIN) and LD_LIBRARY_PATH. The
// first one of this very build is taken.
SampledPathSearch load_module() {
  std::string tried;
  const std::string own = own_directory();
  if (!own.empty())
    if (const SampledPathSearch search = open_module(own + kModule, tried)) return search;
  if (const SampledPathSearch search = open_module(kModule, tried)) return search;
  throw std::runtime_error(std::string("rrt_connect: cannot load OMPL's planner module ") +
                           kModule + " of floornav " + FLOORNAV_RRT_CONNECT_ABI +
                           "; tried:" + tried);
}

SampledPathSearch module_search() {
  static std::once_flag once;
  static SampledPathSearch search = nullptr;
  std::call_once(once, [] { search = load_module(); });  // a throw leaves it to the next call
  return search;
}

}  // namespace

bool rrt_connect_path(const FreeRaster& raster, GridCell start, GridCell goal, std::uint64_t seed,
                      int max_samples, std::vector<Vec2>& out) {
  out.clear();
  if (max_samples > kMaxRrtConnectSamples)
    throw std::invalid_argument("rrt_connect_path: max_samples " + std::to_string(max_samples) +
                                " is above the limit of " + std::to_string(kMaxRrtConnectSamples) +
                                " samples a plan");
  if (!raster.is_free(start.x, start.y) || !raster.is_free(goal.x, goal.y) || max_samples < 1)
    return false;
  if (start == goal) {  // no search: OMPL is not loaded for it
    out.assign({Vec2(start.x + 0.5, start.y + 0.5), Vec2(goal.x + 0.5, goal.y + 0.5)});
    return true;
  }
  return module_search()(raster, start, goal, seed, max_samples, out);
}

}  // namespace floornav

// A program that links floornav::ompl has the rrt_connect planner, installed before main(). The
// link option -u floornav_ompl_rrt_connect in floornav::ompl's interface makes the linker take
// this file out of the static library although no code names it.
extern "C" {
extern const bool floornav_ompl_rrt_connect;
const bool floornav_ompl_rrt_connect =
    (floornav::set_rrt_connect_search(&floornav::rrt_connect_path), true);
}
