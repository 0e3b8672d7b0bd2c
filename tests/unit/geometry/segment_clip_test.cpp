// Segment clipping by half-spaces against hand-worked cases: a unit cube crossed straight and
// obliquely, a segment that misses, one parallel to a face, one that only touches an edge.
#include "blockdem/geometry/segment_clip.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace blockdem {
namespace segment_clip_test {
namespace {

// The cube [0, 1]^3.
std::vector<Halfspace> cube() {
  std::vector<Halfspace> h;
  for (int axis = 0; axis < 3; ++axis) {
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    n[axis] = 1.0;
    h.push_back({n, 1.0});
    h.push_back({-n, 0.0});
  }
  return h;
}

TEST(SegmentClip, StraightThroughTheCube) {
  const auto t = clip_segment(cube(), {0.5, 0.5, -1.0}, {0.5, 0.5, 3.0});
  ASSERT_TRUE(t);
  EXPECT_DOUBLE_EQ(t->first, 0.25);
  EXPECT_DOUBLE_EQ(t->second, 0.5);
}

TEST(SegmentClip, ObliqueThroughTheCube) {
  // From (-1, 0.5, 0) to (2, 0.5, 3): inside for x in [0, 1] and z in [0, 1], i.e. t in [1/3, 2/3]
  // by x and [0, 1/3] by z: the single point t = 1/3, which is no interval.
  EXPECT_FALSE(clip_segment(cube(), {-1.0, 0.5, 0.0}, {2.0, 0.5, 3.0}));
  // From (-1, 0.5, -0.5) to (2, 0.5, 1): x in [0, 1] for t in [1/3, 2/3], z in [0, 1] for
  // t in [1/3, 1].
  const auto t = clip_segment(cube(), {-1.0, 0.5, -0.5}, {2.0, 0.5, 1.0});
  ASSERT_TRUE(t);
  EXPECT_NEAR(t->first, 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(t->second, 2.0 / 3.0, 1e-15);
}

TEST(SegmentClip, StartsInsideAndEndsInside) {
  const auto t = clip_segment(cube(), {0.2, 0.2, 0.2}, {0.8, 0.8, 0.8});
  ASSERT_TRUE(t);
  EXPECT_EQ(t->first, 0.0);
  EXPECT_EQ(t->second, 1.0);
}

TEST(SegmentClip, MissesAndRunsParallelOutside) {
  EXPECT_FALSE(clip_segment(cube(), {2.0, 0.5, -1.0}, {2.0, 0.5, 3.0}));
  EXPECT_FALSE(clip_segment(cube(), {0.5, 0.5, 2.0}, {0.5, 0.5, 5.0}));
  // Parallel to the faces x = 0 and x = 1, inside them: kept.
  const auto t = clip_segment(cube(), {0.5, 0.5, -1.0}, {0.5, 0.5, 0.5});
  ASSERT_TRUE(t);
  EXPECT_NEAR(t->first, 2.0 / 3.0, 1e-15);
  EXPECT_EQ(t->second, 1.0);
}

}  // namespace
}  // namespace segment_clip_test
}  // namespace blockdem
