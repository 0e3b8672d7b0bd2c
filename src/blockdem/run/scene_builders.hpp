// The scene builders the program knows, and the scenario reader that uses all of them.
#pragma once

#include <string>

#include "blockdem/scenario/scenario.hpp"

namespace blockdem {

/// Every built-in scene builder: [voussoir].
const SceneBuilders& scene_builders();

/// Reads and checks a scenario file with every built-in builder (throws ScenarioError).
Scenario load_scenario(const std::string& path);
/// The same from TOML text; `file` is used in messages.
Scenario parse_scenario(const std::string& toml_text, const std::string& file);

}  // namespace blockdem
