// The [voussoir] table of a scenario file: a scene builder that reads a VoussoirSpec and builds
// the beam's blocks, joint law and stages (keys in docs/scenario-files.md).
#pragma once

#include "blockdem/scenario/scenario.hpp"
#include "blockdem/voussoir/beam.hpp"

namespace blockdem {

/// What the voussoir builder leaves in a scenario: the beam and where its parts are.
struct VoussoirScene : BuiltScene {
  VoussoirSpec spec;
  VoussoirLayout layout;

  /// A VoussoirRecorder.
  std::unique_ptr<RunObserver> observer(const std::filesystem::path& out, const World& world,
                                        bool resumed) const override;
  bool writes_own_tables() const override { return true; }
};

/// The voussoir scene of a scenario, or nullptr when it was not built by [voussoir].
const VoussoirScene* voussoir_scene(const Scenario& scenario);

/// Builder of the [voussoir] table.
class VoussoirSceneBuilder final : public SceneBuilder {
 public:
  std::string table() const override { return "voussoir"; }
  std::vector<std::string> replaces() const override {
    return {"blocks", "stages", "joint_laws", "joints", "materials"};
  }
  void build(const CheckedTable& table, Scenario& scenario) const override;
};

}  // namespace blockdem
