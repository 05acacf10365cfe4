// Whole runs and batches: floornav.run (summary, trajectory, transition log) and floornav.batch
// (the CLI's results.jsonl lines, on all cores with the GIL released).

#include <fmt/format.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>
#include <tuple>

#include "bindings.hpp"
#include "floornav/io/atomic_file.hpp"
#include "floornav/io/summary_json.hpp"
#include "floornav/render/palette.hpp"
#include "floornav/runner/batch.hpp"
#include "floornav/runner/run_outputs.hpp"
#include "floornav/runner/run_summary.hpp"
#include "floornav/scenario/simulate.hpp"

namespace floornav::python {

using namespace pybind11::literals;

namespace {

std::vector<const RunResult*> runs_of(const PyRunResult& r) {
  std::vector<const RunResult*> out;
  if (r.run) out.push_back(&*r.run);
  if (r.fleet)
    for (const RunResult& x : r.fleet->robots) out.push_back(&x);
  return out;
}

// What the CLI's `run` puts in a summary besides the run: the --set values and the grid optimum,
// computed once per result (the summary and write() both use it). Called with the GIL held; the
// optimum is computed without it.
const RunContext& context_of(PyRunResult& r) {
  if (!r.context) {
    RunContext context;
    context.overrides = r.scenario->overrides;
    {
      py::gil_scoped_release nogil;
      context.optimum = compute_optimum(r.scenario->scenario);
    }
    if (!r.context) r.context = std::move(context);  // unless another thread set it meanwhile
  }
  return *r.context;
}

py::object make_summary(PyRunResult& r) {
  if (!r.summary) {
    const RunContext& context = context_of(r);
    nlohmann::ordered_json j;
    {
      py::gil_scoped_release nogil;
      j = r.run ? run_summary(r.scenario->scenario, *r.run, context)
                : fleet_run_summary(r.scenario->scenario, *r.fleet, context);
    }
    r.summary = json_to_python(j);
  }
  return r.summary;
}

// The trajectory.csv columns as arrays: t, x, y, theta, v, omega, w_left, w_right (float64),
// mode (str); a fleet's robot after robot with a `robot` column (str), as in its CSV.
py::object make_trajectory(PyRunResult& r) {
  if (r.trajectory) return r.trajectory;
  const auto runs = runs_of(r);
  std::size_t n = 0;
  for (const RunResult* x : runs) n += x->trajectory.size();
  const auto size = static_cast<py::ssize_t>(n);
  constexpr int kColumns = 8;
  std::array<py::array_t<double>, kColumns> cols;
  std::array<double*, kColumns> out{};
  for (int c = 0; c < kColumns; ++c) {
    cols[static_cast<std::size_t>(c)] = py::array_t<double>(size);
    out[static_cast<std::size_t>(c)] = cols[static_cast<std::size_t>(c)].mutable_data();
  }
  py::array_t<std::int64_t> mode_id(size);
  py::array_t<std::int64_t> robot_id(size);
  std::int64_t* mid = mode_id.mutable_data();
  std::int64_t* rid = robot_id.mutable_data();
  // Names of every robot's modes in one table (robots of a fleet may differ in controller).
  std::vector<std::string> names;
  std::size_t k = 0;
  for (std::size_t ri = 0; ri < runs.size(); ++ri) {
    const RunResult& x = *runs[ri];
    std::vector<std::int64_t> local;
    for (std::size_t m = 0; m < x.mode_names.size(); ++m) {
      auto it = std::find(names.begin(), names.end(), x.mode_names[m]);
      if (it == names.end()) {
        names.push_back(x.mode_names[m]);
        it = names.end() - 1;
      }
      local.push_back(it - names.begin());
    }
    for (const TrajectorySample& s : x.trajectory) {
      out[0][k] = s.t;
      out[1][k] = s.x;
      out[2][k] = s.y;
      out[3][k] = s.theta;
      out[4][k] = s.v;
      out[5][k] = s.omega;
      out[6][k] = s.w_left;
      out[7][k] = s.w_right;
      std::int64_t id;
      if (s.mode >= 0 && static_cast<std::size_t>(s.mode) < local.size()) {
        id = local[static_cast<std::size_t>(s.mode)];
      } else {  // as trajectory_to_csv spells a mode without a name
        const std::string name = "mode_" + std::to_string(s.mode);
        auto it = std::find(names.begin(), names.end(), name);
        if (it == names.end()) {
          names.push_back(name);
          it = names.end() - 1;
        }
        id = it - names.begin();
      }
      mid[k] = id;
      rid[k] = static_cast<std::int64_t>(ri);
      ++k;
    }
  }
  const py::module_ np = py::module_::import("numpy");
  py::dict d;
  const char* keys[kColumns] = {"t", "x", "y", "theta", "v", "omega", "w_left", "w_right"};
  for (int c = 0; c < kColumns; ++c) d[keys[c]] = cols[static_cast<std::size_t>(c)];
  py::list name_list;
  for (const auto& s : names) name_list.append(s);
  if (names.empty()) name_list.append("");
  d["mode"] = np.attr("array")(name_list, "dtype"_a = "str")[mode_id];
  if (r.fleet) {
    py::list robot_names;
    for (const RunResult* x : runs) robot_names.append(x->scenario);
    if (runs.empty()) robot_names.append("");
    d["robot"] = np.attr("array")(robot_names, "dtype"_a = "str")[robot_id];
  }
  r.trajectory = d;
  return d;
}

py::list transitions_of(const RunResult& r) {
  py::list out;
  auto name = [](const std::vector<std::string>& names, int i, const char* fallback) {
    return i >= 0 && static_cast<std::size_t>(i) < names.size()
               ? names[static_cast<std::size_t>(i)]
               : std::string(fallback) + std::to_string(i);
  };
  for (std::size_t i = 0; i < r.transitions.size(); ++i) {
    const Transition& tr = r.transitions[i];
    py::dict t;
    t["t"] = tr.time;
    t["from"] = name(r.mode_names, tr.from, "mode_");
    t["to"] = name(r.mode_names, tr.to, "mode_");
    if (tr.edge >= 0)
      t["guard"] = name(r.guard_names, tr.edge, "edge_");
    else
      t["guard"] = py::none();  // a mode change no guard made (as summary.json's null)
    t["x"] = i < r.transition_x.size() ? r.transition_x[i] : std::nan("");
    t["y"] = i < r.transition_y.size() ? r.transition_y[i] : std::nan("");
    out.append(t);
  }
  return out;
}

// Ctrl-C is looked at every this many steps of a run (a few milliseconds of simulation).
constexpr int kStepsBetweenSignalChecks = 4096;

// Raises KeyboardInterrupt (or what a signal handler raised) once one is pending; called
// without the GIL.
void check_signals() {
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();
}

// As run_timed / run_fleet_timed (the same simulation, the same result), in pieces between which
// a pending Ctrl-C stops the run.
std::shared_ptr<PyRunResult> run(const ScenarioPtr& s, int threads, bool mcap) {
  // For a bag, the run records the trajectory and the sensor ranges (prepare_outputs); the
  // result keeps the scenario as given.
  std::optional<Scenario> prepared;
  if (mcap) {
    prepared = s->scenario;
    prepare_outputs(*prepared, OutputSelection{.mcap = true});
  }
  const Scenario& scenario = prepared ? *prepared : s->scenario;
  check_recording_limits(scenario, s->source);  // as the command line: before it starts
  auto r = std::make_shared<PyRunResult>();
  r->scenario = s;
  {
    py::gil_scoped_release nogil;  // a Python controller takes it back per step
    const auto t0 = std::chrono::steady_clock::now();
    const auto elapsed = [&] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    };
    if (scenario.is_fleet()) {
      FleetSimulation fleet = make_fleet_simulation(scenario);
      const int n = s->python_controller ? 1 : threads;
      while (fleet.run_steps(kStepsBetweenSignalChecks / 16, n) > 0 && !fleet.finished())
        check_signals();
      r->fleet = fleet.take_result();
      r->fleet->wall_time = elapsed();
    } else {
      Simulation sim = make_simulation(scenario);
      for (int k = 1; sim.step(); ++k)
        if (k % kStepsBetweenSignalChecks == 0) check_signals();
      r->run = sim.result();
      r->run->wall_time = elapsed();
    }
  }
  return r;
}

void write_outputs(PyRunResult& r, const std::filesystem::path& dir, bool mcap) {
  const RunContext& context = context_of(r);
  OutputSelection which;
  which.mcap = mcap;
  py::gil_scoped_release nogil;
  if (r.fleet)
    write_fleet_outputs(dir, r.scenario->scenario, *r.fleet, context, which);
  else
    write_run_outputs(dir, r.scenario->scenario, *r.run, context, which);
}

// Cases on `jobs` worker threads (the GIL released); the calling thread watches for Ctrl-C.
py::tuple batch(const std::vector<ScenarioPtr>& scenarios, int jobs, bool timing, bool optimum,
                const std::optional<std::filesystem::path>& out,
                const std::optional<std::vector<std::size_t>>& ids,
                const std::optional<std::tuple<std::string, int, int, std::size_t>>& sweep) {
  const std::size_t n = scenarios.size();
  if (ids && ids->size() != n)
    throw py::value_error(fmt::format("batch: {} case ids for {} scenarios", ids->size(), n));
  if (ids) {  // each case once: two lines of one case in results.jsonl would each claim it
    std::vector<std::size_t> sorted = *ids;
    std::sort(sorted.begin(), sorted.end());
    if (const auto twice = std::adjacent_find(sorted.begin(), sorted.end()); twice != sorted.end())
      throw py::value_error(fmt::format("batch: case id {} is given twice", *twice));
  }
  std::vector<BatchCase> cases;
  cases.reserve(n);
  bool python = false;
  for (std::size_t i = 0; i < n; ++i) {
    if (!scenarios[i]) throw py::value_error("batch: a scenario is None");
    cases.push_back(
        {scenarios[i]->scenario, scenarios[i]->source, ids ? (*ids)[i] : i, {}, {}, {}});
    python = python || scenarios[i]->python_controller;
  }
  BatchOptions options;
  options.timing = timing;
  options.optimum = optimum;
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  int workers = jobs > 0 ? jobs : static_cast<int>(hw);
  if (python) workers = 1;  // Python controllers hold the GIL at every step: one thread
  workers = std::max(1, std::min<int>(workers, static_cast<int>(std::max<std::size_t>(n, 1))));

  std::vector<nlohmann::ordered_json> lines(n);
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex mutex;
  std::condition_variable cv;
  std::size_t running = static_cast<std::size_t>(workers);
  std::exception_ptr error;
  {
    py::gil_scoped_release nogil;
    auto work = [&] {
      while (!stop.load()) {
        const std::size_t i = next.fetch_add(1);
        if (i >= n) break;
        try {
          BatchOptions case_options = options;  // each scenario's own overrides in its line
          case_options.overrides = scenarios[i]->overrides;
          lines[i] = run_batch_case(cases[i], case_options);
        } catch (...) {
          std::lock_guard lock(mutex);
          if (!error) error = std::current_exception();
          stop.store(true);
        }
      }
      std::lock_guard lock(mutex);
      --running;
      cv.notify_all();
    };
    std::vector<std::thread> threads;
    for (int t = 0; t < workers; ++t) threads.emplace_back(work);
    while (true) {
      {
        std::unique_lock lock(mutex);
        if (cv.wait_for(lock, std::chrono::milliseconds(100), [&] { return running == 0; })) break;
      }
      py::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() != 0) {  // Ctrl-C: finish the cases under way, take no more
        stop.store(true);
        py::error_already_set pending;  // keep the KeyboardInterrupt while the threads end
        {
          py::gil_scoped_release again;
          for (auto& t : threads) t.join();
        }
        throw pending;
      }
    }
    for (auto& t : threads) t.join();
  }
  if (error) std::rethrow_exception(error);

