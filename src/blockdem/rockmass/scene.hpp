// The [rock_mass] scene builder: reads [rock_mass], [[joint_sets]], [[excavations]] and
// [[boundaries]], slices the region, and adds the blocks (one joint law per face) to the scenario.
#pragma once

#include "blockdem/rockmass/rock_mass_model.hpp"
#include "blockdem/scenario/scenario.hpp"

namespace blockdem {

/// What the rock-mass builder leaves in a scenario: the sliced rock mass.
struct RockMassScene : BuiltScene {
  RockMassModel model;
};

/// The rock-mass scene of a scenario, or nullptr when it was not built by [rock_mass].
const RockMassScene* rock_mass_scene(const Scenario& scenario);

class RockMassSceneBuilder final : public SceneBuilder {
 public:
  /// The rock mass is cut on `cut_threads` threads (0: OpenMP's default), its blocks made on
  /// OpenMP's default; the blocks are the same for any numbers. A run cuts on one thread: cut on
  /// two, a million-block run's memory peak while stepping was 2-3 % higher (bench/README.md, "A
  /// million blocks generated on every core").
  explicit RockMassSceneBuilder(int cut_threads = 1) : cut_threads_(cut_threads) {}
  std::string table() const override { return "rock_mass"; }
  std::vector<std::string> replaces() const override { return {}; }
  std::vector<std::string> reads() const override {
    return {"joint_sets", "excavations", "boundaries"};
  }
  /// Not used: the rock mass needs the root table (see build_from_root). Throws logic_error.
  void build(const CheckedTable& table, Scenario& scenario) const override;
  void build_from_root(const CheckedTable& root, Scenario& scenario) const override;

 private:
  int cut_threads_;
};

}  // namespace blockdem
