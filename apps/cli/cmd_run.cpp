// `blockdem run SCENARIO.toml --out DIR`: runs a scenario's stages and writes its outputs.
#include <algorithm>
#include <cstdio>
#include <iostream>

#include "blockdem/run/scenario_runner.hpp"
#include "blockdem/run/scene_builders.hpp"
#include "blockdem/voussoir/scene.hpp"
#include "commands.hpp"
#include "figures.hpp"
#include "progress.hpp"

namespace blockdem::cli {
namespace {

struct RunOptions {
  std::string scenario;
  std::string out;
  bool quiet = false;
  bool figures = true;
  std::int64_t max_steps = 0;  ///< > 0: every stage stops after at most this many steps
};

int run(const RunOptions& opt) {
  Progress progress(!opt.quiet);
  RunCallbacks cb;
  cb.progress = [&](const std::string& s) { progress.update(s); };
  cb.stage_done = [&](const std::string& s) {
    if (!opt.quiet) progress.message(s);
  };
  RunResult r;
  bool beam = false;
  try {
    // Read and check everything before anything is written.
    Scenario sc = load_scenario(opt.scenario);
    if (opt.max_steps > 0) {
      for (auto& stage : sc.stages) {
        stage.max_steps = std::min(stage.max_steps, opt.max_steps);
        stage.min_steps = std::min(stage.min_steps, opt.max_steps);
      }
    }
    beam = voussoir_scene(sc) != nullptr;
    for (const auto& w : sc.warnings)
      std::cerr << "blockdem: warning: " << opt.scenario << ": " << w << "\n";
    r = run_scenario(sc, opt.out, cb);
  } catch (const ScenarioError& e) {
    std::cerr << "blockdem: error: " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "blockdem: error: " << opt.scenario << ": " << e.what() << "\n";
    return 2;
  }
  if (beam && opt.figures && !r.levels.empty()) {
    std::string why;
    if (!run_plot_script("plot_voussoir.py", {"case", opt.out}, why))
      std::cerr << "blockdem: warning: no figures: " << why << "\n";
  }
  if (r.exit_code != 0) {
    std::cerr << "blockdem: error: " << r.message << "\n"
              << "blockdem: outputs up to the last good state are in " << opt.out
              << " (summary.json status \"" << r.status << "\")\n";
  } else if (!opt.quiet) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "blockdem: done in %.2f s, %lld steps; outputs in ", r.wall_time,
                  static_cast<long long>(r.steps));
    std::cerr << buf << opt.out << "\n";
  }
  return r.exit_code;
}

}  // namespace

void register_run(CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  CLI::App* cmd =
      app.add_subcommand("run", "Run a scenario file (TOML; see docs/scenario-files.md)");
  cmd->add_option("scenario", opt->scenario, "Scenario file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--out", opt->out, "Output folder (created if missing)")->required();
  cmd->add_flag("--quiet", opt->quiet, "No progress output");
  cmd->add_option("--max-steps", opt->max_steps,
                  "Stop every stage after at most N steps (a quick look at a scenario; a stage "
                  "cut short is reported as not converged)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("!--no-figures", opt->figures,
                "Do not draw figures (voussoir scenarios draw PNGs with matplotlib)");
  cmd->callback([opt] { set_exit_code(run(*opt)); });
}

}  // namespace blockdem::cli
