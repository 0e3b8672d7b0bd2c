// Shear force and twisting moment of a joint together: the interaction of the two springs under
// Coulomb's law applied pointwise over the contact area, by the instantaneous centre of the slip.
#pragma once

#include <Eigen/Core>

namespace blockdem {

/// The rigid in-plane slip of B relative to A that the elastic state (F, M) stands for. Under a
/// uniform k_s the springs F = -k_s A u0 and M = -k_s J θ are the resultants of the affine
/// shear displacement field u(y) = u0 + θ n × (y - x_p), a rotation θ about the instantaneous
/// centre p = x_p + n × u0 / θ = x_p + (J / (A M)) n × F, where u(p) = 0.
struct SlipCentre {
  /// The field is a translation (M = 0, or p farther than 1e6 contact radii): the shear law's own
  /// cap |F| <= μ F_n is then the whole limit surface.
  bool translation = true;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< p (m)
  double sense = 0.0;                               ///< sign of θ: -sign(M) (-)
};

/// The centre of the slip of the elastic state (force F on B in the tangent plane, N; moment M on
/// B about the unit normal n, N m) with the force acting at x_p (m); J (m^4), A (m^2) and the
/// contact's radius (m) set the scale.
SlipCentre slip_centre(const Eigen::Vector3d& force, double moment, const Eigen::Vector3d& normal,
                       const Eigen::Vector3d& force_point, double polar_moment, double area,
                       double radius);

/// What full slip about a centre p gives, per unit friction coefficient: the traction on B is
/// -μ σ_n(y) ŵ(y), ŵ the unit slip direction of w(y) = s n × (y - p) (s = SlipCentre::sense).
struct FullSlip {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  ///< -∫ σ_n ŵ dA (N)
  double moment = 0.0;  ///< -∫ ((y - x_p) × σ_n ŵ) · n dA, about the force point (N m)
  double power = 0.0;   ///< ∫ σ_n |w| dA: the dissipation of the unit slip rate (N m)
};

/// Whether the elastic state lies outside the joint's limit surface, tested along its own slip:
/// the limit surface of Coulomb's law applied pointwise is convex and full slip about p is its
/// point of largest dissipation for the slip rate (v, s), v = s n × (x_p - p) (Goyal, Ruina &
/// Papadopoulos 1991, Wear 143, eq 14: the maximum-power inequality). So a state whose power
/// -(F · v + M s) exceeds μ ∫ σ_n |w| dA cannot be carried: the joint slips.
bool exceeds_full_slip(const Eigen::Vector3d& force, double moment, const SlipCentre& centre,
                       const Eigen::Vector3d& force_point, const Eigen::Vector3d& normal,
                       const FullSlip& slip, double friction_coefficient);

/// A certificate that the state lies inside the limit surface without integrating: the surface
/// contains the disc |F| <= μ F_n at M = 0 (every point sliding the same way; no moment about
/// the centre of pressure) and the states (0, ±M_c / 2), M_c the moment of full slip about the
/// area's centroid c (whose force is at most μ F_n); by convexity it contains
/// |F| / (μ F_n) + 2 |M| / M_c <= 1. `moment_bound` is a lower bound of M_c (N m), such as
/// μ (∫ σ_n |y - c| dA - F_n |x_p - c|) with a lower bound of the integral.
bool certified_inside(double force, double moment, double friction_limit, double moment_bound);

}  // namespace blockdem
