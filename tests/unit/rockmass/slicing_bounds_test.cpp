// Bounded work for any joint set: estimates refused before any joint is placed (naming the set,
// the estimate and the limit), and every loop over joint planes ends whatever the numbers (a
// spacing that does not advance, an origin far outside the region, joints far smaller than it).
#include "blockdem/rockmass/slicing_bounds.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace blockdem {
namespace slicing_bounds_test {

JointSet horizontal(const std::string& name, double spacing, double origin_z) {
  JointSet s;
  s.name = name;
  s.dip_deg = 0.0;
  s.dip_direction_deg = 0.0;
  s.spacing.mean = spacing;
  s.origin = {2.0, 2.0, origin_z};
  return s;
}

JointSet vertical(const std::string& name, double dip_direction, double spacing) {
  JointSet s = horizontal(name, spacing, 0.5);
  s.dip_deg = 90.0;
  s.dip_direction_deg = dip_direction;
  s.origin = {0.5, 0.5, 0.5};
  return s;
}

RockMassSpec cube_with(const JointSet& set) {
  RockMassSpec spec;
  spec.region = Region::box({0, 0, 0}, {4, 4, 4});
  spec.joint_sets.push_back(set);
  return spec;
}

// The message of the std::invalid_argument that slicing `spec` throws ("" when none).
std::string refusal(const RockMassSpec& spec) {
  try {
    slice_rock_mass(spec);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

void expect_in(const std::string& message, const std::string& fragment) {
  EXPECT_NE(message.find(fragment), std::string::npos)
      << "'" << fragment << "' not in: " << message;
}

TEST(SlicingBounds, SpacingThatCannotAdvanceIsRefusedWithEstimateAndLimit) {
  // 1e-300 m in a 4 m cube: about 4e300 planes; before the check the offset never advanced.
  const std::string m = refusal(cube_with(horizontal("bedding", 1e-300, 0.5)));
  expect_in(m, "joint_sets[1].spacing: ");
  expect_in(m, "\"bedding\"");
  expect_in(m, "4e+300");
  expect_in(m, "max_blocks = 2000000");
}

TEST(SlicingBounds, TinyExponentialSpacingIsRefused) {
  JointSet s = horizontal("J1", 1e-9, 0.5);
  s.spacing.distribution = Spacing::Distribution::exponential;
  s.spacing.seed = 7;
  const std::string m = refusal(cube_with(s));
  expect_in(m, "joint_sets[1].spacing: ");
  expect_in(m, "4e+09 joint planes");
}

TEST(SlicingBounds, TinyDiscsAreRefusedByTheirJointCount) {
  // Discs of radius 1e-6 m at persistence 0.5 over sections of up to pi 6.93^2 / 4 m^2: up to
  // 6e12 discs on each of the 5 planes.
  JointSet s = horizontal("J1", 1.0, 0.5);
  JointExtent disc;
  disc.radius = 1e-6;
  s.extent = disc;
  s.placement_seed = 3;
  const std::string m = refusal(cube_with(s));
  expect_in(m, "joint_sets[1].extent: ");
  expect_in(m, "max_joints = 1000000");
  expect_in(m, "5 planes");
}

TEST(SlicingBounds, ConstantSpacingFromAFarOriginStepsStraightToTheRegion) {
  // Origins 1e12 m above and below the cube, on the planes z = 0.5 + k: the same four joints
  // and five slabs as an origin inside it (before, a walk of 1e12 steps).
  for (const double origin_z : {0.5 + 1e12, 0.5 - 1e12, 0.5}) {
    const RockMass rm = slice_rock_mass(cube_with(horizontal("J1", 1.0, origin_z)));
    ASSERT_EQ(rm.joints.size(), 1u);
    ASSERT_EQ(rm.joints[0].size(), 4u) << origin_z;
    for (std::size_t k = 0; k < 4; ++k)
      EXPECT_DOUBLE_EQ(rm.joints[0][k].offset, 0.5 + static_cast<double>(k)) << origin_z;
    EXPECT_EQ(rm.blocks.size(), 5u);
  }
}

TEST(SlicingBounds, RandomSpacingFromAFarOriginIsRefused) {
  // A random spacing is drawn joint by joint from the origin's joint: 1e12 m at a mean of 1 m
  // would be 1e12 draws.
  JointSet s = horizontal("J1", 1.0, 1e12);
  s.spacing.distribution = Spacing::Distribution::exponential;
  s.spacing.seed = 11;
  const std::string m = refusal(cube_with(s));
  expect_in(m, "joint_sets[1].origin: ");
  expect_in(m, "1e+12");
}

TEST(SlicingBounds, BlockEstimateIsTheProductOfPlanesPlusOneAndNamesTheSetThatCrossesIt) {
  // Three orthogonal sets at 1 m in a 4 m cube: floor(4 / 1) + 1 = 5 planes each, (1 + 5)^3 =
  // 216 blocks estimated (125 cut). A limit of 100 is crossed at the third set (36 after two).
  RockMassSpec spec = cube_with(horizontal("J1", 1.0, 0.5));
  spec.joint_sets.push_back(vertical("J2", 0.0, 1.0));
  spec.joint_sets.push_back(vertical("J3", 90.0, 1.0));
  spec.settings.max_blocks = 100;
  const std::string m = refusal(spec);
  expect_in(m, "joint_sets[3].spacing: ");
  expect_in(m, "\"J3\"");
  expect_in(m, "about 216 blocks");
  expect_in(m, "max_blocks = 100");
  spec.settings.max_blocks = 216;
  EXPECT_EQ(slice_rock_mass(spec).blocks.size(), 125u);
}

TEST(SlicingBounds, PlaneLoopsEndWhenCalledWithoutTheEstimate) {
  // joint_plane_offsets alone: a spacing that does not move the offset, or more planes than
  // asked for, ends in an error instead of a loop without end or memory without bound.
  EXPECT_THROW(joint_plane_offsets(horizontal("J1", 1e-300, 0.5), 0.0, 4.0), std::invalid_argument);
  EXPECT_THROW(joint_plane_offsets(horizontal("J1", 1e-6, 0.5), 0.0, 4.0, 1000.0),
               std::invalid_argument);
  JointSet random = horizontal("J1", 1e-9, 0.5);
  random.spacing.distribution = Spacing::Distribution::exponential;
  random.spacing.seed = 1;
  EXPECT_THROW(joint_plane_offsets(random, 0.0, 4.0, 1000.0), std::invalid_argument);
  EXPECT_EQ(joint_plane_offsets(horizontal("J1", 1.0, 0.5), 0.0, 4.0).size(), 4u);
}

}  // namespace slicing_bounds_test
}  // namespace blockdem
