// The per-contact shear state, the kinematic increment a shear kernel consumes, its result, and the
// rotation that carries the stored shear vectors into a contact's new tangent plane.
#pragma once

#include <Eigen/Core>

#include "blockdem/contact/joint_strength.hpp"

namespace blockdem {

/// Conventions. A contact joins a first body A and a second body B; the unit normal n points from A
/// to B. The normal force on B is +F_n n. The shear force stored here is the force the joint
/// exerts on B (the force on A is its negative), so an elastic step adds -k_s A_c du.
/// The paper's Appendix (eqs 9-16) uses the opposite sign for du; its equations hold unchanged
/// with du replaced by -du.
struct ShearState {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  ///< shear force on B, in the tangent plane (N)
  /// Degrading law only (zero for the others): the elastic shear displacement U_e, whose
  /// magnitude is eq 5's u_s. It follows du while the joint sticks, stops growing at u_peak, and
  /// does not follow Mohr-Coulomb sliding (m).
  Eigen::Vector3d elastic_displacement = Eigen::Vector3d::Zero();
  /// beta: accumulated magnitude of plastic slip, sum |du_p| (eqs 11-12) (m). The friction of the
  /// continuously-yielding law hardens with it; the other laws accumulate it for reporting.
  double plastic_slip = 0.0;
  /// Energy stored in the shear spring (J), accumulated by update_shear step by step.
  double elastic_energy = 0.0;
  /// Whether the joint's bond (cohesion, tensile strength) still holds; once broken it stays
  /// broken and the joint has the residual strength. Stays intact for a joint that cannot break.
  BondState bond = BondState::intact;

  /// Not intact: a limit has been reached, or the contact was never bonded.
  bool broken() const { return bond != BondState::intact; }
};

/// What the world measured at a contact during one time step.
struct ShearIncrement {
  /// du: displacement increment of B relative to A at the contact point, in the current tangent
  /// plane (m). A component along `normal` is removed before use.
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();
  double normal_force = 0.0;   ///< F_n at the end of the step, compression positive (N)
  double normal_stress = 0.0;  ///< sigma_n at the end of the step, compression positive (Pa)
  double contact_area = 0.0;   ///< A_c (m^2); must be positive while F_n > 0
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit contact normal, from A to B (-)
};

/// Diagnostics of one shear update (the new force is in ShearState::force).
struct ShearResult {
  bool sliding = false;             ///< the step was plastic: the force ended on the yield surface
  double stiffness = 0.0;           ///< elastic stiffness used in the step, k_s A_c (N/m)
  double plastic_multiplier = 0.0;  ///< Lambda of eqs 13-15, continuously-yielding law (m/N)
  double slip_increment = 0.0;      ///< |du_p|, plastic slip in this step (m)
  double plastic_work = 0.0;        ///< energy dissipated by slip in this step, -F . du_p (J)
  bool broke = false;               ///< the bond broke in this step (see ShearState::bond)
};

/// Rotates `force` (a vector in the plane normal to old_normal) by the smallest rotation that takes
/// old_normal to new_normal, the tilt of the contact plane during a step. Any component of `force`
/// along old_normal is dropped first; the result lies in the new plane and has the magnitude of the
/// in-plane part of `force`. Spin of the contact about its normal is not visible in the normals:
/// the world applies it separately (a rotation about new_normal). Throws std::invalid_argument if a
/// normal is not a unit vector or the normals are opposite (no unique rotation).
Eigen::Vector3d rotate_into_plane(const Eigen::Vector3d& force, const Eigen::Vector3d& old_normal,
                                  const Eigen::Vector3d& new_normal);

/// Applies rotate_into_plane to every vector of `state` (force and elastic displacement).
void rotate_into_plane(ShearState& state, const Eigen::Vector3d& old_normal,
                       const Eigen::Vector3d& new_normal);

}  // namespace blockdem
