// Scenario runner: stages, outputs, summary.
#include "blockdem/run/scenario_runner.hpp"

#include <chrono>
#include <cstdio>
#include <fstream>

#include "blockdem/io/run_recorder.hpp"
#include "blockdem/numerics/units.hpp"
#include "blockdem/voussoir/recorder.hpp"
#include "blockdem/voussoir/scene.hpp"

namespace blockdem {
namespace {

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

}  // namespace

RunResult run_scenario(const Scenario& sc, const std::filesystem::path& out,
                       const RunCallbacks& cb) {
  const auto wall0 = std::chrono::steady_clock::now();
  World world = build_world(sc);  // may throw ScenarioError: nothing written yet
  check_time_step(sc, world);
  RunResult res;
  const VoussoirScene* voussoir = voussoir_scene(sc);
  const bool beam = voussoir != nullptr;
  RunRecorder recorder(out, sc.output.vtk, !beam);
  std::unique_ptr<VoussoirRecorder> beam_recorder;
  VoussoirReference reference;
  if (beam) beam_recorder = std::make_unique<VoussoirRecorder>(out, world);

  nlohmann::json& summary = res.summary;
  summary["program"] = "blockdem";
  summary["scenario"] = sc.file;
  summary["title"] = sc.title;
  summary["blocks"] = world.blocks().size();
  summary["contact_mode"] = to_string(sc.settings.contact_mode);
  summary["citations"] = {
      "Boon C.W., Houlsby G.T., Utili S. (2012) A new algorithm for contact detection between "
      "convex "
      "polygonal and polyhedral particles in the discrete element method. Computers and "
      "Geotechnics 44:73-82.",
      "Boon C.W., Houlsby G.T., Utili S. (2015) DEM modelling of a jointed rock beam with emphasis "
      "on "
      "interface properties. Geotechnique Letters 5:49-55.",
      "Cundall P.A. (1987) Distinct element models of rock and soil structure. In: Analytical and "
      "Computational Methods in Engineering Rock Mechanics, ch. 4 (local non-viscous damping)."};
  nlohmann::json stages = nlohmann::json::array();
  const int n = static_cast<int>(sc.stages.size());
  for (int level = 0; level < n; ++level) {
    const Stage& stage = sc.stages[level];
    StageResult result;
    bool diverged = false;
    try {
      result = run_stage(world, stage,
                         [&](const Stage& s, std::int64_t k, const EquilibriumMeasures& m) {
                           if (cb.progress) {
                             cb.progress("[" + std::to_string(level + 1) + "/" + std::to_string(n) +
                                         "] " + s.name + ": step " + std::to_string(k) +
                                         ", unbalanced " + fmt("%.2e", m.unbalanced_force_ratio) +
                                         ", KE ratio " + fmt("%.2e", m.kinetic_energy_ratio));
                           }
                         });
    } catch (const DivergenceError& e) {
      diverged = true;
      result.name = stage.name;
      result.time = world.time();
      result.measures = world.equilibrium();
      result.message = e.what();
    }
    res.steps_per_stage.push_back(result.steps);
    stages.push_back({{"name", stage.name},
                      {"converged", result.converged},
                      {"steps", result.steps},
                      {"time_s", result.time},
                      {"unbalanced_force_ratio", result.measures.unbalanced_force_ratio},
                      {"kinetic_energy_ratio", result.measures.kinetic_energy_ratio},
                      {"contacts", world.contact_count()},
                      {"message", result.message}});
    // Outputs of this level. A level that did not converge is written flagged converged = 0; a
    // diverged one is not written (the rows so far end with the last good state).
    if (!diverged) recorder.record(world, result, level);
    if (beam && !diverged) {
      const double g_level = world.settings().gravity.norm() / kOneG;
      if (level == 0) reference = capture_reference(world);
      const VoussoirLevel lv =
          measure_voussoir(world, voussoir->spec, voussoir->layout, reference, g_level);
      beam_recorder->record(world, lv, stage.name, result.converged, result.steps, level);
      if (result.converged) res.levels.push_back(lv);
    }
    if (cb.stage_done) {
      cb.stage_done(
          "stage " + std::to_string(level + 1) + "/" + std::to_string(n) + " '" + stage.name +
          "': " + (result.converged ? "done" : (diverged ? "DIVERGED" : "NOT CONVERGED")) +
          " after " + std::to_string(result.steps) + " steps (unbalanced " +
          fmt("%.2e", result.measures.unbalanced_force_ratio) + ")");
    }
    if (diverged) {
      res.status = "diverged";
      res.message = "stage '" + stage.name + "': " + result.message;
      break;
    }
    if (!result.converged) {
      res.status = "not_converged";
      res.message = "stage '" + stage.name + "': " + result.message;
      if (beam) {
        res.message +=
            res.levels.empty()
                ? ""
                : "; the beam lost equilibrium (snap-through or collapse); last stable level " +
                      fmt("%g g", res.levels.back().g_level);
      }
      break;
    }
  }
  res.exit_code = res.status == "completed" ? 0 : 3;
  res.steps = world.step_count();
  res.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  summary["status"] = res.status;
  summary["message"] = res.message;
  summary["stages"] = stages;
  summary["steps"] = res.steps;
  summary["time_s"] = world.time();
  summary["wall_time_s"] = res.wall_time;
  summary["contacts"] = world.contact_count();
  if (beam) {
    summary["voussoir"] = voussoir_summary(voussoir->spec, res.levels);
    // The headline numbers at the top level too, as the contract asks.
    for (const char* key :
         {"g_max", "thrust_N", "midspan_deflection_mm", "equilibrium_residual", "fits"}) {
      if (summary["voussoir"].contains(key)) summary[key] = summary["voussoir"][key];
    }
    summary["lost_equilibrium"] = res.status != "completed";
  }
  std::ofstream f(out / "summary.json");
  f << summary.dump(2) << "\n";
  if (!f) throw std::runtime_error("cannot write " + (out / "summary.json").string());
  return res;
}

}  // namespace blockdem
