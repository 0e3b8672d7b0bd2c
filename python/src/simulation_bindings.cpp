// blockdem.Simulation: a world built from a scenario, run stage by stage or step by step, with a
// Python callback every N steps that can record, change loads and stop the run.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "bindings.hpp"
#include "blockdem/run/stage_driver.hpp"
#include "blockdem/scenario/stage_input.hpp"
#include "simulation.hpp"

namespace py = pybind11;

namespace blockdem::python {
namespace {

/// Called with the steps taken so far; returning false stops.
using StepHook = std::function<bool(std::int64_t)>;

/// The stage hook that calls `callback(sim, steps)` every `every` steps with the GIL held; a
/// return value of False stops.
StepHook make_hook(const py::object& self, const py::object& callback, std::int64_t every) {
  if (callback.is_none()) return {};
  if (every <= 0) throw py::value_error("every: must be > 0 (steps between callbacks)");
  return [self, callback, every](std::int64_t k) {
    if (k % every != 0) return true;
    py::gil_scoped_acquire hold;
    const py::object r = callback(self, k);
    return r.ptr() != Py_False;
  };
}

py::dict stage_dict(const StageResult& r) {
  py::dict d;
  d["name"] = r.name;
  d["converged"] = r.converged;
  d["stopped"] = r.interrupted;
  d["mechanism"] = r.mechanism;
  d["steps"] = r.steps;
  d["time"] = r.time;
  d["message"] = r.interrupted
                     ? "stopped by the callback after " + std::to_string(r.steps) + " steps"
                     : r.message;
  d["unbalanced_force_ratio"] = r.measures.unbalanced_force_ratio;
  d["kinetic_energy_ratio"] = r.measures.kinetic_energy_ratio;
  return d;
}

/// What drive_stages reported of the one stage run_stage drives: its result, or its strength
/// reduction, and its collapse search. A stage that blew up throws its DivergenceError on.
struct StageRecord final : RunObserver {
  StageResult result;
  std::optional<StabilitySearch> strength;
  std::optional<StabilitySearch> collapse;

