// The virtual laboratory's joint compression test: a closure path with loading and unloading
// branches, run through the normal-law kernel and, optionally, through the engine on two blocks.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "blockdem/contact/normal_laws.hpp"
#include "blockdem/lab/two_block_rig.hpp"

namespace blockdem {

/// The path: `cycles` times, load from zero closure to the maximum and unload back to zero, in
/// `steps_per_branch` equal closure increments per branch. The maximum is `max_closure`, or the
/// closure at which the law reaches `max_stress`: exactly one of them is given (positive).
struct CompressionTestDef {
  NormalLaw law = ExponentialNormal{};  ///< default: the paper's eq 4
  double max_closure = 0.0;             ///< u_max (m); 0: from max_stress
  double max_stress = 0.0;              ///< sigma_max (Pa); 0: from max_closure
  int cycles = 1;                       ///< load-unload cycles (-), >= 1
  int steps_per_branch = 50;            ///< closure increments per loading or unloading branch (-)

  /// Throws std::invalid_argument naming the parameter ("compression test: ...").
  void validate() const;
};

enum class PathBranch { loading, unloading };
/// "loading" or "unloading".
const char* branch_name(PathBranch branch);

struct CompressionPoint {
  int cycle = 1;  ///< 1-based (-)
  PathBranch branch = PathBranch::loading;
  double closure = 0.0;            ///< u_n (m)
  double normal_stress = 0.0;      ///< sigma_n(u_n) (Pa)
  double tangent_stiffness = 0.0;  ///< d sigma_n / d u_n (Pa/m)
};

struct CompressionCurve {
  std::vector<CompressionPoint> points;  ///< the path's start (zero closure), then every increment
  double max_closure = 0.0;              ///< (m)
  double max_stress = 0.0;               ///< sigma_n(max_closure) (Pa)
};

/// The closure at which `law` carries `stress` (m): the inverse of normal_stress, found with a
/// bracketing root finder to 1e-13 relative. Throws std::invalid_argument unless stress > 0 and
/// finite.
double closure_at_stress(const NormalLaw& law, double stress);

/// The path through the kernel: normal_stress and normal_tangent_stiffness at every point.
CompressionCurve run_compression_kernel(const CompressionTestDef& def);

/// One load level of the engine run.
struct DemCompressionPoint {
  std::size_t kernel_index = 0;  ///< the kernel point whose stress was applied
  double applied_stress = 0.0;   ///< the top block's weight over the joint area (Pa)
  RigReading reading;            ///< at equilibrium
  std::int64_t steps = 0;        ///< steps to reach equilibrium at this level (-)
  bool converged = false;
};

struct DemCompressionRun {
  /// One level per kernel point with positive stress (the zero-stress points are skipped: with no
  /// load and a rebounding top block there is no equilibrium to measure).
  std::vector<DemCompressionPoint> points;
  ContactMode contact_mode = ContactMode::boon2012;  ///< the rig's
  std::int64_t total_steps = 0;                      ///< (-)
  bool converged = true;                             ///< every level reached equilibrium
  std::string message;  ///< the first level that did not converge, empty otherwise
  /// max over levels |u_dem - u_kernel| (m) and the same over the curve's max closure (-).
  double max_closure_difference = 0.0;
  double max_relative_closure_difference = 0.0;
  /// max over levels |sigma_n(u_dem) - applied stress| (Pa) and the same over the max stress (-).
  double max_stress_difference = 0.0;
  double max_relative_stress_difference = 0.0;
};

/// The same path on the two-block rig: for every kernel point with positive stress, the top
/// block's weight is set to that stress times the joint area and the world is run to equilibrium
/// (quasi-static load control); the closure is then read from the block positions. Throws
/// DivergenceError if the run blows up.
DemCompressionRun run_compression_dem(const CompressionTestDef& def, const CompressionCurve& kernel,
                                      const TwoBlockRigDef& rig = {});

}  // namespace blockdem
