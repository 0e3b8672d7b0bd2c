// `blockdem keyblocks SCENARIO.toml --out DIR`: the blocks each excavation stage of a scenario
// exposes that gravity can move into the opening (block theory), without running it; writes
// key_blocks.json and prints a table (docs/key-blocks.md).
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "blockdem/io/atomic_file.hpp"
#include "blockdem/run/removable_blocks.hpp"
#include "blockdem/run/scene_builders.hpp"
#include "commands.hpp"

namespace blockdem::cli {
namespace {

struct KeyBlocksOptions {
  std::string scenario;
  std::string out;
  double required_factor = kDefaultRequiredFactor;
  bool quiet = false;
};

/// One line per block: name, mode, volume, weight, factor of safety, support force.
void print_table(const nlohmann::json& blocks) {
  std::printf("%-24s %-12s %12s %14s %8s %14s\n", "block", "mode", "volume_m3", "weight_N", "F",
              "support_N");
  for (const auto& b : blocks) {
    std::printf("%-24s %-12s %12.4g %14.6g %8.4f %14.6g\n", b["block"].get<std::string>().c_str(),
                b["mode"].get<std::string>().c_str(), b["volume_m3"].get<double>(),
                b["weight_N"].get<double>(), b["factor_of_safety"].get<double>(),
                b["support_force_N"].get<double>());
  }
}

int keyblocks(const KeyBlocksOptions& opt) {
  Scenario sc;
  nlohmann::json blocks = nlohmann::json::array();
  try {
    // Read and check everything, and analyse, before anything is written.
    sc = load_scenario(opt.scenario);
    bool any = false;
    for (std::size_t s = 0; s < sc.stages.size(); ++s) {
      if (sc.stages[s].remove.empty()) continue;
      any = true;
      for (auto& b : removable_blocks(sc, s, opt.required_factor)) blocks.push_back(std::move(b));
    }
    if (!any)
      throw ScenarioError(sc.file, "stages",
                          "no stage excavates (kind = \"excavation\" with blocks to remove): "
                          "there is no opening to find key blocks on");
  } catch (const ScenarioError& e) {
    std::cerr << "blockdem: error: " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "blockdem: error: " << opt.scenario << ": " << e.what() << "\n";
    return 2;
  }
  const nlohmann::json report = {{"scenario", sc.file},
                                 {"required_factor", opt.required_factor},
                                 {"support_direction", "against the motion"},
                                 {"key_blocks", blocks}};
  std::filesystem::create_directories(opt.out);
  write_file_atomically(std::filesystem::path(opt.out) / "key_blocks.json", report.dump(2) + "\n");
  if (!opt.quiet) {
    print_table(blocks);
    std::cerr << "blockdem: " << blocks.size() << " key blocks; " << opt.out
              << "/key_blocks.json\n";
  }
  return 0;
}

}  // namespace

void register_keyblocks(CLI::App& app) {
  auto opt = std::make_shared<KeyBlocksOptions>();
  CLI::App* cmd = app.add_subcommand(
      "keyblocks",
      "List the blocks an excavation exposes that can fall or slide into it (block theory)");
  cmd->add_option("scenario", opt->scenario, "Scenario file with an excavation stage")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", opt->out, "Output folder (created if missing)")->required();
  cmd->add_option("--required-factor", opt->required_factor,
                  "Factor of safety the support force brings each block to (default 1.5)")
      ->check(positive_number("factor of safety"));
  cmd->add_flag("--quiet", opt->quiet, "No table");
  cmd->callback([opt] { set_exit_code(keyblocks(*opt)); });
}

}  // namespace blockdem::cli