  nlohmann::ordered_json aggregate = aggregate_results(lines);
  // The CLI's keys. The sweep id is the caller's fingerprint of the whole sweep (floornav.batch
  // computes one when it writes a folder), else none.
  aggregate["sweep_id"] = sweep ? nlohmann::ordered_json(std::get<0>(*sweep)) : nullptr;
  aggregate["complete"] = true;
  if (out) {  // the CLI's three files, together, only once every case has run
    if (!sweep) throw py::value_error("batch: a folder is written with its sweep (sweep.json)");
    const auto& [id, k, shards, cases] = *sweep;
    py::gil_scoped_release nogil;
    OutputFolder folder(*out, {"results.jsonl", "aggregate.json", "sweep.json"});
    folder.write("results.jsonl", [&](const std::function<void(std::string_view)>& sink) {
      for (const auto& l : lines) sink(l.dump() + "\n");
    });
    folder.write("aggregate.json", aggregate.dump(2) + "\n");
    folder.write("sweep.json", sweep_json_text(SweepInfo{id, k, shards, cases}, n));
    folder.commit();
  }
  py::list result;
  for (const auto& l : lines) result.append(json_to_python(l));
  return py::make_tuple(result, json_to_python(aggregate));
}

// pickle: (scenario fields, the Python controller's kind or None, the result's data). A result of
// a Python controller pickles too (the results of runs in other processes): its scenario comes
// back with the controller's name and without the controller.
py::tuple run_result_state(const PyRunResult& r) {
  const py::object kind = r.scenario->python_controller
                              ? py::object(py::str(r.scenario->scenario.robot().controller.kind))
                              : py::object(py::none());
  return py::make_tuple(scenario_fields(*r.scenario), kind, run_result_data(r));
}

