// Twisting resistance of a joint about its normal as a pure kernel: an incremental torsional
// spring k_s J with a Coulomb-type cap, and the relative spin of two blocks about the normal.
#pragma once

#include <Eigen/Core>

namespace blockdem {

/// Per-contact state: the twisting moment the joint exerts on B about the contact normal n
/// (positive counter-clockwise seen from B's side, i.e. about +n); the moment on A is its
/// negative (N m).
struct TwistState {
  double moment = 0.0;  ///< M (N m)
};

/// What one step gives the kernel.
struct TwistIncrement {
  /// dθ: rotation of B relative to A about n over the step (relative_spin) (rad).
  double spin = 0.0;
  double shear_stiffness = 0.0;  ///< k_s of the shear law at this step, per unit area (Pa/m)
  /// J = ∫ |y - c|² dA of the compressed contact area about its centre c (m^4).
  double polar_moment = 0.0;
  /// ∫ σ_n(y) |y - c| dA over the compressed area (N m): σ_n ∫ r dA for a uniform stress (the
  /// point contact), the integral of the law for a face-integrated contact.
  double radial_normal_moment = 0.0;
  double friction_coefficient = 0.0;  ///< μ = tan φ of the shear law at this step (-)
};

struct TwistResult {
  bool sliding = false;    ///< the step ended on the cap
  double stiffness = 0.0;  ///< k_s J (N m / rad)
  double limit = 0.0;      ///< the cap μ ∫ σ_n r dA (N m)
};

/// One step of the torsional spring: M ← M - k_s J dθ, then |M| <= μ ∫ σ_n r dA.
/// Elastic part: a rigid relative rotation dθ of the contact area about its centre gives the
/// shear displacement dθ r in the tangential direction at radius r, hence the shear stress
/// k_s dθ r and the moment k_s dθ ∫ r² dA = k_s J dθ (against the spin). Cap: at full slip the
/// stress at every point is μ σ_n along the tangential direction (Coulomb's law pointwise), so
/// the moment cannot exceed μ ∫ σ_n r dA. Twist is capped apart from the shear force (no
/// force-moment interaction surface): exact for pure twist; when both act, the true limit surface
/// lies inside the box |F| <= μ F_n, |M| <= μ ∫ σ_n r dA, so the joint is somewhat too strong
/// (stated in docs/joint-laws.md).
/// Throws std::invalid_argument for negative stiffness, moments or friction, or non-finite input.
TwistResult update_twist(TwistState& state, const TwistIncrement& increment);

/// Rotation of B relative to A about the unit normal n in a step dt (s): ((ω_B - ω_A) · n) dt,
/// ω the angular velocities (rad/s). A rigid rotation of both blocks together gives zero.
double relative_spin(const Eigen::Vector3d& omega_a, const Eigen::Vector3d& omega_b,
                     const Eigen::Vector3d& normal, double dt);

}  // namespace blockdem
