// Rotation of the stored shear state into a tilted contact plane, and objectivity of the shear
// laws: the same shear path on a rotating joint gives the rotated force.
#include "blockdem/contact/shear_state.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

#include "blockdem/contact/shear_laws.hpp"

namespace blockdem {
namespace {

TEST(RotateIntoPlane, IsTheRotationAboutTheCommonPerpendicular) {
  const Eigen::Vector3d old_n = Eigen::Vector3d(0.2, -0.3, 0.9).normalized();
  const Eigen::Vector3d axis = old_n.cross(Eigen::Vector3d::UnitX()).normalized();
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.4, axis).toRotationMatrix();
  const Eigen::Vector3d new_n = rotation * old_n;
  Eigen::Vector3d force = Eigen::Vector3d(1.0, 2.0, -0.5);
  force -= force.dot(old_n) * old_n;
  const Eigen::Vector3d rotated = rotate_into_plane(force, old_n, new_n);
  EXPECT_LT((rotated - rotation * force).norm(), 1e-14 * force.norm());
  EXPECT_NEAR(rotated.dot(new_n), 0.0, 1e-15 * force.norm());
  EXPECT_NEAR(rotated.norm(), force.norm(), 1e-15 * force.norm());
}

TEST(RotateIntoPlane, KeepsTheInPlaneMagnitudeAndDropsTheNormalPart) {
  const Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  EXPECT_EQ(rotate_into_plane(Eigen::Vector3d(3, 4, 0), n, n), Eigen::Vector3d(3, 4, 0));
  EXPECT_EQ(rotate_into_plane(Eigen::Vector3d(3, 4, 7), n, n), Eigen::Vector3d(3, 4, 0));
  EXPECT_EQ(rotate_into_plane(Eigen::Vector3d::Zero(), n, Eigen::Vector3d::UnitX()),
            Eigen::Vector3d::Zero());
  // A quarter turn about x takes y into z.
  const Eigen::Vector3d r =
      rotate_into_plane(Eigen::Vector3d(0, 2, 0), n, Eigen::Vector3d(0, -1, 0));
  EXPECT_LT((r - Eigen::Vector3d(0, 0, 2)).norm(), 1e-15);
}

TEST(RotateIntoPlane, RejectsOppositeOrNonUnitNormals) {
  const Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  EXPECT_THROW(rotate_into_plane(Eigen::Vector3d::UnitX(), n, -n), std::invalid_argument);
  EXPECT_THROW(rotate_into_plane(Eigen::Vector3d::UnitX(), n, 2.0 * n), std::invalid_argument);
}

/// The shear path of a joint whose plane turns by `total_angle` about an axis in the plane, with
/// the displacement increments turning with it; the world's sequence: rotate the stored state into
/// the new plane, then update. Returns the final state.
ShearState run_rotating(const ShearLaw& law, const Eigen::Vector3d& axis, double total_angle,
                        int steps) {
  ShearState state;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  for (int i = 1; i <= steps; ++i) {
    const Eigen::Matrix3d rotation =
        Eigen::AngleAxisd(total_angle * i / steps, axis).toRotationMatrix();
    const Eigen::Vector3d new_normal = rotation * Eigen::Vector3d::UnitZ();
    rotate_into_plane(state, normal, new_normal);
    normal = new_normal;
    ShearIncrement inc;
    // A curved path of 40 um in the joint's own frame, starting along x and turning towards y.
    const double phase = 1.5 * i / steps;
    inc.displacement =
        rotation * Eigen::Vector3d(std::cos(phase), std::sin(phase), 0) * (4e-5 / steps);
    inc.normal_stress = 0.4e6 + 0.2e6 * i / steps;
    inc.contact_area = 2e-3;
    inc.normal_force = inc.normal_stress * inc.contact_area;
    inc.normal = normal;
    update_shear(law, state, inc);
  }
  return state;
}

TEST(ShearObjectivity, RotatingTheJointRotatesTheForce) {
  const Eigen::Vector3d in_plane_axis = Eigen::Vector3d(1.0, 0.5, 0.0).normalized();
  const double angle = 0.8;  // rad
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(angle, in_plane_axis).toRotationMatrix();
  for (const ShearLaw& law : {ShearLaw{LinearShear{}}, ShearLaw{StressLinearShear{}},
                              ShearLaw{DegradingShear{}}, ShearLaw{ContinuouslyYieldingShear{}}}) {
    const ShearState fixed = run_rotating(law, in_plane_axis, 0.0, 200);
    const ShearState turned = run_rotating(law, in_plane_axis, angle, 200);
    ASSERT_GT(fixed.force.norm(), 0.0) << law_name(law);
    EXPECT_LT((turned.force - rotation * fixed.force).norm(), 1e-12 * fixed.force.norm())
        << law_name(law);
    EXPECT_LT((turned.elastic_displacement - rotation * fixed.elastic_displacement).norm(),
              1e-12 * 4e-5)
        << law_name(law);
    EXPECT_NEAR(turned.plastic_slip, fixed.plastic_slip, 1e-12 * 4e-5) << law_name(law);
  }
}

}  // namespace
}  // namespace blockdem
