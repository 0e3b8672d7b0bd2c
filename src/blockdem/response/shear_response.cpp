// A contact's shear response over one step: the stored shear state turned with the contact frame.
#include "blockdem/response/shear_response.hpp"

namespace blockdem {

void spin_shear_state(ShearState& state, const Eigen::Vector3d& normal, double angle) {
  if (angle == 0.0) return;
  const Eigen::AngleAxisd turn(angle, normal);
  state.force = turn * state.force;
  state.elastic_displacement = turn * state.elastic_displacement;
}

}  // namespace blockdem
