// The torsional spring with a Coulomb-type cap and the relative spin about a contact normal.
#include "blockdem/contact/twist.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "blockdem/numerics/number_text.hpp"

namespace blockdem {
namespace {

void require(bool ok, const char* name, double value) {
  if (!ok) {
    throw std::invalid_argument(std::string("update_twist: ") + name +
                                " must be finite and non-negative, got " + number_text(value));
  }
}

}  // namespace

TwistResult update_twist(TwistState& state, const TwistIncrement& increment) {
  require(std::isfinite(increment.spin), "spin", increment.spin);
  require(std::isfinite(state.moment), "state.moment", state.moment);
  require(std::isfinite(increment.shear_stiffness) && increment.shear_stiffness >= 0.0,
          "shear_stiffness", increment.shear_stiffness);
  require(std::isfinite(increment.polar_moment) && increment.polar_moment >= 0.0, "polar_moment",
          increment.polar_moment);
  require(std::isfinite(increment.radial_normal_moment) && increment.radial_normal_moment >= 0.0,
          "radial_normal_moment", increment.radial_normal_moment);
  require(std::isfinite(increment.friction_coefficient) && increment.friction_coefficient >= 0.0,
          "friction_coefficient", increment.friction_coefficient);

  TwistResult result;
  result.stiffness = increment.shear_stiffness * increment.polar_moment;
  result.limit = increment.friction_coefficient * increment.radial_normal_moment;
  // Elastic trial: the moment on B opposes B's spin relative to A.
  const double trial = state.moment - result.stiffness * increment.spin;
  if (std::abs(trial) <= result.limit) {
    state.moment = trial;
    return result;
  }
  state.moment = std::copysign(result.limit, trial);
  result.sliding = true;
  return result;
}

double relative_spin(const Eigen::Vector3d& omega_a, const Eigen::Vector3d& omega_b,
                     const Eigen::Vector3d& normal, double dt) {
  return (omega_b - omega_a).dot(normal) * dt;
}

}  // namespace blockdem
