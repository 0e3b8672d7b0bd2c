// Small scenes shared by the validation tests: worlds built in code, one joint law.
#pragma once

#include "blockdem/dynamics/block.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem::test {

/// A world with one linear joint law acting between all blocks.
inline World linear_world(double kn, double ks, double friction_deg, WorldSettings s = {}) {
  World w(s);
  JointLaw law;
  law.name = "joint";
  law.normal = LinearNormal{kn};
  law.shear = LinearShear{ks, JointStrength::from_friction_deg(friction_deg)};
  w.add_joint_law(law);
  w.add_joint_rule(JointRule{"", "", 0});
  return w;
}

/// A box block of the given size centred at `centre`.
inline Block box_block(const Eigen::Vector3d& size, const Eigen::Vector3d& centre, double density,
                       Motion motion = Motion::free, const std::string& name = "block") {
  Block b = make_block(Polyhedron::box(size).transformed(Eigen::Matrix3d::Identity(), centre),
                       density, name);
  b.motion = motion;
  return b;
}

}  // namespace blockdem::test
