// Tests of the slice polygon: closed-form areas, the small-vector vertex
// storage on and off the heap, and the warm start against plain clipping.
#include "blockdem/collision/slice_polygon.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "support/random_shapes.hpp"

namespace blockdem {
namespace {

using test_shapes::Planes;
using test_shapes::Rng;
using test_shapes::uniform;

// Vertices as 3D points, for order-free comparisons.
std::vector<Eigen::Vector3d> world_vertices(const SlicePolygon& p) {
  std::vector<Eigen::Vector3d> out;
  for (const Eigen::Vector2d& v : p.vertices) out.push_back(p.to_world(v));
  return out;
}

// Largest distance from a vertex of `a` to the nearest vertex of `b` (m).
double vertex_set_distance(const SlicePolygon& a, const SlicePolygon& b) {
  double worst = 0.0;
  for (const Eigen::Vector3d& p : world_vertices(a)) {
    double best = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& q : world_vertices(b)) best = std::min(best, (p - q).norm());
    worst = std::max(worst, best);
  }
  return worst;
}

TEST(SliceVertices, InlineThenHeapKeepsOrderThroughCopyAndMove) {
  SliceVertices v;
  for (int i = 0; i < 40; ++i) {
    v.push_back(Eigen::Vector2d(i, -i));
    ASSERT_EQ(v.size(), static_cast<std::size_t>(i + 1));
    for (int k = 0; k <= i; ++k) ASSERT_EQ(v[k], Eigen::Vector2d(k, -k));
    // Copies and moves keep every point, inline (i < 16) or on the heap.
    SliceVertices copy = v;
    SliceVertices moved = std::move(copy);
    ASSERT_EQ(moved.size(), v.size());
    for (std::size_t k = 0; k < v.size(); ++k) ASSERT_EQ(moved[k], v[k]);
    EXPECT_TRUE(copy.empty());
  }
  v.clear();
  EXPECT_TRUE(v.empty());
  v.push_back(Eigen::Vector2d(1, 2));
  EXPECT_EQ(v[0], Eigen::Vector2d(1, 2));
}

// A unit cube cut through its centre normal to a body diagonal: a regular hexagon of side
// √2/2, area (3√3/2)(1/2) = 3√3/4.
TEST(SlicePolygon, CubeDiagonalSliceIsTheRegularHexagon) {
  Rng rng(1);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Matrix3d r = test_shapes::random_rotation(rng);
    const Eigen::Vector3d c(uniform(rng, -3, 3), uniform(rng, -3, 3), uniform(rng, -3, 3));
    const Planes cube = test_shapes::box(Eigen::Vector3d::Constant(0.5), r, c);
    const SlicePolygon p =
        slice_halfspaces(cube, c, r * Eigen::Vector3d(1, 1, 1).normalized(), 4.0);
    ASSERT_EQ(p.vertices.size(), 6u);
    EXPECT_NEAR(p.area(), 3.0 * std::sqrt(3.0) / 4.0, 1e-13);
    EXPECT_LT(p.centroid_2d().norm(), 1e-13);
  }
}

// A regular prism of k sides (inradius ρ) cut normal to its axis: the regular k-gon, area
// k ρ² tan(π/k). k = 70 needs the heap for both the clipping (over 64 planes) and the result
// (over SliceVertices::kInline vertices).
TEST(SlicePolygon, PrismCrossSectionIsTheRegularPolygon) {
  for (const int k : {3, 8, 16, 17, 70}) {
    const double rho = 0.3;
    std::vector<Eigen::Vector2d> polygon;
    const double circum = rho / std::cos(std::numbers::pi / k);
    for (int i = 0; i < k; ++i) {
      const double angle = 2.0 * std::numbers::pi * (i + 0.5) / k;
      polygon.emplace_back(circum * std::cos(angle), circum * std::sin(angle));
    }
    const Planes prism = test_shapes::prism(polygon, 1.0);
    const SlicePolygon p = slice_halfspaces(prism, {0, 0, 0.2}, Eigen::Vector3d::UnitZ(), 4.0);
    ASSERT_EQ(p.vertices.size(), static_cast<std::size_t>(k));
    EXPECT_NEAR(p.area(), k * rho * rho * std::tan(std::numbers::pi / k), 1e-13) << k;
    // A plane parallel to the slice removes everything when the slice lies outside it.
    EXPECT_TRUE(
        slice_halfspaces(prism, {0, 0, 1.5}, Eigen::Vector3d::UnitZ(), 4.0).vertices.empty());
  }
}

