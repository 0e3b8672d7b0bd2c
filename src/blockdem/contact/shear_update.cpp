// The incremental shear update of one contact over one time step, per shear law: an elastic trial
// force, then the law's yield condition (a Mohr-Coulomb cap, or the implicit return mapping of the
// continuously-yielding law of Boon, Houlsby & Utili 2015, Appendix eqs 9-16).
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "blockdem/contact/law_params.hpp"
#include "blockdem/contact/shear_laws.hpp"
#include "blockdem/numerics/bracketed_root.hpp"

namespace blockdem {
namespace {

/// The kinematics of a step on a closed joint, checked.
struct ClosedStep {
  Eigen::Vector3d du;    ///< tangential displacement increment of B relative to A (m)
  double normal_force;   ///< F_n > 0 (N)
  double normal_stress;  ///< sigma_n > 0 (Pa)
  double area;           ///< A_c > 0 (m^2)
};

void require_finite(const char* name, double value) {
  if (!std::isfinite(value)) {
    throw std::invalid_argument(std::string("update_shear: increment.") + name +
                                " must be finite, got " + format_value(value));
  }
}

/// The Mohr-Coulomb cap c A_c + F_n tan(phi) of a closed step (N).
double mohr_coulomb_cap(const CurrentStrength& strength, const ClosedStep& step) {
  return strength.cohesion * step.area + step.normal_force * strength.friction_coefficient;
}

/// Mohr-Coulomb radial return: the trial force F_t (N) is scaled back onto |F| = cap (N) if it
/// exceeds it. With F = F_0 - k (du - du_p), the plastic slip is du_p = (F - F_t) / k.
ShearResult cap_mohr_coulomb(ShearState& state, const Eigen::Vector3d& trial, double stiffness,
                             double cap) {
  ShearResult result;
  result.stiffness = stiffness;
  const double trial_magnitude = trial.norm();
  if (trial_magnitude <= cap) {
    state.force = trial;
    return result;
  }
  const Eigen::Vector3d force = trial * (cap / trial_magnitude);
  const Eigen::Vector3d slip = (force - trial) / stiffness;
  state.force = force;
  state.plastic_slip += slip.norm();
  result.sliding = true;
  result.slip_increment = slip.norm();
  result.plastic_work = -force.dot(slip);
  return result;
}

ShearResult update(const LinearShear& law, ShearState& state, const ClosedStep& step,
                   const CurrentStrength& strength) {
  const double stiffness = law.stiffness * step.area;
  return cap_mohr_coulomb(state, state.force - stiffness * step.du, stiffness,
                          mohr_coulomb_cap(strength, step));
}

ShearResult update(const StressLinearShear& law, ShearState& state, const ClosedStep& step,
                   const CurrentStrength& strength) {
  // Eq 2 at the step's normal stress.
  const double stiffness = law.stiffness(step.normal_stress) * step.area;
  return cap_mohr_coulomb(state, state.force - stiffness * step.du, stiffness,
                          mohr_coulomb_cap(strength, step));
}

/// U scaled back onto the ball |U| <= radius.
Eigen::Vector3d clamp_to_ball(const Eigen::Vector3d& u, double radius) {
  const double norm = u.norm();
  return norm <= radius ? u : Eigen::Vector3d(u * (radius / norm));
}

/// Mean over the segment U(t) = U0 + t du, t in [0, 1], of the eq 5 factor
/// max(0, 1 - |U(t)| / u_peak). The factor is positive on one interval of t (the ball is convex);
/// |U(t)| is linear in t on either side of the point closest to the origin, so the midpoint rule
/// on each side is exact when du is parallel to U0 and second-order accurate otherwise.
double mean_degradation_factor(const Eigen::Vector3d& u0, const Eigen::Vector3d& du, double peak) {
  const auto factor = [&](double t) { return std::max(0.0, 1.0 - (u0 + t * du).norm() / peak); };
  const double length = du.norm();
  if (length == 0.0) return factor(0.0);
  // |U(t)|^2 = (p + t L)^2 + h^2 with p the projection of U0 on du and h its distance from du's
  // line.
  const double p = u0.dot(du) / length;
  const double h_squared = std::max(0.0, u0.squaredNorm() - p * p);
  const double r_squared = peak * peak - h_squared;
  if (r_squared <= 0.0) return 0.0;
  const double r = std::sqrt(r_squared);
  const double t_in = std::max(0.0, (-r - p) / length);
  const double t_out = std::min(1.0, (r - p) / length);
  if (t_out <= t_in) return 0.0;
  const double t_closest = -p / length;
  if (t_closest > t_in && t_closest < t_out) {
    return (t_closest - t_in) * factor(0.5 * (t_in + t_closest)) +
           (t_out - t_closest) * factor(0.5 * (t_closest + t_out));
  }
  return (t_out - t_in) * factor(0.5 * (t_in + t_out));
}

ShearResult update(const DegradingShear& law, ShearState& state, const ClosedStep& step,
                   const CurrentStrength& strength) {
  const double peak = law.power_laws.peak_displacement(step.normal_stress);
  const double initial = law.power_laws.initial_stiffness(step.normal_stress) * step.area;
  const Eigen::Vector3d u0 = state.elastic_displacement;
  // Eq 5 integrated along the step: dF = -k_s,initial A_c (1 - |U_e|/u_peak)_+ dU_e.
  const double stiffness = initial * mean_degradation_factor(u0, step.du, peak);
  const Eigen::Vector3d trial = state.force - stiffness * step.du;
  const double cap = mohr_coulomb_cap(strength, step);

  ShearResult result;
  result.stiffness = stiffness;
  Eigen::Vector3d u1;
  if (trial.norm() <= cap) {
    // Sticking: U_e follows du, held on the sphere |U_e| = u_peak beyond which k_s = 0.
    state.force = trial;
    u1 = clamp_to_ball(u0 + step.du, peak);
  } else {
    // Sliding on the Mohr-Coulomb cap: the whole step is slip, U_e keeps its value.
    state.force = trial * (cap / trial.norm());
    u1 = clamp_to_ball(u0, peak);
    result.sliding = true;
  }
  const Eigen::Vector3d slip = step.du - (u1 - u0);
  state.elastic_displacement = u1;
  state.plastic_slip += slip.norm();
  result.slip_increment = slip.norm();
  result.plastic_work = -state.force.dot(slip);
  return result;
}

/// Continuously-yielding return mapping (Appendix eqs 9-16, with du -> -du for the force-on-B
/// convention). With du_p = -Lambda F (eq 13), F = F_t / (1 + k Lambda) (eq 15, k = k_s A_c in
/// N/m), so F is parallel to F_t and, writing s = |F|,
///   beta = beta_0 + Lambda s = beta_0 + (|F_t| - s) / k            (eq 14)
///   g(s) = s - mu(beta_0 + (|F_t| - s) / k) F_n = 0                (eq 16).
/// Lambda in [0, inf) maps onto s in (0, |F_t|]; g(|F_t|) > 0 for a trial force outside the yield
/// surface and g(0) = -mu(beta_0 + |F_t|/k) F_n < 0, so [0, |F_t|] is the Appendix's bracket
/// [0, Lambda_hi] with Lambda_hi -> inf, known without growing it. g is strictly increasing in s
/// (mu increases with beta), so the root, found by Brent's method to 1e-12 relative, is unique.
/// beta is the current step's (implicit, backward Euler); for monotonic loading in a fixed
/// direction at constant F_n and area this reproduces the exact solution u = beta + mu(beta) F_n /
/// k at any step size.
/// With cohesion c the yield surface is |F| <= c A_c + mu(beta) F_n and g(s) gains -c A_c: the
/// bracket and the uniqueness argument are unchanged. mu0 is the current tan(phi) (peak or
/// residual).
ShearResult update(const ContinuouslyYieldingShear& law, ShearState& state, const ClosedStep& step,
                   const CurrentStrength& strength) {
  const double peak = law.power_laws.peak_displacement(step.normal_stress);
  const double stiffness = law.power_laws.initial_stiffness(step.normal_stress) * step.area;
  const Eigen::Vector3d trial = state.force - stiffness * step.du;
  const double trial_magnitude = trial.norm();
  const double beta0 = state.plastic_slip;

  ShearResult result;
  result.stiffness = stiffness;
  const double cohesion_force = strength.cohesion * step.area;
  // Eq 8 with mu0 = the current tan(phi), expm1 for small beta.
  const auto mu = [&](double beta) {
    return -strength.friction_coefficient * std::expm1(-beta / peak);
  };
  const double residual_elastic = trial_magnitude - cohesion_force - mu(beta0) * step.normal_force;
  if (residual_elastic <= 0.0) {
    state.force = trial;
    return result;
  }
  const auto residual = [&](double s) {
    const double beta = beta0 + (trial_magnitude - s) / stiffness;
    return s - cohesion_force - mu(beta) * step.normal_force;
  };
  const double s = find_root_bracketed(residual, 0.0, trial_magnitude, residual(0.0),
                                       residual_elastic, 1e-12, 0.0);
  const double slip = (trial_magnitude - s) / stiffness;
  state.force = trial * (s / trial_magnitude);
  state.plastic_slip = beta0 + slip;
  result.sliding = true;
  result.plastic_multiplier = slip / s;
  result.slip_increment = slip;
  result.plastic_work = s * slip;
  return result;
}

/// The update of every law: the checked increment, the bond's limits, the law's own step.
ShearResult update_shear_force(const ShearLaw& law, ShearState& state,
                               const ShearIncrement& increment) {
  const Eigen::Vector3d& n = increment.normal;
  if (!(std::abs(n.norm() - 1.0) <= 1e-6)) {
    throw std::invalid_argument(
        "update_shear: increment.normal must be a unit vector, has length " +
        format_value(n.norm()));
  }
  for (int i = 0; i < 3; ++i) require_finite("displacement", increment.displacement[i]);
  require_finite("normal_force", increment.normal_force);
  require_finite("normal_stress", increment.normal_stress);
  require_finite("contact_area", increment.contact_area);

  const JointStrength& strength = strength_of(law);
  const bool bonded = strength.can_break() && state.bond == BondState::intact;
  ShearResult broke;
  broke.broke = true;
  if (bonded && strength.tension_limit_reached(increment.normal_stress)) {
    // Tension cut-off: the bond breaks and the joint opens.
    state.bond = BondState::broken_in_tension;
    state.force.setZero();
    state.elastic_displacement.setZero();
    return broke;
  }
  const bool closed = increment.normal_force > 0.0 && increment.normal_stress > 0.0;
  if (!closed && !bonded) {
    // Open joint: no normal force, hence no friction and no stored shear force.
    state.force.setZero();
    state.elastic_displacement.setZero();
    return ShearResult{};
  }
  if (!(increment.contact_area > 0.0)) {
    throw std::invalid_argument(
        "update_shear: increment.contact_area must be positive on a closed or bonded joint (F_n "
        "= " +
        format_value(increment.normal_force) + " N), got " + format_value(increment.contact_area));
  }
  const Eigen::Vector3d du = increment.displacement - increment.displacement.dot(n) * n;
  if (!closed) {
    // Intact bond in tension: the stiffness at zero normal stress, and the cap c A_c + F_n tan(phi)
    // (F_n <= 0). Beyond it the bond breaks in shear and, broken in tension, the joint opens.
    ShearResult result;
    result.stiffness = shear_stiffness_estimate(law, 0.0) * increment.contact_area;
    const Eigen::Vector3d trial = state.force - result.stiffness * du;
    const double cap = strength.cohesion * increment.contact_area +
                       increment.normal_force * strength.friction_coefficient;
    if (trial.norm() <= cap) {
      state.force = trial;
      return result;
    }
    state.bond = BondState::broken_in_shear;
    state.force.setZero();
    state.elastic_displacement.setZero();
    return broke;
  }
  const ClosedStep step{du, increment.normal_force, increment.normal_stress,
                        increment.contact_area};
  const auto run = [&](const CurrentStrength& current) {
    return std::visit([&](const auto& l) { return update(l, state, step, current); }, law);
  };
  if (!bonded) return run(current_strength(strength, state.bond));
  // Intact bond: a step that leaves the intact yield surface breaks it, and is taken again from
  // the same start with the residual strength.
  const ShearState start = state;
  const ShearResult intact = run(current_strength(strength, BondState::intact));
  if (!intact.sliding) return intact;
  state = start;
  state.bond = BondState::broken_in_shear;
  ShearResult result = run(current_strength(strength, state.bond));
  result.broke = true;
  return result;
}

}  // namespace

ShearResult update_shear(const ShearLaw& law, ShearState& state, const ShearIncrement& increment) {
  const double before = state.force.squaredNorm();
  const ShearResult result = update_shear_force(law, state, increment);
  // The spring's energy by increments at the step's stiffness, dE = F·dF / k: equal to
  // |F|² / (2 k) while k is constant, and unchanged when k changes under a held force (an
  // area that shrinks as a joint opens), where |F|² / (2 k) would create energy.
  const double after = state.force.squaredNorm();
  if (after == 0.0) {
    state.elastic_energy = 0.0;
  } else if (result.stiffness > 0.0) {
    state.elastic_energy += 0.5 * (after - before) / result.stiffness;
  }
  return result;
}

}  // namespace blockdem
