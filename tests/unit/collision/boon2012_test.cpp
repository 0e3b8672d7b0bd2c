// Tests of the Boon et al. (2012) narrow phase pipeline: the rounded normal and chord in closed
// form, warm-started (cached) calls against cold calls along trajectories, and the fast overlap
// LP against the same pipeline with the LP solved by CLP.
#include "blockdem/collision/boon2012.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "oracle/clp_boon2012.hpp"
#include "support/random_shapes.hpp"

namespace blockdem {
namespace {

using test_shapes::Planes;
using test_shapes::Rng;
using test_shapes::uniform;

const Boon2012Settings kSettings{};  // r_round = 0.2 mm

// Chord of a box through its centre along an axis: the box's size along it; along a body
// diagonal of a cube of edge e: e√3.
TEST(Boon2012, ChordLengthOfABox) {
  Rng rng(6);
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::Matrix3d r = test_shapes::random_rotation(rng);
    const Eigen::Vector3d c(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
    const Planes box = test_shapes::box({0.1, 0.2, 0.3}, r, c);
    EXPECT_NEAR(chord_length(box, c, r.col(1)), 0.4, 1e-14);
    const Planes cube = test_shapes::box(Eigen::Vector3d::Constant(0.2), r, c);
    EXPECT_NEAR(chord_length(cube, c, r * Eigen::Vector3d(1, 1, 1).normalized()),
                0.4 * std::sqrt(3.0), 1e-14);
  }
}

// The rounded gradient of a unit cube: within r_round of one face only,
// 2 (r - s) n of that face; within r_round of two faces, the sum; deeper, 2 r n of the nearest.
TEST(Boon2012, PotentialGradientOfACube) {
  const Planes cube = test_shapes::box(Eigen::Vector3d::Constant(0.5));
  const double r = 0.01;
  const Eigen::Vector3d one = potential_gradient(cube, {0.496, 0.1, 0.0}, r);
  EXPECT_LT((one - Eigen::Vector3d(2 * (r - 0.004), 0, 0)).norm(), 1e-15);
  const Eigen::Vector3d two = potential_gradient(cube, {0.497, 0.0, -0.492}, r);
  EXPECT_LT((two - Eigen::Vector3d(2 * (r - 0.003), 0, -2 * (r - 0.008))).norm(), 1e-15);
  const Eigen::Vector3d deep = potential_gradient(cube, {0.0, 0.3, 0.0}, r);
  EXPECT_LT((deep - Eigen::Vector3d(0, 2 * r, 0)).norm(), 1e-15);
}

// A pair and its trajectory: B moved by small rigid steps, as over time steps.
struct Trajectory {
  Planes a;
  std::vector<Planes> b;
  double extent = 0.0;
};

// 46 mm cubes face to face (closure 1e-7..1e-4 m, offset, tilt up to 0.2 mrad, random frame)
// and random hulls (B's vertex up to 1 mm into a face of A), 40 steps each.
std::vector<Trajectory> trajectories(Rng& rng, int pairs) {
  std::vector<Trajectory> out;
  for (int p = 0; p < pairs; ++p) {
    Trajectory t;
    Planes b;
    if (p % 2 == 0) {
      const Eigen::Matrix3d frame = test_shapes::random_rotation(rng);
      const Eigen::Vector3d half = Eigen::Vector3d::Constant(0.023);
      t.a = test_shapes::box(half, frame);
      const Eigen::Matrix3d tilt =
          frame *
          Eigen::AngleAxisd(uniform(rng, -2e-4, 2e-4), Eigen::Vector3d::UnitX()).toRotationMatrix();
      b = test_shapes::box(
          half, tilt,
          frame * Eigen::Vector3d(uniform(rng, -5e-3, 5e-3), uniform(rng, -5e-3, 5e-3),
                                  0.046 - std::pow(10.0, uniform(rng, -7, -4))));
      t.extent = 0.32;
    } else {
      t.a = test_shapes::random_hull(rng, 5 + p % 12, 0.02);
      b = test_shapes::place_vertex_on_face(t.a, p % t.a.size(),
                                            test_shapes::random_hull(rng, 5 + p % 9, 0.02),
                                            -std::pow(10.0, uniform(rng, -6, -3)));
      t.extent = 1.0;
    }
    const Eigen::Vector3d axis = test_shapes::random_unit_vector(rng);
    const Eigen::Vector3d velocity = 1e-8 * test_shapes::random_unit_vector(rng);
    const Eigen::Vector3d centre = 0.5 * test_shapes::vertices(t.a).front();
    for (int s = 0; s < 40; ++s) {
      const Eigen::Matrix3d turn = Eigen::AngleAxisd(1e-6 * s, axis).toRotationMatrix();
      t.b.push_back(test_shapes::transformed(b, turn, centre - turn * centre + s * velocity));
    }
    out.push_back(t);
  }
  return out;
}

// Compares two contact geometries of the same pair. The contact point is the analytic centre to
// a Newton decrement at round-off level (~1e-12), so two runs from different starts agree to
// ~1e-12 of the overlap's size in each direction (thickness across, block size along); normal
// and chord follow it smoothly. The area is worse conditioned: where a joint is partly open, a
// contact face cuts the slice at a grazing angle θ (down to 1e-4 rad here), which amplifies
// round-off in the normal by ~1/θ. Measured: point 5e-12 of the size, normal 2e-13, chord
// 3e-11 relative, area 2e-9 relative. Tolerances: 1e-10 of the size, 1e-9, 1e-9, 1e-8.
// (Vertex counts are not compared: an edge shorter than round-off may come and go.)
void expect_same_geometry(const ContactGeometry& g, const ContactGeometry& ref, double size,
                          const std::string& where) {
  ASSERT_EQ(g.touching, ref.touching) << where;
  EXPECT_NEAR(g.inscribed_radius, ref.inscribed_radius, 1e-12 * size) << where;
  if (!ref.touching) return;
  EXPECT_LT((g.point - ref.point).norm(), 1e-10 * size) << where;
  EXPECT_LT((g.normal - ref.normal).norm(), 1e-9) << where;
  EXPECT_NEAR(g.overlap, ref.overlap, 1e-9 * ref.overlap) << where;
  EXPECT_NEAR(g.area, ref.area, 1e-8 * ref.area) << where;
}

// Warm starts (LP from the last solution, analytic centre from the last point, slice from the
// last edges) change nothing beyond the tolerance of the analytic centre.
TEST(Boon2012, CachedCallsMatchColdCallsAlongTrajectories) {
  Rng rng(7);
  int touching = 0;
  for (const Trajectory& t : trajectories(rng, 60)) {
    Boon2012Cache cache;
    for (std::size_t s = 0; s < t.b.size(); ++s) {
      const ContactGeometry cold = boon2012_contact(t.a, t.b[s], t.extent, kSettings);
      const ContactGeometry warm = boon2012_contact(t.a, t.b[s], t.extent, kSettings, &cache);
      touching += cold.touching ? 1 : 0;
      expect_same_geometry(warm, cold, 0.046, "step " + std::to_string(s));
    }
  }
  EXPECT_GT(touching, 60 * 40 * 9 / 10);
}

// The same pipeline with CLP as the LP solver (the oracle path) gives the same geometry.
TEST(Boon2012, ClpPathMatchesFastPath) {
  Rng rng(8);
  for (const Trajectory& t : trajectories(rng, 40)) {
    Boon2012Cache fast_cache, clp_cache;
    oracle::ClpInscribedBallSolver solver;
    for (std::size_t s = 0; s < t.b.size(); s += 8) {
      const ContactGeometry fast = boon2012_contact(t.a, t.b[s], t.extent, kSettings, &fast_cache);
      const ContactGeometry clp_cold =
          oracle::clp_boon2012_contact(t.a, t.b[s], t.extent, kSettings);
      const ContactGeometry clp_warm =
          oracle::clp_boon2012_contact(t.a, t.b[s], t.extent, kSettings, &clp_cache, &solver);
      expect_same_geometry(clp_cold, fast, 0.046, "cold step " + std::to_string(s));
      expect_same_geometry(clp_warm, fast, 0.046, "warm step " + std::to_string(s));
    }
  }
}

// A cache filled for other plane lists is cleared, not misused.
TEST(Boon2012, CacheOfOtherPlaneListsIsCleared) {
  Rng rng(9);
  const Planes cube = test_shapes::box(Eigen::Vector3d::Constant(0.5));
  const Planes above = test_shapes::box(Eigen::Vector3d::Constant(0.5), Eigen::Matrix3d::Identity(),
                                        {0.1, 0, 0.999});
  const Planes hull =
      test_shapes::place_vertex_on_face(cube, 4, test_shapes::random_hull(rng, 9, 0.3), -1e-3);
  Boon2012Cache cache;
  boon2012_contact(cube, above, 4.0, kSettings, &cache);
  ASSERT_EQ(cache.planes_b, 6);
  const ContactGeometry warm = boon2012_contact(cube, hull, 4.0, kSettings, &cache);
  EXPECT_EQ(cache.planes_b, 9);
  expect_same_geometry(warm, boon2012_contact(cube, hull, 4.0, kSettings), 1.0, "hull");
}

}  // namespace
}  // namespace blockdem
