// The scene builders the program knows, the scenario reader that uses all of them, and what
// their observers measured in a run.
#pragma once

#include <string>
#include <vector>

#include "blockdem/scenario/scenario.hpp"

namespace blockdem {

struct RunResult;
struct VoussoirLevel;

/// Every built-in scene builder: [voussoir], [rock_mass].
const SceneBuilders& scene_builders();

/// Reads and checks a scenario file with every built-in builder (throws ScenarioError).
Scenario load_scenario(const std::string& path);
/// The same with a rock mass cut on `cut_threads` threads (0: OpenMP's default; the blocks are
/// the same for any number). `load_scenario` cuts on one (see RockMassSceneBuilder).
Scenario load_scenario(const std::string& path, int cut_threads);
/// The same from TOML text; `file` is used in messages.
Scenario parse_scenario(const std::string& toml_text, const std::string& file);

/// The voussoir beam levels of a run whose stage converged, preload first (empty when the run's
/// scene is not a voussoir beam). Their type is in voussoir/measures.hpp.
const std::vector<VoussoirLevel>& voussoir_levels(const RunResult& result);

}  // namespace blockdem
