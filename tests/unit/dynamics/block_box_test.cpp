// A block's world-frame bounding box is not kept in the block: update_world_geometry hands it to
// the caller (the world's compact box arrays) and world_box computes it again. Both must be the
// box of the block's vertices at its pose, with the same bits.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <limits>

#include "validation/scenes.hpp"

namespace blockdem::test {
namespace {

TEST(BlockBox, IsTheBoxOfTheVerticesAtThePoseWithTheSameBitsEitherWay) {
  Block b =
      box_block(Eigen::Vector3d(0.3, 0.2, 0.1), {1.5, -2.0, 0.7}, 2600.0, Motion::free, "rotated");
  b.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  b.position = Eigen::Vector3d(10.25, -3.5, 1.125);

  Eigen::Vector3d lo, hi;
  b.update_world_geometry(lo, hi);
  Eigen::Vector3d again_lo, again_hi;
  b.world_box(again_lo, again_hi);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(lo[k]), std::bit_cast<std::uint64_t>(again_lo[k]));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(hi[k]), std::bit_cast<std::uint64_t>(again_hi[k]));
  }
  // An independent oracle: the vertices carried by the quaternion (to_world), to round-off.
  Eigen::Vector3d want_lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d want_hi = -want_lo;
  for (const Eigen::Vector3d& v : b.shape.vertices()) {
    want_lo = want_lo.cwiseMin(b.to_world(v));
    want_hi = want_hi.cwiseMax(b.to_world(v));
  }
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(lo[k], want_lo[k], 1e-12);
    EXPECT_NEAR(hi[k], want_hi[k], 1e-12);
  }
  // The planes are refreshed with the box.
  EXPECT_EQ(b.world_planes.size(), b.shape.planes().size());
}

}  // namespace
}  // namespace blockdem::test