  void on_stage_end(const World&, const StageEnd& end) override {
    if (end.error) std::rethrow_exception(end.error);
    result = end.result;
  }
  void on_interrupted(const World&, const Stage&, int, const StageResult* r) override {
    if (r) result = *r;
  }
  void on_strength_reduction(const World&, const Stage&, int, const StabilitySearch& search,
                             const StageResult& r) override {
    strength = search;
    result = r;
  }
  void on_collapse_search(const Stage&, int, const StabilitySearch& search) override {
    collapse = search;
  }
};

/// A strength-reduction stage: the factor of safety (the world is left as it was).
py::dict strength_dict(const Stage& stage, const StabilitySearch& sr, std::int64_t steps) {
  py::dict d;
  d["name"] = stage.name;
  d["converged"] = true;
  d["factor_of_safety"] = 0.5 * (sr.last_stable + sr.first_failed);
  d["last_stable"] = sr.last_stable;
  d["first_failed"] = sr.first_failed;
  d["search"] = sr.extrapolating ? "extrapolate" : "bisect";
  d["extrapolated"] = sr.extrapolated ? py::object(py::float_(*sr.extrapolated)) : py::none();
  d["trials"] = sr.trials.size();
  d["steps"] = steps;
  return d;
}

/// The collapse load of a failed stage, bisected as `blockdem run` does: {last_stable,
/// first_failed, trials} in g.
py::dict collapse_dict(const StabilitySearch& cs) {
  py::dict d;
  d["last_stable"] = cs.last_stable;
  d["first_failed"] = cs.first_failed;
  d["trials"] = cs.trials.size();
  return d;
}

/// Where run_stage's status lines go: None, to sys.stderr at most every 2 s of wall time (as
/// `blockdem run` updates its line on a pipe); False, nowhere; a callable, every line to it.
using LineFn = std::function<void(const std::string&)>;
LineFn progress_lines(const py::object& progress) {
  if (progress.is(py::bool_(false))) return {};
  if (!progress.is_none()) {
    if (!PyCallable_Check(progress.ptr()))
      throw py::type_error("progress: None (print), False (silent) or a callable(line)");
    return [progress](const std::string& line) { progress(line); };
  }
  auto last = std::make_shared<std::chrono::steady_clock::time_point>();
  return [last](const std::string& line) {
    const auto now = std::chrono::steady_clock::now();
    if (now - *last < std::chrono::seconds(2)) return;
    *last = now;
    py::module_::import("sys").attr("stderr").attr("write")("blockdem: " + line + "\n");
  };
}

/// The status lines of stage `level` of `s`: step, unbalanced and kinetic-energy ratios, rate.
std::function<ProgressFn(int)> stage_lines(const Simulation& s, const LineFn& line) {
  if (!line) return {};
  const int n = static_cast<int>(s.scenario->stages.size());
  return [line, n](int level) -> ProgressFn {
    const auto wall0 = std::chrono::steady_clock::now();
    return [line, n, level, wall0](const Stage& st, std::int64_t k, const EquilibriumMeasures& m) {
      const double wall =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
      char rate[64];
      const double per_second = wall > 0.0 ? static_cast<double>(k) / wall : 0.0;
      // Three digits below 100 steps per second (a step of a million blocks takes seconds).
      std::snprintf(rate, sizeof rate,
                    per_second >= 100.0 ? "%.2e, KE ratio %.2e, %.0f steps/s"
                                        : "%.2e, KE ratio %.2e, %.3g steps/s",
                    m.unbalanced_force_ratio, m.kinetic_energy_ratio, per_second);
      line("[" + std::to_string(level + 1) + "/" + std::to_string(n) + "] " + st.name + ": step " +
           std::to_string(k) + ", unbalanced " + rate);
    };
  };
}

/// Runs stage `i` with the driver `blockdem run` uses; `hook` may stop it; `line` gets its
/// status lines (a strength reduction's trials' too).
py::dict run_one_stage(Simulation& s, int i, const StepHook& hook, const LineFn& line) {
  const Stage& stage = s.scenario->stages[i];
  DriveControl control;
  control.progress = stage_lines(s, line);
  if (hook) {
    control.after_step = [&hook](int, const StageResume& at, const MotionMonitor&, const World*) {
      return !hook(at.steps_done);
    };
  }
  control.search_after_any_failure = true;
  StageRecord record;
  {
    // Python's lock stays held (a callback takes it anyway): no other thread can read or change
    // the world in the middle of a step.
    const Running running(s);
    drive_stages(s.world, s.scenario->stages, i + 1, DriveStart{i, nullptr, {}, {}}, control,
                 {&record});
  }
  if (record.strength) return strength_dict(stage, *record.strength, record.result.steps);
  py::dict d = stage_dict(record.result);
  if (record.collapse) d["collapse"] = collapse_dict(*record.collapse);
  return d;
}

}  // namespace

int block_index(const World& world, const py::handle& block) {
  if (py::isinstance<py::str>(block)) {
    const std::string name = block.cast<std::string>();
    const int i = world.find_block(name);
    if (i < 0) throw py::key_error("no block named '" + name + "'");
    return i;
  }
  const auto i = block.cast<std::int64_t>();
  if (i < 0 || i >= static_cast<std::int64_t>(world.blocks().size()))
    throw py::index_error("block index " + std::to_string(i) + " out of range");
  return static_cast<int>(i);
}

void bind_simulation(py::module_& m) {
  py::class_<Simulation> cls(m, "Simulation",
                             "A world built from a Scenario (the same build as `blockdem run`).");
  cls.def(py::init([](std::shared_ptr<Scenario> sc) {
            if (!sc) throw py::type_error("Simulation(scenario): a blockdem.Scenario, not None");
            return std::make_unique<Simulation>(std::make_shared<Scenario>(*sc));
          }),
          py::arg("scenario"),
          "Builds the world (a copy of the scenario: later changes to it do not reach it). "
          "Raises ScenarioError for deep initial overlaps or an absurd time step.")
      .def_property_readonly("scenario", [](const Simulation& s) { return s.scenario; })
      .def_property_readonly(
          "next_stage", [](const Simulation& s) { return s.next_stage; },
          "index of the stage run_stage() runs when given none")
      .def_property_readonly("stage_count",
                             [](const Simulation& s) { return s.scenario->stages.size(); })
      .def(
          "run_stage",
          [](py::object self, std::optional<int> index, py::object callback, std::int64_t every,
             py::object progress) {
            Simulation& s = self.cast<Simulation&>();
            const int n = static_cast<int>(s.scenario->stages.size());
            const int i = index.value_or(s.next_stage);
            if (i < 0 || i >= n)
              throw py::index_error("stage " + std::to_string(i) + " out of range (" +
                                    std::to_string(n) + " stages)");
            s.next_stage = i + 1;
            return run_one_stage(s, i, make_hook(self, callback, every), progress_lines(progress));
          },
          py::arg("index") = py::none(), py::arg("callback") = py::none(), py::arg("every") = 100,
          py::arg("progress") = py::none(),
          "Runs stage `index` (default: the next one) as `blockdem run` does; callback(sim, "
          "steps) every `every` steps, returning False stops the stage. progress: None prints "
          "a status line (step, unbalanced and kinetic-energy ratios, steps/s; a strength "
          "reduction's trials named with their factor) to sys.stderr at most every 2 s, False "
          "prints nothing, a callable(line) gets each line (at the first check of a stage or "
          "trial, then at most every 250 ms). Returns a dict (name, "
          "converged, stopped, mechanism, steps, time, message, unbalanced_force_ratio, "
          "kinetic_energy_ratio); a strength_reduction stage returns factor_of_safety, "
          "last_stable, first_failed, trials and leaves the world unchanged; a failed stage with "
          "find_collapse adds collapse = {last_stable, first_failed, trials} (g).")
      .def(
          "step",
          [](py::object self, std::int64_t n, py::object callback, std::int64_t every) {
            Simulation& s = self.cast<Simulation&>();
            if (n < 0) throw py::value_error("n: must be >= 0");
            const StepHook hook = make_hook(self, callback, every);
            std::int64_t k = 0;
            const Running running(s);
            while (k < n) {
              s.world.step();
              ++k;
              if (hook && !hook(k)) break;
            }
            return k;
          },
          py::arg("n") = 1, py::arg("callback") = py::none(), py::arg("every") = 100,
          "Advances n time steps with the current loads; callback(sim, steps) every `every` "
          "steps, returning False stops. Returns the steps taken.")
      .def_property_readonly(
          "time", [](const Simulation& s) { return s.world.time(); }, "simulated time (s)")
      .def_property_readonly("step_count", [](const Simulation& s) { return s.world.step_count(); })
      .def_property_readonly(
          "time_step", [](const Simulation& s) { return s.world.last_time_step(); },
          "the last step's time step (s)")
      .def_property_readonly("contact_count",
                             [](const Simulation& s) { return s.world.contact_count(); })
      .def_property_readonly("broken_bonds",
                             [](const Simulation& s) { return s.world.broken_bond_count(); })
      .def_property(
          "gravity",
          [](const Simulation& s) -> Eigen::Vector3d { return s.world.settings().gravity; },
          [](Simulation& s, const Eigen::Vector3d& g) { s.world.settings().gravity = g; },
          "gravity (m/s^2); a stage with a gravity ramp overwrites it at every step of the ramp")
      .def_property(
          "damping", [](const Simulation& s) { return s.world.settings().damping; },
          [](Simulation& s, double a) {
            if (!(a >= 0.0 && a < 1.0)) throw py::value_error("damping: must be in [0, 1)");
            s.world.settings().damping = a;
          },
          "Cundall local damping coefficient (-)")
      .def(
          "equilibrium",
          [](const Simulation& s) {
            const EquilibriumMeasures e = s.world.equilibrium();
            py::dict d;
            d["unbalanced_force_ratio"] = e.unbalanced_force_ratio;
            d["kinetic_energy"] = e.kinetic_energy;
            d["kinetic_energy_ratio"] = e.kinetic_energy_ratio;
            d["mean_contact_force"] = e.mean_contact_force;
            return d;
          },
          "unbalanced_force_ratio (-), kinetic_energy (J), kinetic_energy_ratio (-), "
          "mean_contact_force (N)")
      .def(
          "block_index",
          [](const Simulation& s, const py::handle& block) { return block_index(s.world, block); },
          py::arg("block"))
      .def(
          "set_external_force",
          [](Simulation& s, const py::handle& block, const Eigen::Vector3d& f) {
            s.world.blocks()[block_index(s.world, block)].set_external_force(f);
          },
          py::arg("block"), py::arg("force"),
          "Constant force on a free block from now on, world frame, at its centroid (N).")
      .def(
          "set_external_torque",
          [](Simulation& s, const py::handle& block, const Eigen::Vector3d& t) {
            s.world.blocks()[block_index(s.world, block)].set_external_torque(t);
          },
          py::arg("block"), py::arg("torque"), "Constant torque on a free block (N m).")
      .def(
          "set_velocity",
          [](Simulation& s, const py::handle& block, const Eigen::Vector3d& v) {
            s.world.blocks()[block_index(s.world, block)].velocity = v;
          },
          py::arg("block"), py::arg("velocity"),
          "Sets a block's velocity (m/s): the motion of a prescribed block, or a kick to a free "
          "one.");
  cls.def(
      "set_laws",
      [](Simulation& s, const py::list& changes, bool reset) {
        const std::vector<std::string>& sets = s.scenario->joint_sets;
        const auto& laws = s.world.joint_laws();
        const auto law_index = [&](const std::string& name) {
          for (std::size_t k = 0; k < laws.size(); ++k)
            if (laws[k].name == name) return static_cast<int>(k);
          return -1;
        };
        std::vector<LawChange> out;
        for (const py::handle& item : changes) {
          const py::dict e = item.cast<py::dict>();
          for (const auto& [key, value] : e) {
            const std::string k = key.cast<std::string>();
            if (k != "joint_set" && k != "group" && k != "law")
              throw py::value_error("set_laws: unknown key \"" + k +
                                    "\" (known: joint_set, group, law)");
          }
          if (e.contains("joint_set") == e.contains("group"))
            throw py::value_error("set_laws: name either a joint_set or a group");
          LawChange c;
          if (e.contains("joint_set")) {
            const std::string name = e["joint_set"].cast<std::string>();
            const auto it = std::find(sets.begin(), sets.end(), name);
            if (it == sets.end()) {
              std::string known;
              for (const auto& n : sets) known += (known.empty() ? "" : ", ") + n;
              throw py::key_error("set_laws: no joint set named \"" + name + "\" (known: " + known +
                                  ")");
            }
            c.joint_set = static_cast<int>(it - sets.begin());
          } else {
            c.group = e["group"].cast<std::string>();
            const auto& blocks = s.world.blocks();
            if (std::none_of(blocks.begin(), blocks.end(),
                             [&](const Block& b) { return b.group() == c.group; }))
              throw py::key_error("set_laws: no block is in group \"" + c.group + "\"");
          }
          if (!e.contains("law")) throw py::value_error("set_laws: each change needs a law");
          const std::string law = e["law"].cast<std::string>();
          c.law = law_index(law);
          c.elastic = c.law < 0 && law == "elastic";
          if (c.law < 0 && !c.elastic)
            throw py::key_error("set_laws: no joint law named \"" + law + "\"");
          out.push_back(std::move(c));
        }
        // The elastic twins a scenario without an elastic stage lacks, made now.
        if (std::any_of(out.begin(), out.end(), [](const LawChange& c) { return c.elastic; })) {
          const std::size_t n = laws.size();
          for (std::size_t k = 0; k < n; ++k) {
            const std::string& name = s.world.joint_laws()[k].name;
            if (name.ends_with(kElasticSuffix)) continue;
            if (law_index(name + std::string(kElasticSuffix)) < 0)
              s.world.add_joint_law(elastic_twin(s.world.joint_laws()[k]));
          }
        }
        s.world.change_laws(out);
        if (reset) s.world.reset_displacements();
      },
      py::arg("changes"), py::arg("reset_displacements") = false,
      "Gives joint laws anew, as a stage's set_laws does: changes is a list of dicts "
      "{'joint_set': NAME or 'group': NAME, 'law': NAME or 'elastic'}. Contacts keep their bond "
      "state, closure and shear history; a broken bond stays broken. 'elastic' gives each face "
      "its law's elastic twin 'NAME (elastic)' (made on first use when the scenario has none). "
      "reset_displacements: displacements count from now on.");
  bind_state(cls);
  bind_save(cls);
}

}  // namespace blockdem::python
