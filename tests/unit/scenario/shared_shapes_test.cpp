// Box blocks of one size, rotation and density share one shape, and are the blocks that building
// each box on its own gives, bit for bit.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "blockdem/dynamics/block.hpp"
#include "blockdem/geometry/polyhedron.hpp"
#include "blockdem/numerics/units.hpp"
#include "blockdem/run/scene_builders.hpp"

namespace blockdem::test::shared_shapes_test {
namespace {

// Three 0.1 m cubes turned 30° about z, a fourth of another size, a fifth of another density.
const char* kScene = R"(
[[materials]]
name = "rock"
density = 2600.0
[[joint_laws]]
name = "joint"
normal = { law = "linear", stiffness = 1e10 }
shear = { law = "linear", stiffness = 1e9, friction_deg = 35 }
[[blocks]]
name = "a"
material = "rock"
size = [0.1, 0.1, 0.1]
rotation_deg = 30.0
position = [0.0, 0.0, 0.05]
[[blocks]]
name = "b"
material = "rock"
size = [0.1, 0.1, 0.1]
rotation_deg = 30.0
position = [0.5, 0.0, 0.05]
[[blocks]]
name = "c"
group = "other"
material = "rock"
size = [0.1, 0.1, 0.1]
rotation_deg = 30.0
position = [1.0, 0.3, 0.05]
[[blocks]]
name = "d"
material = "rock"
size = [0.1, 0.1, 0.2]
rotation_deg = 30.0
position = [2.0, 0.0, 0.1]
[[blocks]]
name = "e"
density = 2000.0
size = [0.1, 0.1, 0.1]
rotation_deg = 30.0
position = [3.0, 0.0, 0.05]
[[stages]]
name = "settle"
gravity = [0.0, 0.0, -9.81]
)";

// The block as the scenario reader made every box before boxes were shared: its own shape.
Block box_block(const Eigen::Vector3d& size, double density, const Eigen::Vector3d& position) {
  const Eigen::Matrix3d rot =
      Eigen::AngleAxisd(deg_to_rad(30.0), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Block b = make_block(Polyhedron::box(size).transformed(rot, Eigen::Vector3d::Zero()), density,
                       "x", "default");
  b.position += position;
  return b;
}

void expect_same_block(const Block& got, const Block& want) {
  EXPECT_EQ(got.mass, want.mass);  // exact: the same computation
  EXPECT_EQ(got.inertia, want.inertia);
  EXPECT_EQ(got.position, want.position);
  EXPECT_EQ(got.orientation.coeffs(), want.orientation.coeffs());
  ASSERT_EQ(got.shape.planes().size(), want.shape.planes().size());
  for (std::size_t i = 0; i < got.shape.planes().size(); ++i) {
    EXPECT_EQ(got.shape.planes()[i].normal, want.shape.planes()[i].normal);
    EXPECT_EQ(got.shape.planes()[i].offset, want.shape.planes()[i].offset);
  }
  EXPECT_TRUE(std::ranges::equal(got.shape.vertices(), want.shape.vertices()));
  ASSERT_EQ(got.shape.faces().size(), want.shape.faces().size());
  for (std::size_t f = 0; f < got.shape.faces().size(); ++f)
    EXPECT_TRUE(std::ranges::equal(got.shape.faces()[f].vertices, want.shape.faces()[f].vertices));
}

TEST(SharedShapes, IdenticalBoxesShareOneShapeAndEqualBoxesBuiltAlone) {
  const Scenario sc = parse_scenario(kScene, "boxes.toml");
  ASSERT_EQ(sc.blocks.size(), 5u);
  const auto& bl = sc.blocks;
  EXPECT_TRUE(bl[0].shape.shares_data_with(bl[1].shape));
  EXPECT_TRUE(bl[0].shape.shares_data_with(bl[2].shape));
  EXPECT_FALSE(bl[0].shape.shares_data_with(bl[3].shape));  // another size
  EXPECT_FALSE(bl[0].shape.shares_data_with(bl[4].shape));  // another density
  EXPECT_EQ(bl[1].name, "b");
  EXPECT_EQ(bl[2].group(), "other");

  const Eigen::Vector3d cube(0.1, 0.1, 0.1);
  expect_same_block(bl[0], box_block(cube, 2600.0, {0.0, 0.0, 0.05}));
  expect_same_block(bl[1], box_block(cube, 2600.0, {0.5, 0.0, 0.05}));
  expect_same_block(bl[2], box_block(cube, 2600.0, {1.0, 0.3, 0.05}));
  expect_same_block(bl[3], box_block({0.1, 0.1, 0.2}, 2600.0, {2.0, 0.0, 0.1}));
  expect_same_block(bl[4], box_block(cube, 2000.0, {3.0, 0.0, 0.05}));
  // Mass from the closed form rho a b c, to round-off.
  EXPECT_NEAR(bl[1].mass, 2600.0 * 1e-3, 1e-12);

  // The world's blocks share the scenario's shapes and have their world planes; the scenario
  // keeps none.
  const World w = build_world(sc);
  EXPECT_TRUE(w.blocks()[1].shape.shares_data_with(bl[0].shape));
  for (const Block& b : bl) EXPECT_TRUE(b.world_planes.empty());
  Block want = box_block(cube, 2600.0, {0.5, 0.0, 0.05});
  want.update_world_geometry();
  ASSERT_EQ(w.blocks()[1].world_planes.size(), want.world_planes.size());
  for (std::size_t i = 0; i < want.world_planes.size(); ++i) {
    EXPECT_EQ(w.blocks()[1].world_planes[i].normal, want.world_planes[i].normal);
    EXPECT_EQ(w.blocks()[1].world_planes[i].offset, want.world_planes[i].offset);
  }
}

}  // namespace
}  // namespace blockdem::test::shared_shapes_test
