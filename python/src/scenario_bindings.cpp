// Scenarios from Python: load or parse TOML with the same checks and messages as `blockdem run`,
// inspect them, and run them with every output (run_scenario). ScenarioError becomes
// blockdem.ScenarioError (a ValueError with file, key and reason attributes).
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <string>

#include "bindings.hpp"
#include "blockdem/io/atomic_file.hpp"
#include "blockdem/run/run_files.hpp"
#include "blockdem/run/run_report.hpp"
#include "blockdem/run/scenario_runner.hpp"
#include "blockdem/run/scene_builders.hpp"
#include "blockdem/scenario/scenario.hpp"
#include "blockdem/world/world.hpp"
#include "simulation.hpp"

namespace py = pybind11;

namespace blockdem::python {
namespace {

/// A setting of a scenario a Simulation was built from would not reach its world: an error.
void refuse_if_built(const Scenario& s, const char* key) {
  if (built_scenarios().count(&s) != 0)
    throw py::value_error(std::string(key) +
                          ": this Scenario is a built Simulation's (sim.scenario), and a change "
                          "would not reach its world: set it on the Scenario before building the "
                          "Simulation");
}

// The Python exception types, created once when the module loads (never unloaded).
PyObject* scenario_error_type = nullptr;
PyObject* divergence_error_type = nullptr;

py::object json_to_python(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

}  // namespace

void bind_scenario(py::module_& m) {
  scenario_error_type = PyErr_NewExceptionWithDoc(
      "blockdem._core.ScenarioError",
      "An input error: str() reads 'FILE: KEY: REASON', as `blockdem run` prints it; the "
      "attributes file, key and reason hold the parts.",
      PyExc_ValueError, nullptr);
  divergence_error_type = PyErr_NewExceptionWithDoc(
      "blockdem._core.DivergenceError",
      "The run blew up (NaN, runaway speed, excessive overlap); the world is back at its last "
      "good state.",
      PyExc_RuntimeError, nullptr);
  m.attr("ScenarioError") = py::handle(scenario_error_type);
  m.attr("DivergenceError") = py::handle(divergence_error_type);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const ScenarioError& e) {
      py::object inst = py::reinterpret_borrow<py::object>(scenario_error_type)(e.what());
      inst.attr("file") = e.file();
      inst.attr("key") = e.key();
      inst.attr("reason") = e.reason();
      PyErr_SetObject(scenario_error_type, inst.ptr());
    } catch (const DivergenceError& e) {
      PyErr_SetString(divergence_error_type, e.what());
    }
  });

  py::class_<Scenario, std::shared_ptr<Scenario>>(
      m, "Scenario", "A checked scenario: what `blockdem run` reads from a TOML file.")
      .def_static(
          "load",
          [](const std::string& path) { return std::make_shared<Scenario>(load_scenario(path)); },
          py::arg("path"), "Reads and checks a TOML scenario file.")
      .def_static(
          "parse",
          [](const std::string& text, const std::string& file) {
            return std::make_shared<Scenario>(parse_scenario(text, file));
          },
          py::arg("text"), py::arg("file") = "<python>",
          "Reads and checks TOML text; `file` names it in messages.")
      .def_readonly("file", &Scenario::file)
      .def_readonly("title", &Scenario::title)
      .def_readonly("warnings", &Scenario::warnings, "values allowed but probably wrong")
      .def_property_readonly("block_names",
                             [](const Scenario& s) {
                               std::vector<std::string> names;
                               for (const auto& b : s.blocks) names.push_back(b.name);
                               return names;
                             })
      .def_property_readonly("stage_names",
                             [](const Scenario& s) {
                               std::vector<std::string> names;
                               for (const auto& st : s.stages) names.push_back(st.name);
                               return names;
                             })
      .def_property_readonly("joint_law_names",
                             [](const Scenario& s) {
                               std::vector<std::string> names;
                               for (const auto& l : s.joint_laws) names.push_back(l.name);
                               return names;
                             })
      .def_property(
          "threads", [](const Scenario& s) { return s.settings.threads; },
          [](Scenario& s, int n) {
            refuse_if_built(s, "threads");
            if (n < 0) throw py::value_error("threads: must be >= 0 (0: OpenMP's default)");
            s.settings.threads = n;
          },
          "threads of a step (0: OMP_NUM_THREADS, else every core); results do not depend on it")
      .def(
          "limit_steps",
          [](Scenario& s, std::int64_t n) {
            refuse_if_built(s, "limit_steps");
            if (n <= 0) throw py::value_error("limit_steps: must be > 0");
            for (auto& st : s.stages) {
              st.max_steps = std::min(st.max_steps, n);
              st.min_steps = std::min(st.min_steps, n);
            }
          },
          py::arg("max_steps"),
          "Caps every stage at this many steps, as `blockdem run --max-steps` (short runs).");

  m.def(
      "run_scenario",
      [](const Scenario& sc, const std::filesystem::path& out,
         const std::function<void(const std::string&)>& progress) {
        if (sc.stages.empty())
          throw ScenarioError(sc.file, "stages", "a run needs at least one [[stages]] entry");
        RunCallbacks cb;
        if (progress) {
          cb.progress = [&](const std::string& s) {
            py::gil_scoped_acquire hold;
            progress(s);
          };
          cb.stage_done = cb.progress;
          cb.setup_done = cb.progress;
          cb.time_step = [&](const std::string& s, bool warning) {
            cb.progress(warning ? "warning: " + s : s);
          };
        }
        RunResult r;
        {
          py::gil_scoped_release free;
          r = run_scenario(sc, out, cb);
          // The report of `blockdem run`, without its figures (they are the command's), and the
          // record of the files with it. An interrupted run has its report when it ends.
          if (!r.interrupted && std::filesystem::exists(out / "summary.json")) {
            write_run_report(out, {});
            update_files_record(out, r.foreign_files);
            r.summary = nlohmann::json::parse(read_file_bytes(out / "summary.json"));
          }
        }
        py::dict d;
        d["status"] = to_string(r.status);
        d["message"] = r.message;
        d["exit_code"] = r.exit_code;
        d["steps"] = r.steps;
        d["steps_per_stage"] = r.steps_per_stage;
        d["wall_time"] = r.wall_time;
        d["factor_of_safety"] = r.factor_of_safety;
        d["collapse"] = r.collapse;
        d["summary"] = json_to_python(r.summary);
        return d;
      },
      py::arg("scenario"), py::arg("out"), py::arg("progress") = nullptr,
      "Runs every stage and writes the outputs of `blockdem run` into `out`; returns status, "
      "message, exit_code, steps, wall_time (s), factor_of_safety, collapse (g) and summary.");
  m.def(
      "run_output_names", [] { return run_output_names(); },
      "The files and folders directly under an output folder that a run may write (what a "
      "new run into that folder clears first).");
}

}  // namespace blockdem::python
