// The twisting resistance of a world contact over one step: the contact area's moments, the
// torsional spring (contact/twist.hpp) with the shear law's terms, and the spin of the stored
// shear force with the contact frame about the normal.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <span>

#include "blockdem/collision/face_contact.hpp"
#include "blockdem/collision/slice_polygon.hpp"
#include "blockdem/contact/normal_laws.hpp"
#include "blockdem/contact/shear_laws.hpp"
#include "blockdem/contact/shear_twist.hpp"
#include "blockdem/contact/twist.hpp"
#include "blockdem/contact/twist_law.hpp"

namespace blockdem {

/// The area terms of the torsional spring, about the compressed area's centroid c.
struct TwistGeometry {
  double polar_moment = 0.0;  ///< J = ∫ r² dA (m^4)
  /// ∫ σ_n r dA (N m) when `exact`; otherwise a lower bound of it, enough to certify an elastic
  /// step without the full quadrature.
  double radial_normal_moment = 0.0;
  bool exact = true;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< the centroid c (m)
  double max_radius = 0.0;                           ///< r_max: largest vertex distance from c (m)
};

/// Face-integrated contact: J over the cells of linear closure about their centroid, exact and
/// without transcendental functions (each cell fanned about a common point p of the plane,
/// triangle (p, p + u, p + w) giving ∫ |y - p|² dA = A (|u|² + |w|² + u·w)/6, then the
/// parallel-axis theorem). The radial moment is the free lower bound F_n |x_p - c| (x_p the
/// centre of pressure; r >= (y - c)·e for the unit e along x_p - c); `exact` is false.
/// `normal` is the contact normal, `force` F_n (N), `pressure_centre` x_p (m).
TwistGeometry face_twist_geometry(std::span<const ClosureCell> cells, const Eigen::Vector3d& normal,
                                  double force, const Eigen::Vector3d& pressure_centre);

/// A sharper lower bound of ∫ σ_n r dA over the cells (N m): r <= r_max gives
/// ∫ σ_n r dA >= ∫ σ_n r² dA / r_max, and since σ_n is convex in the closure g (linear or
/// exponential law), Jensen's inequality under the weight r² dA / J gives
/// ∫ σ_n r² dA >= J σ_n(ḡ), ḡ = ∫ g r² dA / J (exact polynomial moments,
/// face_closure_polar_moments): one stress evaluation.
double face_radial_normal_bound(std::span<const ClosureCell> cells, const NormalLaw& law,
                                const TwistGeometry& geometry);

/// A lower bound of ∫ σ_n |y - x_p| dA over the cells (N m), the twisting capacity about the
/// centre of pressure x_p (`pressure_centre`, m; `force` F_n, N): the larger of the bound about c
/// less F_n |x_p - c| (r_p >= r_c - d) and (J σ_n(ḡ) - F_n d²) / (r_max + d), from
/// ∫ σ_n r_p² dA = ∫ σ_n r_c² dA - F_n d² (d = |x_p - c|, ∫ σ_n (y - c) dA = F_n (x_p - c)),
/// Jensen's inequality as above and r_p <= r_max + d. The second does not lose F_n d at first
/// order: on a partly open joint, whose x_p lies off c, it can still certify a state inside.
double face_pressure_radial_bound(std::span<const ClosureCell> cells, const NormalLaw& law,
                                  const TwistGeometry& geometry, double force,
                                  const Eigen::Vector3d& pressure_centre);

/// The exact ∫ σ_n r dA over the cells about `centre` (face_twist_moments) (N m).
double face_radial_normal_moment(std::span<const ClosureCell> cells, const NormalLaw& law,
                                 const Eigen::Vector3d& centre);

/// Point contact (boon2012): J of the slice polygon about its centroid and σ_n ∫ r dA for the
/// uniform stress σ_n (Pa) the point contact assumes.
TwistGeometry slice_twist_geometry(const SlicePolygon& slice, double normal_stress);

/// Turns the stored shear force and elastic displacement about the unit normal n by `angle`
/// (rad, counter-clockwise about n): the contact frame's spin, the mean spin of the two blocks
/// ((ω_A + ω_B)/2 · n) dt. A rigid rotation of both blocks then carries the force with them.
void spin_shear_state(ShearState& state, const Eigen::Vector3d& normal, double angle);

/// The centroid of a face contact's compressed area, the union of its cells (m); `fallback`
/// where the cells have no area.
Eigen::Vector3d compressed_area_centroid(std::span<const ClosureCell> cells,
                                         const Eigen::Vector3d& fallback);

/// The centroid of a point contact's slice polygon, in world coordinates (m); `fallback` where
/// the slice has no area.
Eigen::Vector3d slice_centroid(const SlicePolygon& slice, const Eigen::Vector3d& fallback);

/// The energy stored in a contact's torsional spring, M² / (2 k_s J) (J): `moment` M (N m),
/// `stiffness` k_s J of the step (N m/rad); zero without a spring. The energy ledger's elastic
/// term adds it to the normal and shear springs' (joint_elastic_energy).
inline double twist_elastic_energy(double moment, double stiffness) {
  return stiffness > 0.0 ? 0.5 * moment * moment / stiffness : 0.0;
}

/// The work the twisting moment dissipates when a step's trial moment `trial` (N m) is capped to
/// `moment`: the moment times the slip part of the turn, |M| (|M_trial| - |M|) / (k_s J) (J), as
/// the shear law's plastic work is the capped force times the slip. Zero when nothing was capped.
inline double twist_slip_work(double trial, double moment, double stiffness) {
  if (!(stiffness > 0.0) || !(std::abs(trial) > std::abs(moment))) return 0.0;
  return std::abs(moment) * (std::abs(trial) - std::abs(moment)) / stiffness;
}

/// One step of a contact's torsional spring (update_twist) with the shear law's terms at σ_n
/// (twist_law_terms), the area terms `geometry` and B's rotation relative to A about n, `spin`
/// (rad). Returns k_s J, the spring (N m/rad), for the rotational stiffness of the time step.
double step_contact_twist(TwistState& twist, const TwistLawTerms& terms,
                          const TwistGeometry& geometry, double spin);

/// The same, sharpening the radial moment only as far as the step needs: when the geometry
/// holds a lower bound that does not certify the elastic trial |M - k_s J dθ| <= μ bound, first
/// `better_bound()`, then `exact_radial()` (both N m).
template <class BetterBound, class ExactRadial>
double advance_contact_twist(TwistState& twist, const ShearLaw& law, const ShearState& shear,
                             double normal_stress, TwistGeometry geometry, double spin,
                             BetterBound&& better_bound, ExactRadial&& exact_radial) {
  const TwistLawTerms terms = twist_law_terms(law, shear, normal_stress);
  if (!geometry.exact && terms.friction_coefficient > 0.0) {
    const double trial =
        std::abs(twist.moment - terms.shear_stiffness * geometry.polar_moment * spin);
    if (trial > terms.friction_coefficient * geometry.radial_normal_moment) {
      geometry.radial_normal_moment = better_bound();
      if (trial > terms.friction_coefficient * geometry.radial_normal_moment) {
        geometry.radial_normal_moment = exact_radial();
        geometry.exact = true;
      }
    }
  }
  return step_contact_twist(twist, terms, geometry, spin);
}

/// What the joint's force and moment together did in a step (interact_shear_twist).
struct ShearTwistResult {
  bool slipped = false;     ///< returned to full slip
  bool integrated = false;  ///< a full-slip quadrature ran (the certificate did not suffice)
};

/// After the shear law's update and the torsional spring's: the shear force F (at the force
/// point x_p) and the moment M of a face contact held against the limit surface of Coulomb's law
/// applied at every point of the contact (shear_twist.hpp). Nothing to do for a translation
/// (M = 0: the law's cap is the limit), a pure turn (F = 0: the spring's cap is), while a bond
/// holds (force and moment capped apart), or when μ = 0; nor when `certified_inside` shows the
/// state inside from the lower bound `geometry.radial_normal_moment` of ∫ σ_n |y - c| dA less
/// F_n |x_p - c|, or, when that is not exact, from `better_bound()`, a lower bound of
/// ∫ σ_n |y - x_p| dA (face_pressure_radial_bound). Otherwise, by `full_slip_at(SlipCentre)`
/// (the quadrature, per unit μ):
/// 1. along the step's own slip (`slip` du at x_p, m; `turn` dθ about n, rad): if the state
///    spends more power against it than full slip about its centre x_p + n × du / dθ can, it
///    becomes that full slip (the instantaneous-centre solution of the motion);
/// 2. else along the slip the state itself stands for (slip_centre): the same test and return.
/// μ is the law's at the state after its update (twist_law_terms). `normal_force` F_n (N),
/// `area` the compressed area (m^2), `normal_stress` the mean σ_n (Pa).
template <class BetterBound, class FullSlipAt>
ShearTwistResult interact_shear_twist(ShearState& shear, TwistState& twist, const ShearLaw& law,
                                      double normal_stress, double normal_force, double area,
                                      TwistGeometry geometry, const Eigen::Vector3d& force_point,
                                      const Eigen::Vector3d& normal, const Eigen::Vector3d& slip,
                                      double turn, BetterBound&& better_bound,
                                      FullSlipAt&& full_slip_at) {
  ShearTwistResult r;
  if (twist.moment == 0.0 || shear.force.squaredNorm() == 0.0) return r;
  if (strength_of(law).cohesion > 0.0 && !shear.broken()) return r;
  const double mu = twist_law_terms(law, shear, normal_stress).friction_coefficient;
  if (!(mu > 0.0)) return r;
  const double offset = normal_force * (geometry.centre - force_point).norm();
  const double force = shear.force.norm(), limit = mu * normal_force;
  if (certified_inside(force, twist.moment, limit, mu * (geometry.radial_normal_moment - offset)))
    return r;
  if (!geometry.exact && certified_inside(force, twist.moment, limit, mu * better_bound()))
    return r;
  // The test and return along a slip about `centre`.
  const auto slip_about = [&](const SlipCentre& centre) {
    const FullSlip full = full_slip_at(centre);
    r.integrated = true;
    if (!exceeds_full_slip(shear.force, twist.moment, centre, force_point, normal, full, mu))
      return false;
    shear.force = mu * full.force;
    twist.moment = mu * full.moment;
    r.slipped = true;
    return true;
  };
  // 1. The step's own slip: the springs' response -(A du, J dθ) has its centre where the motion
  // is still. A translation (dθ = 0, or a centre very far) has the law's limit |F| <= μ F_n.
  if (slip.squaredNorm() > 0.0 || turn != 0.0) {
    const SlipCentre motion =
        slip_centre(-area * slip, -geometry.polar_moment * turn, normal, force_point,
                    geometry.polar_moment, area, geometry.max_radius);
    if (!motion.translation && slip_about(motion)) return r;
    if (motion.translation && slip.squaredNorm() > 0.0) {
      const Eigen::Vector3d along = slip.normalized();
      if (-shear.force.dot(along) > limit) {
        shear.force = -limit * along;
        twist.moment = 0.0;
        r.slipped = true;
        return r;
      }
    }
  }
  // 2. The slip the state stands for.
  const SlipCentre own = slip_centre(shear.force, twist.moment, normal, force_point,
                                     geometry.polar_moment, area, geometry.max_radius);
  if (!own.translation) slip_about(own);
  return r;
}

}  // namespace blockdem
