// The list of built-in scene builders, and the voussoir levels a run's observer measured.
#include "blockdem/run/scene_builders.hpp"

#include "blockdem/rockmass/scene.hpp"
#include "blockdem/run/scenario_runner.hpp"
#include "blockdem/voussoir/recorder.hpp"
#include "blockdem/voussoir/scene.hpp"

namespace blockdem {

const SceneBuilders& scene_builders() {
  static const VoussoirSceneBuilder voussoir;
  static const RockMassSceneBuilder rock_mass;
  static const SceneBuilders all = {&voussoir, &rock_mass};
  return all;
}

Scenario load_scenario(const std::string& path) {
  return load_scenario(path, scene_builders());
}

Scenario load_scenario(const std::string& path, int cut_threads) {
  static const VoussoirSceneBuilder voussoir;
  const RockMassSceneBuilder rock_mass(cut_threads);
  return load_scenario(path, SceneBuilders{&voussoir, &rock_mass});
}

Scenario parse_scenario(const std::string& toml_text, const std::string& file) {
  return parse_scenario(toml_text, file, scene_builders());
}

const std::vector<VoussoirLevel>& voussoir_levels(const RunResult& result) {
  static const std::vector<VoussoirLevel> none;
  const auto* recorder = dynamic_cast<const VoussoirRecorder*>(result.scene_output.get());
  return recorder ? recorder->stable_levels() : none;
}

}  // namespace blockdem
