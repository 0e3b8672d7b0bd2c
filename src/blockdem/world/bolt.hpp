// Rock bolts and cables: a tendon along a line through the blocks, tied to them at its ends
// (point-anchored) or along its length by a grout annulus, with dowel action at each joint it
// crosses (docs/support.md).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "blockdem/dynamics/block.hpp"

namespace blockdem {

/// A bolt as given: the line, the tendon, the grout and the dowel. Every force in N, every
/// stiffness of the tendon and dowel in N/m, the grout's per unit length of bolt.
struct BoltSpec {
  std::string name;
  Eigen::Vector3d start = Eigen::Vector3d::Zero();        ///< collar (m)
  Eigen::Vector3d direction = -Eigen::Vector3d::UnitZ();  ///< into the rock (unit, -)
  double length = 0.0;                                    ///< (m)
  double axial_stiffness = 0.0;                           ///< E A / L of the whole tendon (N/m)
  double yield_force = std::numeric_limits<double>::infinity();     ///< tendon (N)
  double rupture_strain = std::numeric_limits<double>::infinity();  ///< tendon (-)
  /// Grout annulus: shear stiffness per unit length (N/m/m); 0: point-anchored at the ends.
  double bond_stiffness = 0.0;
  double bond_strength = std::numeric_limits<double>::infinity();  ///< per unit length (N/m)
  double shear_stiffness = 0.0;  ///< dowel at each joint crossing (N/m); 0: none
  double shear_capacity = std::numeric_limits<double>::infinity();  ///< dowel (N)
  /// The dowel's shear displacement across the bolt at which it breaks in shear (m): the bolt
  /// ruptures and is removed. Infinite: it never breaks in shear.
  double shear_rupture_displacement = std::numeric_limits<double>::infinity();
  double pretension = 0.0;  ///< tendon force at installation, point-anchored bolts (N)

  /// The tendon's E A (N): axial_stiffness · length.
  double axial_rigidity() const { return axial_stiffness * length; }
  bool grouted() const { return bond_stiffness > 0.0; }
  /// Throws std::invalid_argument "KEY: REASON" for an unusable value.
  void validate() const;
};

/// One block's stretch of a bolt: the block and the arc lengths (m from the collar) where the
/// line enters and leaves it.
struct BoltSpan {
  int block = -1;
  double from = 0.0, to = 0.0;  ///< (m)
};

/// A block's planes in the world at its present pose (as Block::update_world_geometry forms
/// them), for a block whose world_planes may be stale or absent.
std::vector<Halfspace> planes_at_pose(const Block& block);

/// A block at its present pose: its vertices and planes in the world (m).
struct PosedBlock {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Halfspace> planes;
};
/// The vertices (Block::to_world) and planes_at_pose of `block`.
PosedBlock posed_block(const Block& block);

/// The blocks a bolt's line passes through, in order from the collar: each block's interval of
/// the segment start + s direction, s in [0, length], found by clipping the segment by the
/// block's planes at its present pose (geometry/segment_clip.hpp). Spans shorter than 1e-9 of
/// the length (a line grazing an edge) are dropped.
std::vector<BoltSpan> bolt_spans(const BoltSpec& spec, const std::vector<Block>& blocks);

/// Why a bolt cannot be installed along these spans (empty: it can): the collar outside every
/// block, the far end outside the rock, or a gap along the line (each by more than 1 % of the
/// length: the line leaves the rock), or no joint crossed.
std::string bolt_span_problem(const BoltSpec& spec, const std::vector<BoltSpan>& spans,
                              const std::vector<Block>& blocks);

/// The tendon of a grouted bolt, solved for static equilibrium given the rock's displacements:
/// nodes 0..n along the bolt, node 0 tied to the collar's block by the face plate, elements
/// between nodes, and grout springs that tie nodes to blocks. Axial displacements along the bolt
/// (m), forces positive in tension (N). One-dimensional: the shear-lag model of a fully grouted
/// bolt (Farmer 1975, Int. J. Rock Mech. Min. Sci. 12:347; Li & Stillborg 1999, Int. J. Rock
/// Mech. Min. Sci. 36:1013), E A u'' = k_b (u - w), discretised by lumping the grout at the
/// nodes (trapezoidal rule).
struct Tendon {
  struct Element {
    double stiffness = 0.0;  ///< E A / h (N/m)
    double plastic = 0.0;    ///< plastic extension (m)
    double force = 0.0;      ///< axial force after the last solve (N)
  };
  struct Spring {
    int node = 0;
    double stiffness = 0.0;  ///< k_b · tributary length (N/m)
    double strength = 0.0;   ///< bond_strength · tributary length (N)
    double slip = 0.0;       ///< plastic slip of the grout (m)
    double force = 0.0;      ///< on the rock, along the bolt, after the last solve (N)
  };
  std::vector<double> u;  ///< node displacements (m), node 0 the plate's
  std::vector<Element> elements;
  std::vector<Spring> springs;
  double yield_force = std::numeric_limits<double>::infinity();  ///< (N)

