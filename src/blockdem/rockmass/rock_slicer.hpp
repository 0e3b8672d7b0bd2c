// Rock slicing (Boon, Houlsby & Utili 2015): a convex region cut by joint sets and excavation
// outlines into convex blocks whose faces remember what made them.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "blockdem/geometry/halfspace.hpp"
#include "blockdem/rockmass/convex_cell.hpp"
#include "blockdem/rockmass/joint_set.hpp"
#include "blockdem/rockmass/planar_extent.hpp"

namespace blockdem {

/// The rock mass's region: a convex, closed set of planes with a name per face.
struct Region {
  std::vector<Halfspace> planes;  ///< unit outward normals (m offsets)
  std::vector<std::string> face_names;
  /// An axis-aligned box; faces x_min, x_max, y_min, y_max, z_min, z_max.
  static Region box(const Eigen::Vector3d& min, const Eigen::Vector3d& max);
  /// Any convex plane set; faces plane_0, plane_1, ...
  static Region from_planes(std::vector<Halfspace> planes);
};

/// A convex volume to excavate (tunnel, slope cut, box): the set {n_i·x <= d_i}.
struct Excavation {
  std::string name;
  std::vector<Halfspace> planes;
};

struct SlicingSettings {
  double min_block_volume = 0.0;  ///< (m^3); 0: no limit
  double max_aspect_ratio = 0.0;  ///< ConvexCell::aspect_ratio limit (-); 0: no limit
  /// What happens to a part that would fall below min_block_volume or exceed the aspect ratio:
  /// merge (the cut is not made there; the part stays with its neighbour) or remove (the part
  /// is deleted and its volume reported).
  enum class SmallBlocks { merge, remove };
  SmallBlocks small_blocks = SmallBlocks::merge;
  /// A plane cuts a block only where it lies at least this far inside it on both sides (m);
  /// 0: 1e-6 of the region's diameter.
  double cut_tolerance = 0.0;
  /// Limits of the work a rock mass may cause (check_slicing_work): the estimated blocks of all
  /// joint sets together, and the estimated joints of one non-persistent set.
  std::int64_t max_blocks = 2000000;
  std::int64_t max_joints = 1000000;
  /// Threads that cut the cells (not a scenario key; the parts are the same for any number):
  /// 0, OpenMP's default (OMP_NUM_THREADS, else every core).
  int threads = 0;
};

struct RockMassSpec {
  Region region;
  std::vector<JointSet> joint_sets;
  std::vector<Excavation> excavations;
  SlicingSettings settings;
};

struct RockMass {
  std::vector<ConvexCell> blocks;
  double region_volume = 0.0;  ///< (m^3)
  int merged_cuts = 0;         ///< cuts not made because a part would have been too small
  double merged_volume = 0.0;  ///< volume of those parts, kept in their neighbours (m^3)
  int removed_blocks = 0;
  double removed_volume = 0.0;  ///< (m^3)
  double cut_tolerance = 0.0;   ///< the tolerance used (m)
  /// The joints of each set (index as in the spec), and their extents (non-persistent only).
  std::vector<std::vector<Joint>> joints;
  std::vector<std::vector<PlanarExtent>> joint_extents;
  /// Outline facets of each excavation.
  std::vector<std::vector<PlanarExtent>> facets;
  std::vector<std::string> region_face_names;

  double total_volume() const;  ///< Σ block volumes (m^3)
  /// Indices of blocks whose centroid lies inside excavation e.
  std::vector<int> blocks_inside(const RockMassSpec& spec, int e) const;
};

/// Cuts the region by every joint set in order, then along every excavation outline. Throws
/// std::invalid_argument "KEY: REASON" for a region that is not closed, a bad joint set, joint
/// sets that would make more blocks or joints than the settings' limits (check_slicing_work,
/// before any joint is placed), or an excavation outside the region. Deterministic.
RockMass slice_rock_mass(const RockMassSpec& spec);

}  // namespace blockdem
