// The list of built-in scene builders.
#include "blockdem/run/scene_builders.hpp"

#include "blockdem/voussoir/scene.hpp"

namespace blockdem {

const SceneBuilders& scene_builders() {
  static const VoussoirSceneBuilder voussoir;
  static const SceneBuilders all = {&voussoir};
  return all;
}

Scenario load_scenario(const std::string& path) {
  return load_scenario(path, scene_builders());
}

Scenario parse_scenario(const std::string& toml_text, const std::string& file) {
  return parse_scenario(toml_text, file, scene_builders());
}

}  // namespace blockdem