  /// Solves for u[1..n] given the plate's displacement u[0] and each spring's rock displacement
  /// `rock[k]` (m), elastic-perfectly plastic elements and springs (a Newton iteration on the
  /// set of yielded members, from the last solution), then keeps the plastic parts. Returns
  /// whether any member yielded in this solve. Sets each element's and spring's force.
  bool solve(std::span<const double> rock);
  /// The plate's force on the collar's block along the bolt (N): the tendon's pull at node 0
  /// less the grout's share there.
  double plate_force() const;
};

/// A dowel where a bolt crosses a joint: the crossing point in both blocks' body frames, and an
/// elastic-perfectly plastic spring on their relative displacement across the bolt's axis.
struct BoltCrossing {
  int block_a = -1, block_b = -1;  ///< before and after the crossing along the bolt
  Eigen::Vector3d body_a = Eigen::Vector3d::Zero(), body_b = Eigen::Vector3d::Zero();  ///< (m)
  double at = 0.0;                                    ///< arc length (m)
  Eigen::Vector3d plastic = Eigen::Vector3d::Zero();  ///< plastic shear slip (m), world
  Eigen::Vector3d force = Eigen::Vector3d::Zero();    ///< on block_b (N), world
};

/// A grout spring's (or an end anchor's) place: its block and point in that block's body frame.
struct BoltTie {
  int block = -1;
  Eigen::Vector3d body_point = Eigen::Vector3d::Zero();  ///< (m)
  Eigen::Vector3d installed = Eigen::Vector3d::Zero();   ///< world point at installation (m)
};

/// An installed bolt.
struct Bolt {
  enum class State : std::uint8_t { intact, yielded, ruptured, removed };
  BoltSpec spec;
  std::vector<BoltSpan> spans;
  std::vector<double> node_at;  ///< arc length of each tendon node (m)
  /// Point-anchored: ties[0] the head (collar), ties[1] the anchor (far end). Grouted: one per
  /// spring of the tendon, then the plate's last.
  std::vector<BoltTie> ties;
  Tendon tendon;                   ///< grouted bolts
  double anchored_length = 0.0;    ///< point-anchored: head to anchor at installation (m)
  double plastic_extension = 0.0;  ///< point-anchored (m)
  double axial_force = 0.0;        ///< point-anchored: the tendon's force (N)
  std::vector<BoltCrossing> crossings;
  State state = State::intact;
  bool yielded = false;         ///< the tendon, grout or a dowel has yielded
  double largest_strain = 0.0;  ///< the tendon's largest strain so far (-)

  bool active() const { return state == State::intact || state == State::yielded; }
  /// The largest tendon tension over [from, to] (N).
  double largest_axial_force(double from, double to) const;
};

/// "intact", "yielded", "ruptured" or "removed" (a block it was tied to was excavated).
const char* to_string(Bolt::State state);

/// Installs a bolt along `spans` (bolt_spans) at the blocks' present poses: nodes, ties in the
/// blocks' body frames, dowels at the crossings; a grouted tendon has elements no longer than
/// min(L / 64, 0.25 / α), α = sqrt(k_b / (E A)), and at least one per span.
Bolt install_bolt(const BoltSpec& spec, std::vector<BoltSpan> spans,
                  const std::vector<Block>& blocks);

/// One load of a bolt on a block: a force at a world point, and the member's stiffness for the
/// time step.
struct BoltLoad {
  int block = -1;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  ///< (N)
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< world (m)
  double stiffness = 0.0;                           ///< (N/m)
};

/// The loads of one bolt on its blocks at their present poses: updates its state (tendon,
/// dowels, rupture) and writes its loads into `loads` (emptied first) in a fixed order. Reads the
/// blocks' poses only, so that bolts can be solved side by side.
void bolt_loads(Bolt& bolt, const std::vector<Block>& blocks, std::vector<BoltLoad>& loads);

/// Adds each load's force and moment to its block (force, torque) in the order given, and its
/// stiffness terms to `stiffness` and `rotational` (per block, for the time step).
void add_bolt_loads(std::span<const BoltLoad> loads, std::vector<Block>& blocks,
                    std::vector<double>& stiffness, std::vector<double>& rotational);

}  // namespace blockdem
