// Rotation of stored shear vectors into a contact's new tangent plane (Rodrigues' formula).
#include "blockdem/contact/shear_state.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

#include "blockdem/contact/law_params.hpp"

namespace blockdem {
namespace {

void require_unit(const Eigen::Vector3d& n, const char* name) {
  const double norm = n.norm();
  if (!(std::abs(norm - 1.0) <= 1e-6)) {
    throw std::invalid_argument(std::string("rotate_into_plane: ") + name +
                                " must be a unit vector, has length " + format_value(norm));
  }
}

}  // namespace

Eigen::Vector3d rotate_into_plane(const Eigen::Vector3d& force, const Eigen::Vector3d& old_normal,
                                  const Eigen::Vector3d& new_normal) {
  require_unit(old_normal, "old_normal");
  require_unit(new_normal, "new_normal");
  const double cos_angle = old_normal.dot(new_normal);
  if (cos_angle <= -1.0 + 1e-12) {
    throw std::invalid_argument(
        "rotate_into_plane: the normals are opposite, the rotation between them is not unique");
  }
  // The in-plane part of the force, whose magnitude the rotation must keep.
  const Eigen::Vector3d in_plane = force - force.dot(old_normal) * old_normal;
  const double magnitude = in_plane.norm();
  if (magnitude == 0.0) return Eigen::Vector3d::Zero();
  // Rodrigues' formula for the rotation about old x new by the angle between them:
  // R x = cos x + v x x + v (v . x) / (1 + cos), with v = old x new (|v| = sin).
  const Eigen::Vector3d axis = old_normal.cross(new_normal);
  Eigen::Vector3d rotated =
      cos_angle * in_plane + axis.cross(in_plane) + axis * (axis.dot(in_plane) / (1.0 + cos_angle));
  // Remove the rounding-level normal component and restore the magnitude exactly.
  rotated -= rotated.dot(new_normal) * new_normal;
  return rotated * (magnitude / rotated.norm());
}

void rotate_into_plane(ShearState& state, const Eigen::Vector3d& old_normal,
                       const Eigen::Vector3d& new_normal) {
  state.force = rotate_into_plane(state.force, old_normal, new_normal);
  state.elastic_displacement =
      rotate_into_plane(state.elastic_displacement, old_normal, new_normal);
}

}  // namespace blockdem