// The warm start gives the polygon plain clipping gives, along the trajectories of random pairs
// (overlapping hulls, boxes face to face), including steps where the polygon changes its edges.
TEST(SlicePolygon, WarmStartMatchesClippingAlongTrajectories) {
  Rng rng(2);
  int warm_accepted = 0, steps = 0;
  for (int pair = 0; pair < 200; ++pair) {
    const bool boxes = pair % 2 == 0;
    const Planes a = boxes ? test_shapes::box({0.5, 0.4, 0.3}, test_shapes::random_rotation(rng))
                           : test_shapes::random_hull(rng, 6 + pair % 10, 0.5);
    const Planes b0 = boxes
                          ? test_shapes::place_face_on_face(a, 0, test_shapes::box({0.3, 0.5, 0.4}),
                                                            1, uniform(rng, 0, 1), -1e-3)
                          : test_shapes::place_vertex_on_face(
                                a, pair % a.size(), test_shapes::random_hull(rng, 8, 0.4), -0.05);
    const Planes both0 = test_shapes::concat(a, b0);
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& v : test_shapes::vertices(both0)) origin += v;
    origin /= static_cast<double>(test_shapes::vertices(both0).size());
    const Eigen::Vector3d axis = test_shapes::random_unit_vector(rng);
    Eigen::Vector3d normal =
        boxes ? Eigen::Vector3d(a[0].normal) : test_shapes::random_unit_vector(rng);
    SliceWarmStart warm;
    for (int step = 0; step < 30; ++step) {
      // B turns by up to 20 mrad per step about the origin, and the slice normal wanders.
      const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.02 * step, axis).toRotationMatrix();
      const Planes both =
          test_shapes::concat(a, test_shapes::transformed(b0, turn, origin - turn * origin));
      normal = (normal + 0.01 * test_shapes::random_unit_vector(rng)).normalized();
      const std::size_t before = warm.count;
      const SlicePolygon cold = slice_halfspaces(both, origin, normal, 8.0);
      const SlicePolygon hot = slice_halfspaces(both, origin, normal, 8.0, warm);
      ++steps;
      if (before > 0 && warm.count == before) ++warm_accepted;
      ASSERT_EQ(hot.vertices.size(), cold.vertices.size()) << "pair " << pair << " step " << step;
      EXPECT_NEAR(hot.area(), cold.area(), 1e-13 * (1.0 + cold.area()));
      EXPECT_LT(vertex_set_distance(hot, cold), 1e-12);
      EXPECT_LT(vertex_set_distance(cold, hot), 1e-12);
    }
  }
  // The warm start is the common case (this also proves the test exercises it).
  EXPECT_GT(warm_accepted, steps / 2);
}

// A stale warm start naming planes that no longer bound the slice is rejected.
TEST(SlicePolygon, StaleWarmStartFallsBackToClipping) {
  const Planes cube = test_shapes::box(Eigen::Vector3d::Constant(0.5));
  SliceWarmStart warm;
  const SlicePolygon square =
      slice_halfspaces(cube, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 4.0, warm);
  ASSERT_EQ(warm.count, 4u);
  // The same planes for a slice normal to x: the old edges (the x and y faces) no longer bound it.
  const SlicePolygon side =
      slice_halfspaces(cube, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 4.0, warm);
  EXPECT_NEAR(side.area(), 1.0, 1e-14);
  EXPECT_EQ(warm.count, 4u);
  // Indices beyond the plane list are rejected too.
  warm.edge_planes = {0, 1, 2, 99};
  warm.count = 4;
  EXPECT_NEAR(
      slice_halfspaces(cube, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 4.0, warm).area(),
      square.area(), 1e-14);
}

// A warm polygon that one plane cuts is rejected wherever that plane sits in the list (the inside
// test takes the planes two at a time, with a last plane of an odd count on its own).
TEST(SlicePolygon, WarmStartCutByAnyPlaneOfTheListIsRejected) {
  const Planes cube = test_shapes::box(Eigen::Vector3d::Constant(0.5));
  const Eigen::Vector3d diagonal = Eigen::Vector3d(1.0, 1.0, 0.0).normalized();
  for (const bool even : {false, true}) {
    for (std::size_t k = 0; k <= cube.size(); ++k) {
      // x + y <= 0.9 cuts the corner (0.5, 0.5) of the unit square: area 1 - 0.1²/2. The same
      // plane moved to x + y <= 5 cuts nothing and lets the square's edges be the warm start.
      const auto with_plane = [&](double offset) {
        Planes planes = cube;
        planes.insert(planes.begin() + static_cast<std::ptrdiff_t>(k),
                      Halfspace{diagonal, offset / std::sqrt(2.0)});
        if (even) planes.push_back(Halfspace{Eigen::Vector3d::UnitZ(), 5.0});
        return planes;
      };
      SliceWarmStart warm;
      const SlicePolygon square = slice_halfspaces(with_plane(5.0), Eigen::Vector3d::Zero(),
                                                   Eigen::Vector3d::UnitZ(), 4.0, warm);
      ASSERT_NEAR(square.area(), 1.0, 1e-14);
      ASSERT_EQ(warm.count, 4u);
      const SlicePolygon cut = slice_halfspaces(with_plane(0.9), Eigen::Vector3d::Zero(),
                                                Eigen::Vector3d::UnitZ(), 4.0, warm);
      EXPECT_EQ(cut.vertices.size(), 5u) << "plane " << k << (even ? " of 8" : " of 7");
      EXPECT_NEAR(cut.area(), 1.0 - 0.5 * 0.1 * 0.1, 1e-14);
    }
  }
}

}  // namespace
}  // namespace blockdem
