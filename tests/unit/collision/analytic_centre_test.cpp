// Tests of the analytic centre (Boon et al. 2012 contact point): closed forms (box centre, simplex
// centroid), starts near walls, the stationarity of the barrier, nanometre-thin overlaps whose
// decrement is limited by round-off, and a start outside.
#include "blockdem/collision/analytic_centre.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "support/dense_solves.hpp"
#include "support/random_shapes.hpp"

namespace blockdem {
namespace {

using test_shapes::Planes;
using test_shapes::Rng;
using test_shapes::uniform;

// Smallest slack d - n·x over the planes (m).
double min_slack_of(const Planes& planes, const Eigen::Vector3d& x) {
  double s = std::numeric_limits<double>::infinity();
  for (const Halfspace& p : planes) s = std::min(s, p.slack(x));
  return s;
}

// The Newton decrement of φ = -Σ ln(d - n·x) at x: sqrt(gᵀ H⁻¹ g) (-).
double newton_decrement(const Planes& planes, const Eigen::Vector3d& x) {
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (const Halfspace& p : planes) {
    const Eigen::Vector3d w = p.normal / p.slack(x);
    g += w;
    h += w * w.transpose();
  }
  return std::sqrt(g.dot(test::solve_ldlt(h, g)));
}

// A box's analytic centre is its centre (each pair of opposite faces is balanced there), from
// any start, including starts a millionth of the box size from a corner (thin boxes too).
TEST(AnalyticCentre, BoxCentreFromStartsNearCorners) {
  Rng rng(3);
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Vector3d half(std::pow(10.0, uniform(rng, -5, 0)), uniform(rng, 0.1, 1.0),
                               uniform(rng, 0.1, 1.0));
    const Eigen::Matrix3d r = test_shapes::random_rotation(rng);
    const Eigen::Vector3d c(uniform(rng, -2, 2), uniform(rng, -2, 2), uniform(rng, -2, 2));
    const Planes box = test_shapes::box(half, r, c);
    const double margin = std::pow(10.0, uniform(rng, -6, -0.5));
    const Eigen::Vector3d corner(uniform(rng, -1, 1) > 0 ? 1 : -1, uniform(rng, -1, 1) > 0 ? 1 : -1,
                                 uniform(rng, -1, 1) > 0 ? 1 : -1);
    const Eigen::Vector3d start = c + r * corner.cwiseProduct(half * (1.0 - margin));
    const AnalyticCentreResult res = analytic_centre(box, start);
    ASSERT_TRUE(res.start_inside);
    ASSERT_TRUE(res.converged) << "trial " << trial;
    // Newton decrement below 1e-10 at the result: distance to the centre below ~1e-10 of the
    // half sizes in the Hessian norm; asserted per axis with round-off headroom.
    const Eigen::Vector3d local = r.transpose() * (res.point - c);
    for (int k = 0; k < 3; ++k) EXPECT_LT(std::abs(local[k]), 1e-9 * half[k] + 1e-15) << trial;
    EXPECT_LE(res.iterations, 40);
  }
}

// The analytic centre of a tetrahedron is its centroid (the minimiser is affine invariant, and
// for the standard simplex symmetry puts it at the centroid).
TEST(AnalyticCentre, TetrahedronCentroid) {
  Rng rng(4);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<Eigen::Vector3d> v;
    for (int i = 0; i < 4; ++i)
      v.emplace_back(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
    const Eigen::Vector3d centroid = (v[0] + v[1] + v[2] + v[3]) / 4.0;
    const double volume = std::abs((v[1] - v[0]).cross(v[2] - v[0]).dot(v[3] - v[0])) / 6.0;
    if (volume < 1e-3) continue;
    Planes planes;
    for (int i = 0; i < 4; ++i) {
      // Face opposite vertex i, normal pointing away from it.
      const Eigen::Vector3d& p = v[(i + 1) % 4];
      Eigen::Vector3d n = (v[(i + 2) % 4] - p).cross(v[(i + 3) % 4] - p).normalized();
      if (n.dot(v[i] - p) > 0) n = -n;
      Halfspace h;
      h.normal = n;
      h.offset = n.dot(p);
      planes.push_back(h);
    }
    // Start near vertex 0.
    const AnalyticCentreResult res = analytic_centre(planes, v[0] + 1e-4 * (centroid - v[0]));
    ASSERT_TRUE(res.converged);
    EXPECT_LT((res.point - centroid).norm(), 1e-9);
  }
}

// A thin, wide, wedge-shaped overlap of two tilted boxes (the hard case: the LP's centre sits by
// a side wall): the result is stationary (decrement below 1e-10 plus round-off) and lies in
// the overlap.
TEST(AnalyticCentre, WedgeOverlapIsStationary) {
  Rng rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Matrix3d frame = test_shapes::random_rotation(rng);
    const double closure = std::pow(10.0, uniform(rng, -7, -4));
    const Eigen::Vector3d half = Eigen::Vector3d::Constant(0.023);
    const Planes a = test_shapes::box(half, frame);
    const Eigen::Matrix3d tilt =
        frame *
        Eigen::AngleAxisd(uniform(rng, -0.5, 0.5) * closure / 0.046, Eigen::Vector3d::UnitX())
            .toRotationMatrix();
    const double offset = uniform(rng, -1e-3, 1e-3);
    const Planes b =
        test_shapes::box(half, tilt, frame * Eigen::Vector3d(offset, 0.0, 0.046 - closure));
    const Planes both = test_shapes::concat(a, b);
    // Start by a side wall of the overlap (a closure away), as the LP's vertex does.
    const double wall = std::min(0.023, 0.023 + offset);
    const Eigen::Vector3d start = frame * Eigen::Vector3d(wall - closure, 0.0, 0.023 - closure / 2);
    ASSERT_GT(min_slack_of(both, start), 0.0);
    const AnalyticCentreResult res = analytic_centre(both, start);
    ASSERT_TRUE(res.converged);
    EXPECT_LT(newton_decrement(both, res.point), 1e-9) << trial;
    EXPECT_GT(min_slack_of(both, res.point), 0.0);
  }
}

