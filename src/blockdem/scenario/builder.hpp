// Scene builders: a top-level table of a scenario file (e.g. [voussoir]) that builds blocks,
// joint laws, rules and stages from a few parameters instead of a list of blocks. Builders live
// in the layers above this one and are handed to the reader (run/scene_builders.hpp lists them).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "blockdem/scenario/checked_table.hpp"
#include "blockdem/scenario/run_observer.hpp"

namespace blockdem {

struct Scenario;

/// What a builder leaves in the scenario for the layers above it (measures, reports): derive
/// from it and find it again with dynamic_cast.
struct BuiltScene {
  virtual ~BuiltScene() = default;
  /// The observer that writes this scene's outputs of a run into `out` (null: none), made once the
  /// world is built. `resumed`: the run continues a checkpoint, whose files are back in `out`
  /// (the observer appends to them, and its state is loaded next: RunObserver::load_state).
  virtual std::unique_ptr<RunObserver> observer(const std::filesystem::path& /*out*/,
                                                const World& /*world*/, bool /*resumed*/) const {
    return nullptr;
  }
  /// Whether the observer writes history.csv and blocks.csv itself (the run then writes neither
  /// those nor contacts.csv).
  virtual bool writes_own_tables() const { return false; }
};

class SceneBuilder {
 public:
  virtual ~SceneBuilder() = default;
  /// The top-level table this builder reads, e.g. "voussoir".
  virtual std::string table() const = 0;
  /// Top-level keys that must not stand beside the builder's table, because it builds them.
  virtual std::vector<std::string> replaces() const = 0;
  /// Reads the builder's table (every key checked; errors through `table.fail`) and adds blocks,
  /// joint laws, rules and stages to `scenario`, which already holds the file's settings,
  /// materials, joint laws and blocks. May set `scenario.built`.
  virtual void build(const CheckedTable& table, Scenario& scenario) const = 0;
  /// Top-level keys beside its table that the builder reads too (e.g. [[joint_sets]]).
  virtual std::vector<std::string> reads() const { return {}; }
  /// Reads the builder's table, and the top-level keys of reads(), from the file's root table.
  /// The default hands build() its table alone.
  virtual void build_from_root(const CheckedTable& root, Scenario& scenario) const {
    build(root.table(table()), scenario);
  }
};

using SceneBuilders = std::vector<const SceneBuilder*>;

}  // namespace blockdem
