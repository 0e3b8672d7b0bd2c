// A scenario's rock mass: the [rock_mass], [[joint_sets]], [[excavations]] and [[boundaries]]
// keys read and checked, the region sliced, and the blocks made for the world with one joint
// law per face.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "blockdem/response/in_situ.hpp"
#include "blockdem/rockmass/rock_slicer.hpp"
#include "blockdem/scenario/checked_table.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

/// Blocks touching chosen region faces held in place, on rollers, or loaded by a stress.
struct BoundaryCondition {
  std::vector<int> faces;  ///< region face indices
  /// fixed: the block never moves; roller: it cannot move along the face normal (an axis) nor
  /// rotate, and slides freely along the face; stress: the traction -σ m of a stress field on
  /// the block's faces there (m their outward normal), a constant force and moment.
  enum class Kind { fixed, roller, stress } kind = Kind::fixed;
  /// stress: the field (the in-situ field, or a uniform stress given with the boundary).
  StressField stress;
};

struct RockMassModel {
  RockMassSpec spec;
  RockMass rock_mass;
  std::string group = "rock";  ///< block group of every block
  double density = 0.0;        ///< (kg/m^3)
  std::vector<int> set_laws;   ///< joint law index per set (-1: the default)
  int default_law = -1;        ///< [rock_mass] law: faces without a law of their own
  int bonded_law = -1;         ///< [rock_mass] bonded_law (-1: the face's joint set law)
  std::vector<BoundaryCondition> boundaries;

  /// Name of block i ("rock_1", ...).
  static std::string block_name(std::size_t i);
  /// The joint law of a face from its tag (-1: group rules).
  int law_of(const FaceTag& tag) const;
  /// A readable label of a face tag ("J1", "J1 bonded", "region x_min", "excavation tunnel").
  std::string label(const FaceTag& tag) const;
};

/// Reads the rock-mass keys of a scenario's root table (the caller has read [[materials]] and
/// [[joint_laws]] into `materials` (density by name) and `laws` (index by name)) and slices
/// the region on `cut_threads` threads (SlicingSettings::threads). Throws ScenarioError naming
/// file, key and reason.
RockMassModel read_rock_mass(const CheckedTable& root,
                             const std::map<std::string, double>& materials,
                             const std::map<std::string, int>& laws,
                             const std::optional<StressField>& in_situ = std::nullopt,
                             int cut_threads = 1);

/// The world blocks of a sliced rock mass, each with its per-plane joint laws (indices into the
/// scenario's joint laws; -1 for a plane without one) and the boundary conditions applied.
struct RockMassBlocks {
  std::vector<Block> blocks;
  std::vector<std::vector<int>> face_laws;
  /// Per block, the joint set that made each plane (-1: none).
  std::vector<std::vector<int>> face_sets;
  /// The names of the blocks inside each excavation, by excavation name.
  std::map<std::string, std::vector<std::string>> excavated;
};
/// Made on `threads` threads (0: OpenMP's default); the blocks are the same for any number.
RockMassBlocks make_rock_mass_blocks(const RockMassModel& model, int threads = 0);

}  // namespace blockdem
