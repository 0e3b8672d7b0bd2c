// Scenario files (TOML, schema in docs/scenario-files.md): blocks, materials, joint laws, stages
// and outputs, read with every key checked, and turned into a World.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "blockdem/scenario/checked_table.hpp"
#include "blockdem/scenario/voussoir.hpp"
#include "blockdem/world/stage.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

struct RockMassModel;

struct OutputSpec {
  bool vtk = true;  ///< write VTK files of blocks and contacts at every stage end
};

struct Scenario {
  std::string file;  ///< where it was read from
  std::string title;
  WorldSettings settings;
  std::vector<Block> blocks;
  std::vector<JointLaw> joint_laws;
  std::vector<JointRule> joint_rules;
  std::vector<Stage> stages;
  OutputSpec output;
  /// Set for a [voussoir] scenario: the beam it was built from and where its parts are.
  std::optional<VoussoirSpec> voussoir;
  VoussoirLayout voussoir_layout;
  /// Set for a [rock_mass] scenario: the sliced rock mass the blocks were made from.
  std::shared_ptr<const RockMassModel> rock_mass;
  /// Per block: its planes' own joint laws (empty: none; see World::set_face_laws).
  std::vector<std::vector<int>> face_laws;
  /// Names of the blocks inside each excavation, by excavation name.
  std::map<std::string, std::vector<std::string>> excavations;
};

/// Reads and checks a scenario file. Throws ScenarioError ("FILE: KEY: REASON").
Scenario load_scenario(const std::string& path);
/// The same from TOML text; `file` is used in messages.
Scenario parse_scenario(const std::string& toml_text, const std::string& file);

/// Builds the world. Throws ScenarioError when blocks overlap deeply at the start (more than
/// the settings' max_overlap_fraction of the smaller block's radius).
World build_world(const Scenario& scenario);

}  // namespace blockdem
