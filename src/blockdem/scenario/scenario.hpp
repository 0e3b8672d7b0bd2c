// Scenario files (TOML, schema in docs/scenario-files.md): blocks, materials, joint laws, stages
// and outputs, read with every key checked, and turned into a World.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "blockdem/response/in_situ.hpp"
#include "blockdem/scenario/builder.hpp"
#include "blockdem/scenario/checked_table.hpp"
#include "blockdem/world/stage.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

struct OutputSpec {
  bool vtk = true;                ///< write VTK files of blocks and contacts at every stage end
  std::int64_t vtk_interval = 0;  ///< also a VTK frame every this many steps (0: stage ends only)
  /// time_history.csv: a row every history_interval steps, or every history_interval_s of
  /// model time (s) when that is given; never more than history_max_rows rows.
  std::int64_t history_interval = 100;
  double history_interval_s = 0.0;
  std::int64_t history_max_rows = 20000;
  std::vector<std::string> history_blocks;  ///< blocks with their own columns
  std::vector<std::string> history_bolts;   ///< bolts with their own columns
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
  /// Densities of the [[materials]] by name (kg/m^3).
  std::map<std::string, double> materials;
  /// Values that are allowed but probably wrong (e.g. a density off by orders of magnitude).
  std::vector<std::string> warnings;
  /// Set by a scene builder (e.g. the voussoir beam: its spec and where its parts are).
  std::shared_ptr<const BuiltScene> built;
  /// Per block: its planes' own joint laws (empty: none; see World::set_face_laws). Set by a
  /// builder (a rock mass: one law per joint set).
  std::vector<std::vector<int>> face_laws;
  /// Per block: the joint set that made each plane (empty: none; see World::set_face_sets), and
  /// the joint sets' names. Set by a builder (a rock mass).
  std::vector<std::vector<int>> face_sets;
  std::vector<std::string> joint_sets;
  /// Named sets of blocks that a stage can remove (`excavation = "NAME"`). Set by a builder.
  std::map<std::string, std::vector<std::string>> excavations;
  /// [in_situ]: the stress field the joints carry from the start (simulation coordinates).
  std::optional<StressField> in_situ;
  /// [settings] initial_overlap = "allow": overlapping blocks at the start are deliberate
  /// (prestressed contacts) and pass the set-up's check.
  bool allow_initial_overlap = false;
  /// The TOML text it was read from, when at most kKeptScenarioText bytes (empty for a larger
  /// file): what a saved simulation compares a scenario with (its fingerprint).
  std::string text;
};

/// The largest scenario text a Scenario keeps (Scenario::text).
inline constexpr std::size_t kKeptScenarioText = 8u << 20;

/// Reads and checks a scenario file; `builders` are the scene builders whose tables the file may
/// hold. Throws ScenarioError ("FILE: KEY: REASON"). run/scene_builders.hpp has the overload
/// with every built-in builder.
Scenario load_scenario(const std::string& path, const SceneBuilders& builders);
/// The same from TOML text; `file` is used in messages.
Scenario parse_scenario(const std::string& toml_text, const std::string& file,
                        const SceneBuilders& builders);

/// Reads the `normal` and `shear` sub-tables of a joint-law table into `law`.
void read_joint_law_tables(const CheckedTable& table, JointLaw& law);
/// Reads an [output] table.
void read_output(const CheckedTable& table, OutputSpec& output);

/// Throws ScenarioError when the world's first time step is absurdly small (below 1 ns), which
/// means a unit is wrong somewhere.
void check_time_step(const Scenario& scenario, const World& world);

/// Builds the world. Throws ScenarioError when blocks overlap deeply at the start (more than
/// the settings' max_overlap_fraction of the smaller block's radius).
World build_world(const Scenario& scenario);
/// The same, moving the blocks and their faces' laws and joint sets out of the scenario into the
/// world (they are not copied; the scenario is left without them): for a caller that needs them
/// no more, so that a large scene holds its blocks once.
World build_world_taking_blocks(Scenario& scenario);

}  // namespace blockdem
