// `blockdem generate SCENARIO.toml --out DIR`: cuts a scenario's rock mass into blocks without
// running it, and writes the blocks (VTK, CSV), rock_mass.json and two figures.
#include <chrono>
#include <iomanip>
#include <iostream>

#include <omp.h>

#include "blockdem/rockmass/rock_mass_output.hpp"
#include "blockdem/rockmass/scene.hpp"
#include "blockdem/run/scene_builders.hpp"
#include "commands.hpp"
#include "figures.hpp"

namespace blockdem::cli {
namespace {

struct GenerateOptions {
  std::string scenario;
  std::string out;
  bool figures = true;
  bool quiet = false;
  int threads = 0;  // 0: OMP_NUM_THREADS, else every core
};

int generate(const GenerateOptions& opt) {
  check_thread_count(opt.threads);
  // The cut and the files' text on this many threads (the same blocks and bytes for any).
  if (opt.threads > 0) omp_set_num_threads(opt.threads);
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::time_point from) {
    return std::chrono::duration<double>(Clock::now() - from).count();
  };
  const auto start = Clock::now();
  Scenario sc;
  try {
    // Read, check and slice everything before anything is written.
    sc = load_scenario(opt.scenario, 0);
    if (!rock_mass_scene(sc))
      throw ScenarioError(sc.file, "rock_mass", "generate needs a [rock_mass] to cut into blocks");
  } catch (const ScenarioError& e) {
    std::cerr << "blockdem: error: " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "blockdem: error: " << opt.scenario << ": " << e.what() << "\n";
    return 2;
  }
  const double cut_s = seconds(start);
  const auto written = Clock::now();
  const RockMassModel& model = rock_mass_scene(sc)->model;
  write_rock_mass(model, opt.out);
  const double write_s = seconds(written);
  if (opt.figures) {
    std::string why;
    if (!run_plot_script("plot_rock_mass.py", {opt.out}, why))
      std::cerr << "blockdem: warning: no figures: " << why << "\n";
  }
  if (!opt.quiet) {
    const RockMass& rm = model.rock_mass;
    std::cerr << "blockdem: " << rm.blocks.size() << " blocks, " << rm.total_volume() << " m3 of a "
              << rm.region_volume << " m3 region (" << rm.removed_blocks << " removed, "
              << rm.removed_volume << " m3; " << rm.merged_cuts << " cuts merged back); outputs in "
              << opt.out << "\n";
    // A large rock mass takes a while: where the time went.
    if (cut_s + write_s >= 1.0)
      std::cerr << "blockdem: read and cut in " << std::fixed << std::setprecision(1) << cut_s
                << " s, files written in " << write_s << " s\n";
  }
  return 0;
}

}  // namespace

void register_generate(CLI::App& app) {
  auto opt = std::make_shared<GenerateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "generate", "Cut a scenario's rock mass into blocks and write them without running");
  cmd->add_option("scenario", opt->scenario, "Scenario file with a [rock_mass]")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", opt->out, "Output folder (created if missing)")->required();
  cmd->add_flag("--quiet", opt->quiet, "No summary line");
  cmd->add_option("--threads", opt->threads,
                  "Threads that cut the blocks and write the files (default: OMP_NUM_THREADS, "
                  "else every core); the outputs are the same for any number")
      ->check(positive_number("threads"));
  cmd->add_flag("!--no-figures", opt->figures, "Do not draw figures (matplotlib)");
  cmd->callback([opt] { set_exit_code(generate(*opt)); });
}

}  // namespace blockdem::cli
