// A contact's side of the energy ledger over one step: what its shear spring holds, and the work
// its shear and normal forces do on the blocks that no spring holds (docs/outputs.md, "Energy").
#pragma once

#include <variant>

#include <Eigen/Core>

#include "blockdem/contact/shear_laws.hpp"
#include "blockdem/contact/shear_state.hpp"
#include "blockdem/dynamics/block.hpp"

namespace blockdem {

// Both parts count work by the trapezoidal rule of central differences, the rule by which the
// leapfrog's blocks receive a force's work (world/energy_budget.hpp; Hairer, Lubich & Wanner,
// Geometric Numerical Integration, 2nd ed., 2006, ch. I.1.4): the force F_n of step n acts over
// ½ Δt_n with the velocities v_{n-1/2} and over ½ Δt_n with v_{n+1/2}, the second half counted in
// the next step.

/// The shear spring's side of a step (J).
struct ShearSpringEnergy {
  double stored = 0.0;    ///< the energy the spring holds after the step
  double unstored = 0.0;  ///< work done on the spring in the step that it does not hold
};

/// The shear spring's energy after a step and the work done on it that it does not hold, from
/// the force F_0 (N) and energy E_0 (J) before the step (after the carry into this step's
/// frame), the state and result the shear law left, and the step's slip du (m).
/// The work done on the spring is -½ (F_0 + F_1) · du. A linear spring F = -k U_e (every law but
/// `degrading`) holds |F_1|² / (2 k) at the step's stiffness k = k_s A_c, zero with its force;
/// the rest of the work is dissipated: the slip's, and the energy a change of k under a held
/// force gives or takes. k follows the compressed area and σ_n, and such a spring has no
/// potential: split by the law, dE = F·dF / k at the new k, a force that a falling cap removes at
/// a tiny area (a joint opening) releases ½ |F_0|² / k where the spring held ½ |F_0|² / k_0, and
/// a stored energy left negative is lost with the contact. The `degrading` law's stiffness falls
/// with U_e (eq 5 of Boon, Houlsby & Utili 2015): a nonlinear spring whose energy is the law's,
/// by increments, and whose slip's work is the law's.
inline ShearSpringEnergy shear_spring_energy(const ShearLaw& law,
                                             const Eigen::Vector3d& force_before,
                                             double energy_before, const ShearState& after,
                                             const ShearResult& result,
                                             const Eigen::Vector3d& slip) {
  if (std::holds_alternative<DegradingShear>(law))
    return {after.elastic_energy, result.plastic_work};
  const double held = after.force.squaredNorm();
  ShearSpringEnergy e;
  if (held == 0.0) {
    e.stored = 0.0;
  } else if (result.stiffness > 0.0) {
    e.stored = 0.5 * held / result.stiffness;
  } else {
    e.stored = energy_before;
  }
  const double work = -0.5 * (force_before + after.force).dot(slip);
  e.unstored = work - (e.stored - energy_before);
  return e;
}

/// A contact's normal force at one level, as the step's loads apply it.
struct NormalLevel {
  double force = 0.0;                                 ///< F_n (N), on B along +normal
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< (-)
  Eigen::Vector3d point = Eigen::Vector3d::Zero();    ///< x_f, where it acts (m)
  double energy = 0.0;                                ///< the energy the ledger shows for it (J)
};

/// The rate at which B moves away from A along the unit normal n at x (m/s, negative when
/// closing), from the blocks' velocities v_{n-1/2}, ω_{n-1/2} about their centroids `back`
/// seconds of those velocities before their present ones.
inline double opening_rate(const Block& a, const Block& b, const Eigen::Vector3d& x,
                           const Eigen::Vector3d& n, double back) {
  const Eigen::Vector3d vb =
      b.velocity + b.angular_velocity.cross(x - (b.position - back * b.velocity));
  const Eigen::Vector3d va =
      a.velocity + a.angular_velocity.cross(x - (a.position - back * a.velocity));
  return n.dot(vb - va);
}

/// The work a contact's normal force does on its springs in the step that the energy the ledger
/// shows for them does not hold (J), from the blocks A and B at level n (velocities v_{n-1/2}),
/// the last step's force `last` and this step's `now`:
///   W = -½ [Δt_n F_n n_n · v_rel(x_n) + Δt_{n-1} F_{n-1} n_{n-1} · v_rel(x_{n-1})] - ΔE,
/// v_rel the relative velocity of B's and A's material points, the last force's lever arms about
/// the centroids of its own level (as its torque was applied). The energy shown, E, is ½ F_n δ
/// for a point contact and ∫ e(g) dA for a face contact. Neither force is the gradient of it in
/// general: the point contact's σ_n(δ) A_c at x_c (Boon et al. 2012) follows the shape of the
/// overlap (A_c and x_c; ½ F_n δ is the energy of a uniform closure only: 8% short of the work
/// done for a cube whose base joint is partly open), and a face contact's integrated force acts
/// along the narrow phase's normal, which on an edge is not the face's (a prism rocking on its
/// edges: 1.7% of the largest term in 0.7 s). The ledger counts the difference with the
/// contact's dissipation, where it would otherwise stay as a residual
/// (tests/validation/energy_ledger_test.cpp); on a face pressed flat it is round-off.
inline double normal_unstored_work(const Block& a, const Block& b, const NormalLevel& last,
                                   double last_dt, const NormalLevel& now, double dt) {
  const double into_spring =
      -0.5 * (dt * now.force * opening_rate(a, b, now.point, now.normal, 0.0) +
              last_dt * last.force * opening_rate(a, b, last.point, last.normal, last_dt));
  return into_spring - (now.energy - last.energy);
}

}  // namespace blockdem
