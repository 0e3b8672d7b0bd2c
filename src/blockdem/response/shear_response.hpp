// A contact's shear response over one step: the stored shear state carried into this step's
// contact frame, the slip of B relative to A where the shear spring acts, and the shear law's
// update (contact/shear_laws.hpp) for that increment.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "blockdem/contact/shear_laws.hpp"
#include "blockdem/contact/shear_state.hpp"
#include "blockdem/response/normal_response.hpp"

namespace blockdem {

/// A contact's relative motion over one step, seen at one point of the contact.
struct ContactMotion {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();    ///< where the motion is seen (m)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit contact normal n, from A to B (-)
  Eigen::Vector3d slip = Eigen::Vector3d::Zero();     ///< du: B's slip relative to A there (m)
  double turn = 0.0;  ///< dθ: B's rotation relative to A about n (rad)
};

/// Turns the stored shear force and elastic displacement about the unit normal n by `angle`
/// (rad, counter-clockwise about n): the contact frame's spin, the mean spin of the two blocks
/// ((ω_A + ω_B)/2 · n) dt. A rigid rotation of both blocks then carries the force with them.
void spin_shear_state(ShearState& state, const Eigen::Vector3d& normal, double angle);

/// The contact frame's spin about the unit normal n over a step dt (s): the blocks' mean
/// ((ω_A + ω_B)/2 · n) dt (rad), ω the angular velocities (rad/s).
inline double frame_spin(const Eigen::Vector3d& omega_a, const Eigen::Vector3d& omega_b,
                         const Eigen::Vector3d& normal, double dt) {
  return 0.5 * (omega_a + omega_b).dot(normal) * dt;
}

/// Carries a contact's stored shear state into this step's frame: into the new tangent plane by
/// the smallest rotation from `previous_normal` to `normal` (rotate_into_plane), then about the
/// new normal by the frame's spin `spin` (rad; zero without twist: spin_shear_state).
inline void carry_shear_state(ShearState& shear, const Eigen::Vector3d& previous_normal,
                              const Eigen::Vector3d& normal, double spin) {
  rotate_into_plane(shear, previous_normal, normal);
  spin_shear_state(shear, normal, spin);
}

/// B's slip relative to A over a step dt (s) in the tangent plane of the unit normal n (m): the
/// relative velocity of the material points, v_B(x) - v_A(x) (m/s), less its part along n,
/// times dt.
inline Eigen::Vector3d tangential_slip(const Eigen::Vector3d& relative_velocity,
                                       const Eigen::Vector3d& normal, double dt) {
  return (relative_velocity - relative_velocity.dot(normal) * normal) * dt;
}

/// The shear law's update (update_shear) for the step's slip `motion.slip` at the shear spring's
/// point under the normal load `load`: the new force in `shear`, the law's diagnostics returned.
inline ShearResult shear_response(ShearState& shear, const ShearLaw& law, const ContactLoad& load,
                                  const ContactMotion& motion) {
  ShearIncrement inc;
  inc.displacement = motion.slip;
  inc.normal_force = load.force;
  inc.normal_stress = load.stress;
  inc.contact_area = load.area;
  inc.normal = motion.normal;
  return update_shear(law, shear, inc);
}

/// The couple about the unit normal n that moves the shear force F from `from` to `to` (N m):
/// ((to - from) × F) · n. From the force point x_f to the shear spring's point x_s, it is the
/// couple on B that the force point alone misses.
inline double shear_couple(const Eigen::Vector3d& to, const Eigen::Vector3d& from,
                           const Eigen::Vector3d& force, const Eigen::Vector3d& normal) {
  return (to - from).cross(force).dot(normal);
}

}  // namespace blockdem