std::shared_ptr<PyRunResult> run_result_of_state(const py::tuple& t) {
  if (t.size() != 3)
    throw py::value_error("a pickled RunResult is (scenario, controller kind, data)");
  auto r = std::make_shared<PyRunResult>();
  r->scenario = scenario_of_fields(t[0].cast<py::tuple>());
  if (!t[1].is_none())
    r->scenario = with_unpickled_controller(*r->scenario, t[1].cast<std::string>());
  load_run_result_data(*r, t[2].cast<py::bytes>());
  return r;
}

// Equal results: the same data, bit for bit (NaN equal to NaN, as in the files they write), of
// scenarios with the same fields.
bool same_result(const PyRunResult& a, const PyRunResult& b) {
  if (&a == &b) return true;
  if (!scenario_fields(*a.scenario).equal(scenario_fields(*b.scenario))) return false;
  // the context aside: it is computed on first use, from the scenario
  return run_result_data(a, false).equal(run_result_data(b, false));
}

}  // namespace

void bind_run(py::module_& m) {
  m.def(
      "_robot_colour", [](std::size_t i) { return robot_color(i); }, py::arg("index"),
      "Robot `index`'s colour in trajectory.svg (#rrggbb).");
  py::class_<PyRunResult, std::shared_ptr<PyRunResult>>(
      m, "RunResult",
      "A finished run: `summary` (summary.json as a dict), `trajectory` (trajectory.csv as "
      "numpy arrays), `transitions` (the transition log with guard names).")
      .def_property_readonly("summary", &make_summary,
                             "summary.json as a dict (the CONTRACT keys first, then goals, "
                             "chatter, final pose and the first 1,000 transitions).")
      .def_property_readonly("trajectory", &make_trajectory,
                             "One numpy array per trajectory.csv column: t, x, y, theta, v, "
                             "omega, w_left, w_right (float64) and mode (str); a fleet adds "
                             "robot (str), robot after robot. Empty unless sim.record_trajectory.")
      .def_property_readonly(
          "transitions",
          [](const PyRunResult& r) {
            if (r.run) return transitions_of(*r.run);
            return py::list();  // fleets count switches but keep no log
          },
          "Every transition, in order: dicts of t, from, to, guard (names), x, y. A fleet's "
          "robots keep counts only (summary mode_switches): an empty list.")
      .def_property_readonly("scenario", [](const PyRunResult& r) { return r.scenario; })
      .def_property_readonly(
          "status",
          [](const PyRunResult& r) {
            return std::string(to_string(r.run ? r.run->status : r.fleet->status));
          },
          "reached, collision, timeout or stuck.")
      .def_property_readonly(
          "mode_names",
          [](const PyRunResult& r) {
            return r.run ? r.run->mode_names : std::vector<std::string>{};
          },
          "The controller's modes, in index order (lone robot).")
      .def_property_readonly("is_fleet", [](const PyRunResult& r) { return r.fleet.has_value(); })
      .def_property_readonly(
          "crowd",
          [](const PyRunResult& r) {
            py::dict out;
            py::list people, forklifts;
            if (r.fleet) {
              for (const auto& [tracks, list] :
                   {std::pair{&r.fleet->crowd.people, &people},
                    std::pair{&r.fleet->crowd.forklifts, &forklifts}}) {
                for (const CrowdTrack& track : *tracks) {
                  const auto n = static_cast<py::ssize_t>(track.samples.size());
                  py::array_t<double> samples({n, py::ssize_t{4}});
                  double* x = samples.mutable_data();
                  for (const CrowdSample& c : track.samples) {
                    *x++ = c.t;
                    *x++ = c.x;
                    *x++ = c.y;
                    *x++ = c.theta;
                  }
                  py::dict d;
                  d["name"] = track.name;
                  d["size"] = py::make_tuple(track.size.x(), track.size.y());
                  d["samples"] = samples;
                  list->append(d);
                }
              }
            }
            out["people"] = people;
            out["forklifts"] = forklifts;
            return out;
          },
          "The people's and forklifts' tracks (a fleet among them): {'people': [...], "
          "'forklifts': [...]}, each {name, size (length, width; a person's diameter twice), "
          "samples (k, 4): t, x, y, theta} (every step while the trajectory is recorded).")
      .def(
          "write",
          [](PyRunResult& r, const std::filesystem::path& dir, bool mcap) {
            write_outputs(r, dir, mcap);
          },
          py::arg("out"), py::arg("mcap") = false,
          "Writes the CLI's files (summary.json, trajectory.csv, trajectory.svg, ...) into `out`; "
          "with mcap=True also run.mcap, the run as a ROS 2 bag (its sensor topics hold the "
          "ranges the run recorded: run with floornav.run(..., mcap=True) to record them).")
      .def(py::pickle(&run_result_state, &run_result_of_state))
      .def("__copy__", [](const std::shared_ptr<PyRunResult>& r) { return r; })  // immutable
      .def("__deepcopy__",
           [](const PyRunResult& r, py::handle) {
             auto c = std::make_shared<PyRunResult>(r);
             c->summary = py::object();  // dicts and arrays of its own, built on first use
             c->trajectory = py::object();
             return c;
           })
      .def("__eq__", &same_result, py::is_operator())
      .def("__repr__", [](const PyRunResult& r) {
        if (r.run) return fmt::format("<floornav.RunResult {}>", describe_run(*r.run));
        return fmt::format("<floornav.RunResult {}>", describe_fleet(*r.fleet));
      });

  m.def("_run", &run, py::arg("scenario"), py::arg("threads") = 0, py::arg("mcap") = false);
  m.def("_batch", &batch, py::arg("scenarios"), py::arg("jobs"), py::arg("timing"),
        py::arg("optimum"), py::arg("out"), py::arg("ids") = py::none(),
        py::arg("sweep") = py::none());
}

}  // namespace floornav::python
