// Viscous contact damping: the dashpot's force at a closed contact and its work over a step.
#include "blockdem/response/contact_damping.hpp"

#include <algorithm>
#include <cmath>

namespace blockdem {

namespace {

// The velocity of the material point of `b` at `x` (m/s), about the centre the block had a step
// `dt` ago (the centre now less dt times the velocity that step gave it).
Eigen::Vector3d point_velocity_before(const Block& b, const Eigen::Vector3d& x, double dt) {
  const Eigen::Vector3d centre = b.position - dt * b.velocity;
  return b.velocity + b.angular_velocity.cross(x - centre);
}

}  // namespace

double contact_oscillator_mass(const Block& a, const Block& b) {
  const bool free_a = a.is_dynamic(), free_b = b.is_dynamic();
  if (free_a && free_b) {
    const double ma = a.inertial_mass(), mb = b.inertial_mass();
    return ma * mb / (ma + mb);
  }
  if (free_a) return a.inertial_mass();
  if (free_b) return b.inertial_mass();
  return 0.0;
}

Dashpot contact_dashpot(double zeta, const Block& a, const Block& b, const Eigen::Vector3d& x,
                        const Eigen::Vector3d& n, double stiffness, double spring_force,
                        double dt) {
  Dashpot d;
  const double m = contact_oscillator_mass(a, b);
  if (!(zeta > 0.0 && m > 0.0 && stiffness > 0.0)) return d;
  const double c = 2.0 * zeta * std::sqrt(m * stiffness);
  // The normal relative velocity of the material points at x (positive: parting).
  const double rate = (b.point_velocity(x) - a.point_velocity(x)).dot(n);
  // No pull beyond the law's: F_n + F_d >= min(F_n, 0).
  d.force = std::max(-c * rate, -std::max(spring_force, 0.0));
  d.half_work = 0.5 * dt * d.force * rate;
  return d;
}

double dashpot_carried_work(double force, const Block& a, const Block& b, const Eigen::Vector3d& x,
                            const Eigen::Vector3d& n, double dt) {
  const Eigen::Vector3d relative =
      point_velocity_before(b, x, dt) - point_velocity_before(a, x, dt);
  return 0.5 * dt * force * relative.dot(n);
}

}  // namespace blockdem
