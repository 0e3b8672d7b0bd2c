// The twisting resistance of a contact over one step: the contact area's moments, the torsional
// spring (contact/twist.hpp) with the shear law's terms, and the shear force and twisting moment
// held together against Coulomb's law at every point of a face contact (contact/shear_twist.hpp).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <span>

#include "blockdem/collision/contact_geometry.hpp"
#include "blockdem/collision/face_contact.hpp"
#include "blockdem/collision/slice_polygon.hpp"
#include "blockdem/contact/normal_laws.hpp"
#include "blockdem/contact/shear_laws.hpp"
#include "blockdem/contact/shear_twist.hpp"
#include "blockdem/contact/twist.hpp"
#include "blockdem/contact/twist_law.hpp"
#include "blockdem/response/face_twist.hpp"
#include "blockdem/response/normal_response.hpp"
#include "blockdem/response/shear_response.hpp"

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

/// The normal stress over a face contact, which the twist's bounds and full-slip quadratures
/// integrate: its cells of linear closure and the normal law. A point contact has no cells.
struct FaceStress {
  std::span<const ClosureCell> cells;
  const NormalLaw& law;
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

/// The area terms of a contact's torsional spring: over a face contact's cells
/// (face_twist_geometry, about its centre of pressure, the radial moment a lower bound) when the
/// normal response was integrated over them, else over the point contact's slice under its
/// uniform σ_n (slice_twist_geometry). `normal` is the contact normal.
inline TwistGeometry twist_geometry(const NormalResponse& response, const ContactGeometry& g,
                                    const FaceContactGeometry& face,
                                    const Eigen::Vector3d& normal) {
  if (response.integrated)
    return face_twist_geometry(face.cells, normal, response.force, response.force_point);
  return slice_twist_geometry(g.slice, response.stress);
}

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

/// What one step of the torsional spring gave (advance_twist).
struct TwistStep {
  double stiffness = 0.0;  ///< k_s J of the step (N m/rad)
  double slip_work = 0.0;  ///< the work the capped moment dissipated (twist_slip_work) (J)
};

/// One step of a contact's torsional spring (step_contact_twist) under the shear law `law` at
/// the shear state `shear` (before this step's update) and the mean normal stress `normal_stress`
/// (Pa), for B's rotation relative to A about n, `spin` (rad). The radial moment of `geometry` is
/// sharpened only as far as the step needs, and kept there for limit_shear_and_twist: when it is
/// a lower bound that does not certify the elastic trial |M - k_s J dθ| <= μ bound, first to
/// face_radial_normal_bound over `stress`, then to the exact face_radial_normal_moment.
inline TwistStep advance_twist(TwistState& twist, const ShearLaw& law, const ShearState& shear,
                               double normal_stress, TwistGeometry& geometry,
                               const FaceStress& stress, double spin) {
  const double before = twist.moment;
  const TwistLawTerms terms = twist_law_terms(law, shear, normal_stress);
  if (!geometry.exact && terms.friction_coefficient > 0.0) {
    const double trial =
        std::abs(twist.moment - terms.shear_stiffness * geometry.polar_moment * spin);
    if (trial > terms.friction_coefficient * geometry.radial_normal_moment) {
      geometry.radial_normal_moment = face_radial_normal_bound(stress.cells, stress.law, geometry);
      if (trial > terms.friction_coefficient * geometry.radial_normal_moment) {
        geometry.radial_normal_moment =
            face_radial_normal_moment(stress.cells, stress.law, geometry.centre);
        geometry.exact = true;
      }
    }
  }
  TwistStep step;
  step.stiffness = step_contact_twist(twist, terms, geometry, spin);
  step.slip_work = twist_slip_work(before - step.stiffness * spin, twist.moment, step.stiffness);
  return step;
}

/// What the joint's force and moment together did in a step (interact_shear_twist).
struct ShearTwistResult {
  bool slipped = false;     ///< returned to full slip
  bool integrated = false;  ///< a full-slip quadrature ran (the certificate did not suffice)
};

/// After the shear law's update and the torsional spring's: the shear force F (at the force
/// point x_p = `motion.point`) and the moment M of a face contact held against the limit surface
/// of Coulomb's law applied at every point of the contact (shear_twist.hpp). Nothing to do for a
/// translation (M = 0: the law's cap is the limit), a pure turn (F = 0: the spring's cap is),
/// while a bond holds (force and moment capped apart), or when μ = 0; nor when
/// `certified_inside` shows the state inside from the lower bound
/// `geometry.radial_normal_moment` of ∫ σ_n |y - c| dA less F_n |x_p - c|, or, when that is not
/// exact, from face_pressure_radial_bound over `stress`, a lower bound of ∫ σ_n |y - x_p| dA.
/// Otherwise, by face_full_slip over `stress` (the quadrature, per unit μ):
/// 1. along the step's own slip (`motion.slip` du at x_p, m; `motion.turn` dθ about n, rad): if
///    the state spends more power against it than full slip about its centre
///    x_p + n × du / dθ can, it becomes that full slip (the instantaneous-centre solution of
///    the motion);
/// 2. else along the slip the state itself stands for (slip_centre): the same test and return.
/// μ is the law's at the state after its update (twist_law_terms). `load`: F_n (N), the
/// compressed area (m^2) and the mean σ_n (Pa).
inline ShearTwistResult interact_shear_twist(ShearState& shear, TwistState& twist,
                                             const ShearLaw& law, const ContactLoad& load,
                                             const TwistGeometry& geometry,
                                             const FaceStress& stress,
                                             const ContactMotion& motion) {
  ShearTwistResult r;
  if (twist.moment == 0.0 || shear.force.squaredNorm() == 0.0) return r;
  if (strength_of(law).cohesion > 0.0 && !shear.broken()) return r;
  const double mu = twist_law_terms(law, shear, load.stress).friction_coefficient;
  if (!(mu > 0.0)) return r;
  const Eigen::Vector3d& force_point = motion.point;
  const Eigen::Vector3d& normal = motion.normal;
  const double offset = load.force * (geometry.centre - force_point).norm();
  const double force = shear.force.norm(), limit = mu * load.force;
  if (certified_inside(force, twist.moment, limit, mu * (geometry.radial_normal_moment - offset)))
    return r;
  if (!geometry.exact &&
      certified_inside(force, twist.moment, limit,
                       mu * face_pressure_radial_bound(stress.cells, stress.law, geometry,
                                                       load.force, force_point)))
    return r;
  // The test and return along a slip about `centre`.
  const auto slip_about = [&](const SlipCentre& centre) {
    const FullSlip full = face_full_slip(stress.cells, stress.law, normal, force_point, centre);
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
  const Eigen::Vector3d& slip = motion.slip;
  const double turn = motion.turn;
  if (slip.squaredNorm() > 0.0 || turn != 0.0) {
    const SlipCentre centre =
        slip_centre(-load.area * slip, -geometry.polar_moment * turn, normal, force_point,
                    geometry.polar_moment, load.area, geometry.max_radius);
    if (!centre.translation && slip_about(centre)) return r;
    if (centre.translation && slip.squaredNorm() > 0.0) {
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
                                     geometry.polar_moment, load.area, geometry.max_radius);
  if (!own.translation) slip_about(own);
  return r;
}

/// What limit_shear_and_twist did.
struct ShearTwistLimit {
  bool slipped = false;         ///< returned to full slip
  double shear_released = 0.0;  ///< the shear spring's energy the return released (J)
  double twist_released = 0.0;  ///< the torsional spring's energy the return released (J)
};

/// A face contact's shear force and twisting moment held together against Coulomb's law at
/// every point (interact_shear_twist). That limit surface is written about the centre of
/// pressure x_p (`pressure_centre`; a uniform slip's friction has no moment there): the state is
/// taken there, the shear force with the couple that moves it from the shear spring's point
/// x_s = `motion.point`, and the slip of x_p, du + dθ n × (x_p - x_s); and back to x_s after.
/// The spring energies a return releases, from the step's stiffnesses k_s A (`shear_stiffness`,
/// N/m) and k_s J (`twist_stiffness`, N m/rad), are dissipated: the shear spring's comes off
/// `shear.elastic_energy`.
inline ShearTwistLimit limit_shear_and_twist(ShearState& shear, TwistState& twist,
                                             const ShearLaw& law, const ContactLoad& load,
                                             const TwistGeometry& geometry,
                                             const FaceStress& stress, const ContactMotion& motion,
                                             const Eigen::Vector3d& pressure_centre,
                                             double shear_stiffness, double twist_stiffness) {
  ShearTwistLimit out;
  const double stored = shear.force.squaredNorm(), twisted = twist.moment;
  const Eigen::Vector3d& xs = motion.point;
  const Eigen::Vector3d& xp = pressure_centre;
  const Eigen::Vector3d& n = motion.normal;
  // The state about x_p: the moment with the couple that moves the shear force there from x_s,
  // and the slip of x_p.
  TwistState at_p{twist.moment + shear_couple(xs, xp, shear.force, n)};
  ContactMotion at_pressure;
  at_pressure.point = xp;
  at_pressure.normal = n;
  at_pressure.slip = motion.slip + motion.turn * n.cross(xp - xs);
  at_pressure.turn = motion.turn;
  if (!interact_shear_twist(shear, at_p, law, load, geometry, stress, at_pressure).slipped)
    return out;
  twist.moment = at_p.moment - shear_couple(xs, xp, shear.force, n);
  out.slipped = true;
  // The shear spring's energy released by the return, dissipated.
  if (shear_stiffness > 0.0) {
    out.shear_released = 0.5 * (stored - shear.force.squaredNorm()) / shear_stiffness;
    shear.elastic_energy -= out.shear_released;
  }
  out.twist_released = twist_elastic_energy(twisted, twist_stiffness) -
                       twist_elastic_energy(twist.moment, twist_stiffness);
  return out;
}

}  // namespace blockdem