// Side faces of neighbouring 46 mm bricks a metre from the origin that overlap by a nanometre
// or less: the overlap is a box 46 mm x 46 mm x closure, whose analytic centre is its centre.
// The slacks across it carry round-off errors of ~1e-16 m, so the decrement cannot fall below
// ~1e-6 there; Newton's method must stop at its round-off floor (a handful of iterations) with
// the centre found in the plane of the faces to 1e-9 of the half size and across them to a
// hundredth of the closure.
TEST(AnalyticCentre, NanometreOverlapFarFromOriginStopsAtRoundOff) {
  Rng rng(6);
  for (int trial = 0; trial < 200; ++trial) {
    // Faces normal to x or y, as in a brick pile (a rotated overlap this thin makes the world
    // frame Hessian singular to round-off: not a case this test covers).
    const Eigen::Matrix3d frame =
        trial % 2 == 0 ? Eigen::Matrix3d::Identity()
                       : Eigen::Matrix3d(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
    const Eigen::Vector3d centre(uniform(rng, 0.5, 1.5), uniform(rng, 0.5, 1.5),
                                 uniform(rng, 0.0, 0.5));
    const double closure = std::pow(10.0, uniform(rng, -10, -9));
    const Eigen::Vector3d half = Eigen::Vector3d::Constant(0.023);
    const Planes a = test_shapes::box(half, frame, centre);
    const Planes b =
        test_shapes::box(half, frame, centre + frame * Eigen::Vector3d(0.046 - closure, 0, 0));
    const Planes both = test_shapes::concat(a, b);
    // The overlap's centre, and a start by one of its side walls (as the LP's centre may be).
    const Eigen::Vector3d middle = centre + frame * Eigen::Vector3d(0.023 - closure / 2, 0, 0);
    const Eigen::Vector3d start =
        middle + frame * Eigen::Vector3d(uniform(rng, -0.2, 0.2) * closure, 0.02, -0.015);
    ASSERT_GT(min_slack_of(both, start), 0.0);
    const AnalyticCentreResult res = analytic_centre(both, start);
    ASSERT_TRUE(res.converged) << trial << ": " << res.iterations << " iterations";
    EXPECT_LE(res.iterations, 25) << trial;
    const Eigen::Vector3d local = frame.transpose() * (res.point - middle);
    EXPECT_LT(std::abs(local.x()), 1e-2 * closure) << trial;
    EXPECT_LT(std::abs(local.y()), 1e-9 * 0.023) << trial;
    EXPECT_LT(std::abs(local.z()), 1e-9 * 0.023) << trial;
    EXPECT_GT(min_slack_of(both, res.point), 0.0);
  }
}

TEST(AnalyticCentre, StartOutsideIsReported) {
  const Planes box = test_shapes::box(Eigen::Vector3d::Constant(1.0));
  const AnalyticCentreResult res = analytic_centre(box, Eigen::Vector3d(2, 0, 0));
  EXPECT_FALSE(res.start_inside);
  EXPECT_FALSE(res.converged);
  EXPECT_EQ(res.point, Eigen::Vector3d(2, 0, 0));
  // On a face is not strictly inside either.
  EXPECT_FALSE(analytic_centre(box, Eigen::Vector3d(1, 0, 0)).start_inside);
}

}  // namespace
}  // namespace blockdem
