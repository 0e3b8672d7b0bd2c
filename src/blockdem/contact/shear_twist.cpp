// Shear force and twisting moment of a joint together, by the instantaneous centre of the slip.
#include "blockdem/contact/shear_twist.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace blockdem {

SlipCentre slip_centre(const Eigen::Vector3d& force, double moment, const Eigen::Vector3d& normal,
                       const Eigen::Vector3d& force_point, double polar_moment, double area,
                       double radius) {
  SlipCentre c;
  if (moment == 0.0 || !(area > 0.0) || !(polar_moment > 0.0)) return c;
  // p - x_p = (J / (A M)) n × F: u0 = -F / (k_s A), θ = -M / (k_s J), p - x_p = n × u0 / θ.
  const Eigen::Vector3d offset = (polar_moment / (area * moment)) * normal.cross(force);
  if (!(offset.norm() <= 1e6 * radius)) return c;
  c.translation = false;
  c.point = force_point + offset;
  c.sense = moment > 0.0 ? -1.0 : 1.0;
  return c;
}

bool exceeds_full_slip(const Eigen::Vector3d& force, double moment, const SlipCentre& centre,
                       const Eigen::Vector3d& force_point, const Eigen::Vector3d& normal,
                       const FullSlip& slip, double friction_coefficient) {
  // The slip rate (v at x_p, s about n) of the rotation about p; the power the state spends
  // against it, and the most the joint can spend.
  const Eigen::Vector3d v = centre.sense * normal.cross(force_point - centre.point);
  const double state_power = -(force.dot(v) + moment * centre.sense);
  return state_power > friction_coefficient * slip.power;
}

bool certified_inside(double force, double moment, double friction_limit, double moment_bound) {
  if (!(friction_limit > 0.0) || !(moment_bound > 0.0)) return false;
  return force / friction_limit + 2.0 * std::abs(moment) / moment_bound <= 1.0;
}

}  // namespace blockdem
