// The two-block rig of the virtual laboratory: building the world and reading its gauges.
#include "blockdem/lab/two_block_rig.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "blockdem/contact/law_params.hpp"
#include "blockdem/dynamics/block.hpp"

namespace blockdem {
namespace {

[[noreturn]] void fail_rig(const std::string& what) {
  throw std::invalid_argument("two-block rig: " + what);
}

void require_positive_rig(const char* name, double value, const char* unit) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    fail_rig(std::string(name) + " must be positive and finite, got " + format_value(value) + " " +
             unit);
  }
}

Block box(const Eigen::Vector3d& size, const Eigen::Vector3d& centre, double density,
          const std::string& name) {
  return make_block(Polyhedron::box(size).transformed(Eigen::Matrix3d::Identity(), centre), density,
                    name);
}

}  // namespace

void TwoBlockRigDef::validate() const {
  require_positive_rig("top_size.x", top_size.x(), "m");
  require_positive_rig("top_size.y", top_size.y(), "m");
  require_positive_rig("top_size.z", top_size.z(), "m");
  require_positive_rig("bottom_height", bottom_height, "m");
  require_positive_rig("density", density, "kg/m^3");
  require_positive_rig("rounding_distance", rounding_distance, "m");
  require_positive_rig("unbalanced_tolerance", unbalanced_tolerance, "-");
  require_positive_rig("kinetic_tolerance", kinetic_tolerance, "-");
  if (!(damping >= 0.0 && damping < 1.0)) {
    fail_rig("damping must be in [0, 1), got " + format_value(damping));
  }
  if (max_steps_per_level <= 0) fail_rig("max_steps_per_level must be positive");
}

World make_two_block_rig(const TwoBlockRigDef& rig, const NormalLaw& normal, const ShearLaw& shear,
                         double bottom_length, double initial_closure) {
  rig.validate();
  require_positive_rig("bottom_length", bottom_length, "m");
  if (!(initial_closure >= 0.0 && initial_closure <= rig.rounding_distance)) {
    fail_rig("initial closure must be in [0, rounding_distance], got " +
             format_value(initial_closure) + " m");
  }
  WorldSettings settings;
  settings.damping = rig.damping;
  settings.contact_mode = rig.contact_mode;
  settings.boon2012.rounding_distance = rig.rounding_distance;
  World world(settings);
  world.add_joint_law(JointLaw{"lab", normal, shear});
  world.add_joint_rule(JointRule{"", "", 0});

  // Bottom: top face at z = 0, moved only by prescribing its velocity.
  const Eigen::Vector3d bottom_size(bottom_length, rig.top_size.y(), rig.bottom_height);
  Block bottom =
      box(bottom_size, Eigen::Vector3d(0.0, 0.0, -0.5 * rig.bottom_height), rig.density, "bottom");
  bottom.motion = Motion::prescribed;
  world.add_block(std::move(bottom));

  // Top: bottom face at z = -initial_closure, free along z only.
  Block top = box(rig.top_size, Eigen::Vector3d(0.0, 0.0, 0.5 * rig.top_size.z() - initial_closure),
                  rig.density, "top");
  top.blocked_translation = Eigen::Matrix<bool, 3, 1>(true, true, false);
  top.blocked_rotation = Eigen::Matrix<bool, 3, 1>::Constant(true);
  world.add_block(std::move(top));
  return world;
}

double rig_gravity_for_stress(const World& world, const TwoBlockRigDef& rig, double normal_stress) {
  return normal_stress * rig.joint_area() / world.blocks()[rig_top].mass;
}

RigReading read_rig(const World& world, const TwoBlockRigDef& rig) {
  const Block& bottom = world.blocks()[rig_bottom];
  const Block& top = world.blocks()[rig_top];
  RigReading r;
  const double bottom_face = bottom.position.z() + 0.5 * rig.bottom_height;
  const double top_face = top.position.z() - 0.5 * rig.top_size.z();
  r.closure = bottom_face - top_face;
  r.shear_displacement = (top.position.x() - top.initial_position.x()) -
                         (bottom.position.x() - bottom.initial_position.x());
  const double area = rig.joint_area();
  r.normal_stress = top.contact_force.z() / area;
  r.shear_stress = -top.contact_force.x() / area;
  for (const Contact* c : world.contacts()) {
    r.touching = true;
    r.overlap = c->geometry.overlap;
    r.contact_area = c->geometry.area;
    r.plastic_slip = c->shear.plastic_slip;
  }
  return r;
}

}  // namespace blockdem
