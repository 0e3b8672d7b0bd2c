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
/// Area, J and ∫ r dA are exact (polygon_moments). ∫ σ_n r dA: on a cell where σ_n is linear
/// (the linear law; the exponential law within 1e-6 of the cell's largest stress by its chord,
/// face_full_slip) in closed form, exact to round-off; the exponential law otherwise by its
/// closed radial integrals and Gauss-Legendre in angle (face_full_slip); otherwise by the
/// 7-point degree-5 rule of
/// Dunavant (1985, Int. J. Numer. Meth. Eng. 21, Table I, n = 7) on each fan triangle split into
/// 16 similar triangles: r is smooth on each piece except at the centre, where it is continuous,
/// so the rule converges like h³ there (about 1e-4 relative on a square under uniform closure).
FaceTwistMoments face_twist_moments(std::span<const ClosureCell> cells, const NormalLaw& law,
                                    const Eigen::Vector3d& centre);

/// ∫ r² dA and ∫ g r² dA over the cells, r = |y - centre| and g the closure (m^4 and m^5), by
/// the closed forms of polynomials of degree 2 and 3 over each fan triangle of each cell (from
/// the vertices: no quadrature, no stress evaluation, no square root).
struct ClosurePolarMoments {
  double polar_moment = 0.0;          ///< ∫ r² dA (m^4)
  double closure_polar_moment = 0.0;  ///< ∫ g r² dA (m^5)
};
ClosurePolarMoments face_closure_polar_moments(std::span<const ClosureCell> cells,
                                               const Eigen::Vector3d& centre);

/// Full slip of B about the instantaneous centre `centre` (SlipCentre) over the cells, per unit
/// friction coefficient (FullSlip: force, moment about `force_point`, power). With d = y - p and
/// the two integrals V = ∫ σ_n d / |d| dA and W = ∫ σ_n |d| dA, the force is -s n × V, the
/// power W and the moment about x_p -s (W + (p - x_p) · V). Per cell:
/// - σ_n linear over the cell (the linear law always: the closure is linear; the exponential law
///   when its chord in g between the cell's least and largest closures is within 1e-6 of the
///   largest stress, the bound b² (σ(g_max) + a) Δg² / 8 of a convex function above its chord):
///   V and W in closed form over the signed fan of triangles (p, v_i, v_i+1), one logarithm and
///   three square roots per edge (linear_slip_sums in the source), exact to round-off; the
///   stress gradient comes from the cell's largest fan triangle, so only on a cell that is not a
///   sliver (twice that triangle's area at least 1e-6 of the diameter squared) and whose every
///   vertex agrees with it (1e-9 of the largest stress, or the round-off of closures computed at
///   the coordinates' magnitude): a sliver's closures, at nearly coincident vertices, need not
///   be those of one plane;
/// - the exponential law otherwise (a partly open joint): along a ray from p the closure is
///   linear in r, so ∫ σ_n r^m dr (m = 1, 2) is a closed form in expm1 and φ_j(x) =
///   ∫_0^1 exp(-x (1 - t)) t^j dt; the angle by 4-point Gauss-Legendre along each edge in
///   u = asinh(s / |h|) (the integrands analytic in u), on pieces at most 2 in u and 1 in b g;
///   a centre outside the cell starts its rays on the chord between the two tangent vertices,
///   never extrapolating the closure; 2e-6 of F_n;
/// - otherwise by the rule of face_twist_moments (7 points on each of 16 sub-triangles of every
///   fan triangle; the slip direction is smooth except at p, so about 1e-4 relative under uniform
///   closure, 2e-3 with p inside the cell); a sliver by the rule on its fan triangles alone (its
///   area below 5e-7 D²: the error is below 1e-6 of a contact of that size);
/// - a centre beyond 1e3 cell diameters: the 7-point rule on the fan triangles alone (the
///   direction is smooth over the cell; the closed forms' terms would cancel from D² a σ_n).
FullSlip face_full_slip(std::span<const ClosureCell> cells, const NormalLaw& law,
                        const Eigen::Vector3d& normal, const Eigen::Vector3d& force_point,
                        const SlipCentre& centre);

/// Full slip by the rule alone (7 points on each of 16 sub-triangles of every fan triangle of
/// every cell): the reference face_full_slip falls back on, kept as its check.
FullSlip face_full_slip_by_rule(std::span<const ClosureCell> cells, const NormalLaw& law,
                                const Eigen::Vector3d& normal, const Eigen::Vector3d& force_point,
                                const SlipCentre& centre);

}  // namespace blockdem
