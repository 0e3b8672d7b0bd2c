// `blockdem run SCENARIO.toml --out DIR`: runs a scenario's stages and writes its outputs.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "blockdem/io/run_recorder.hpp"
#include "blockdem/scenario/scenario.hpp"
#include "commands.hpp"
#include "progress.hpp"

namespace blockdem::cli {
namespace {

struct RunOptions {
  std::string scenario;
  std::string out;
  bool quiet = false;
};

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

int run(const RunOptions& opt) {
  const auto wall0 = std::chrono::steady_clock::now();
  // Read and check everything before anything is written.
  Scenario sc;
  World world;
  try {
    sc = load_scenario(opt.scenario);
    world = build_world(sc);
  } catch (const ScenarioError& e) {
    std::cerr << "blockdem: error: " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "blockdem: error: " << opt.scenario << ": " << e.what() << "\n";
    return 2;
  }

  Progress progress(!opt.quiet);
  RunRecorder recorder(opt.out, sc.output.vtk);
  nlohmann::json summary;
  summary["program"] = std::string("blockdem ") + version();
  summary["scenario"] = std::filesystem::absolute(opt.scenario).string();
  summary["title"] = sc.title;
  summary["blocks"] = world.blocks().size();
  summary["citations"] = {
      "Boon C.W., Houlsby G.T., Utili S. (2012) A new algorithm for contact detection between convex "
      "polygonal and polyhedral particles in the discrete element method. Computers and Geotechnics 44:73-82.",
      "Boon C.W., Houlsby G.T., Utili S. (2015) DEM modelling of a jointed rock beam with emphasis on "
      "interface properties. Geotechnique Letters 5:49-55."};
  nlohmann::json stages = nlohmann::json::array();
  std::string status = "completed";
  std::string message;
  int code = 0;

  const int n = static_cast<int>(sc.stages.size());
  for (int level = 0; level < n; ++level) {
    const Stage& stage = sc.stages[level];
    StageResult result;
    try {
      result = run_stage(world, stage, [&](const Stage& s, std::int64_t k, const EquilibriumMeasures& m) {
        progress.update("[" + std::to_string(level + 1) + "/" + std::to_string(n) + "] " + s.name +
                        ": step " + std::to_string(k) + ", unbalanced " +
                        fmt("%.2e", m.unbalanced_force_ratio) + ", KE ratio " +
                        fmt("%.2e", m.kinetic_energy_ratio));
      });
    } catch (const DivergenceError& e) {
      status = "diverged";
      message = e.what();
      result.name = stage.name;
      result.converged = false;
      result.time = world.time();
      result.measures = world.equilibrium();
      result.message = message;
      recorder.record(world, result, level);
      stages.push_back({{"name", stage.name}, {"converged", false}, {"message", message}});
      code = 3;
      break;
    }
    recorder.record(world, result, level);
    stages.push_back({{"name", result.name},
                      {"converged", result.converged},
                      {"steps", result.steps},
                      {"time_s", result.time},
                      {"unbalanced_force_ratio", result.measures.unbalanced_force_ratio},
                      {"kinetic_energy_ratio", result.measures.kinetic_energy_ratio},
                      {"contacts", world.contact_count()},
                      {"message", result.message}});
    if (!opt.quiet) {
      progress.message("stage " + std::to_string(level + 1) + "/" + std::to_string(n) + " '" + stage.name +
                       "': " + (result.converged ? "done" : "NOT CONVERGED") + " after " +
                       std::to_string(result.steps) + " steps (unbalanced " +
                       fmt("%.2e", result.measures.unbalanced_force_ratio) + ")");
    }
    if (!result.converged) {
      status = "not_converged";
      message = "stage '" + stage.name + "': " + result.message;
      code = 3;
      break;
    }
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  summary["status"] = status;
  summary["message"] = message;
  summary["stages"] = stages;
  summary["steps"] = world.step_count();
  summary["time_s"] = world.time();
  summary["wall_time_s"] = wall;
  summary["contacts"] = world.contact_count();
  std::ofstream out(std::filesystem::path(opt.out) / "summary.json");
  out << summary.dump(2) << "\n";
  if (code != 0) {
    std::cerr << "blockdem: error: " << message << "\n"
              << "blockdem: outputs up to the last good state are in " << opt.out
              << " (summary.json status \"" << status << "\")\n";
  } else if (!opt.quiet) {
    std::cerr << "blockdem: done in " << fmt("%.2f", wall) << " s, " << world.step_count() << " steps; outputs in "
              << opt.out << "\n";
  }
  return code;
}

}  // namespace

void register_run(CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "Run a scenario file (TOML; see docs/scenario-files.md)");
  cmd->add_option("scenario", opt->scenario, "Scenario file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--out", opt->out, "Output folder (created if missing)")->required();
  cmd->add_flag("--quiet", opt->quiet, "No progress output");
  cmd->callback([opt] { set_exit_code(run(*opt)); });
}

}  // namespace blockdem::cli
