// Scene builders: a top-level table of a scenario file (e.g. [voussoir]) that builds blocks,
// joint laws, rules and stages from a few parameters instead of a list of blocks. Builders live
// in the layers above this one and are handed to the reader (run/scene_builders.hpp lists them).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "blockdem/scenario/checked_table.hpp"

namespace blockdem {

struct Scenario;

/// What a builder leaves in the scenario for the layers above it (measures, reports): derive
/// from it and find it again with dynamic_cast.
struct BuiltScene {
  virtual ~BuiltScene() = default;
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
};

using SceneBuilders = std::vector<const SceneBuilder*>;

}  // namespace blockdem
