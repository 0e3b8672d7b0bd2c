// What a face-integrated contact's cells give the twisting kernel (contact/twist.hpp): the polar
// moment of the compressed area and the normal stress's radial moment about a centre.
#pragma once

#include <Eigen/Core>
#include <span>

#include "blockdem/collision/face_contact.hpp"
#include "blockdem/contact/normal_laws.hpp"
#include "blockdem/contact/shear_twist.hpp"

namespace blockdem {

struct FaceTwistMoments {
  double compressed_area = 0.0;  ///< ∫ dA over the cells (m^2)
  double polar_moment = 0.0;     ///< J = ∫ |y - c|² dA over the cells (m^4)
  double radial_moment = 0.0;    ///< ∫ |y - c| dA over the cells (m^3)
  /// ∫ σ_n(g(y)) |y - c| dA over the cells (N m): the Coulomb cap of the twisting moment is μ
  /// times this.
  double radial_normal_moment = 0.0;
};

/// Moments about `centre` (a point of the contact plane, m) over the cells of linear closure.
/// Area, J and ∫ r dA are exact (polygon_moments); ∫ σ_n r dA by the 7-point degree-5 rule of
/// Dunavant (1985, Int. J. Numer. Meth. Eng. 21, Table I, n = 7) on each fan triangle split into
/// 16 similar triangles: r is smooth on each piece except at the centre, where it is continuous,
/// so the rule converges like h³ there (about 1e-4 relative on a square under uniform closure).
FaceTwistMoments face_twist_moments(std::span<const ClosureCell> cells, const NormalLaw& law,
                                    const Eigen::Vector3d& centre);

/// ∫ r² dA and ∫ g r² dA over the cells, r = |y - centre| and g the closure (m^4 and m^5), by
/// the 7-point degree-5 rule on each fan triangle of each cell: exact (the integrands are
/// polynomials of degree 2 and 3), and cheap (no stress evaluation, no square root).
struct ClosurePolarMoments {
  double polar_moment = 0.0;          ///< ∫ r² dA (m^4)
  double closure_polar_moment = 0.0;  ///< ∫ g r² dA (m^5)
};
ClosurePolarMoments face_closure_polar_moments(std::span<const ClosureCell> cells,
                                               const Eigen::Vector3d& centre);

/// Full slip of B about the instantaneous centre `centre` (SlipCentre) over the cells, per unit
/// friction coefficient (FullSlip: force, moment about `force_point`, power), by the same rule
/// as face_twist_moments (7 points on each of 16 sub-triangles of every fan triangle; the slip
/// direction is smooth except at the centre, so about 1e-4 relative under uniform closure).
FullSlip face_full_slip(std::span<const ClosureCell> cells, const NormalLaw& law,
                        const Eigen::Vector3d& normal, const Eigen::Vector3d& force_point,
                        const SlipCentre& centre);

}  // namespace blockdem
