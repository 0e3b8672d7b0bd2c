// Polygon area moments against closed forms: a square about its centre (J = a⁴/6,
// ∫ r dA = a³ (√2 + asinh 1) / 6), the parallel-axis theorem about outside points, and a
// right triangle's polar moment.
#include "blockdem/geometry/polygon_moments.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace blockdem {
namespace {

std::vector<Eigen::Vector3d> square(double a, const Eigen::Matrix3d& r, const Eigen::Vector3d& t) {
  const double h = a / 2;
  return {t + r * Eigen::Vector3d(-h, -h, 0), t + r * Eigen::Vector3d(h, -h, 0),
          t + r * Eigen::Vector3d(h, h, 0), t + r * Eigen::Vector3d(-h, h, 0)};
}

TEST(PolygonMoments, SquareAboutItsCentre) {
  const double a = 0.046;
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(0.3, -0.1, 2.0);
  const PolygonMoments m = polygon_moments_about_centroid(square(a, r, t));
  // Closed forms (mean distance from the centre of a unit square: (√2 + ln(1 + √2)) / 6).
  EXPECT_NEAR(m.area, a * a, 1e-14 * a * a);
  EXPECT_NEAR((m.centroid - t).norm(), 0.0, 1e-14);
  EXPECT_NEAR(m.polar_moment / (std::pow(a, 4) / 6.0), 1.0, 1e-12);
  EXPECT_NEAR(m.radial_moment / (std::pow(a, 3) * (std::sqrt(2.0) + std::asinh(1.0)) / 6.0), 1.0,
              1e-12);
}

TEST(PolygonMoments, ParallelAxisTheoremAboutOutsidePoints) {
  // J about p = J about the centroid + A |p - c|², for poles inside and outside the polygon.
  const std::vector<Eigen::Vector3d> hexagon = [] {
    std::vector<Eigen::Vector3d> v;
    for (int i = 0; i < 6; ++i) {
      const double phi = i * 3.14159265358979323846 / 3 + 0.05 * i;
      v.emplace_back(0.02 * std::cos(phi), 0.02 * std::sin(phi), 0.0);
    }
    return v;
  }();
  const PolygonMoments c = polygon_moments_about_centroid(hexagon);
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0.005, 0.001, 0), Eigen::Vector3d(0.05, 0.0, 0),
                                   Eigen::Vector3d(-0.1, 0.2, 0)}) {
    const PolygonMoments m = polygon_moments(hexagon, p);
    EXPECT_NEAR(m.area, c.area, 1e-14);
    const double d2 = (p - c.centroid).squaredNorm();
    EXPECT_NEAR(m.polar_moment / (c.polar_moment + c.area * d2), 1.0, 1e-11);
    // Far away, ∫ r dA tends to A |p - c| (within A J / (2 |p - c|)-order terms): bounded by
    // Jensen, A |p - c| <= ∫ r dA <= sqrt(A J_p).
    EXPECT_GE(m.radial_moment, c.area * std::sqrt(d2) * (1 - 1e-12));
    EXPECT_LE(m.radial_moment, std::sqrt(m.area * m.polar_moment) * (1 + 1e-12));
  }
}

TEST(PolygonMoments, RightTriangleAboutItsRightAngle) {
  // Legs b, h at the origin: J = ∫ (x² + y²) dA = b h (b² + h²) / 12.
  const double b = 0.03, h = 0.05;
  const std::vector<Eigen::Vector3d> tri{{0, 0, 0}, {b, 0, 0}, {0, h, 0}};
  const PolygonMoments m = polygon_moments(tri, Eigen::Vector3d::Zero());
  EXPECT_NEAR(m.polar_moment / (b * h * (b * b + h * h) / 12.0), 1.0, 1e-12);
  EXPECT_NEAR(m.area / (b * h / 2), 1.0, 1e-14);
}

// A contact's slice polygon from a rock mass: four vertices within 1e-4 m of each other on a line
// 4 m from the origin (area ~1e-20 m^2). Reference: area, J and ∫ r dA are non-negative and at
// most A, A r_max^2, A r_max (r <= r_max, the largest vertex distance from the centroid).
TEST(PolygonMoments, SliverFarFromTheOriginHasNoNegativeMoments) {
  const std::vector<Eigen::Vector3d> sliver{
      {0.34469002147367228, 3.901192148904558, 3.707867359884772},
      {0.3431131844982383, 3.9015020344654556, 3.7076894924050996},
      {0.34728046484483183, 3.9006830658417213, 3.7081595623386989},
      {0.34728046484483199, 3.9006830658417218, 3.7081595623386985}};
  const PolygonMoments m = polygon_moments_about_centroid(sliver);
  EXPECT_GE(m.area, 0.0);
  EXPECT_GE(m.polar_moment, 0.0);
  EXPECT_GE(m.radial_moment, 0.0);
  double r_max = 0.0;
  for (const auto& v : sliver) r_max = std::max(r_max, (v - sliver[0]).norm());
  EXPECT_LE(m.polar_moment, m.area * r_max * r_max + 1e-30);
  EXPECT_LE(m.radial_moment, m.area * r_max + 1e-30);
}

// A thin rectangle a x b (b = 1e-6 a) 1000 m from the origin: closed form J = A (a² + b²) / 12
// about its centre, relative 1e-6 (the vector area summed about a vertex, not the origin).
TEST(PolygonMoments, ThinRectangleFarFromTheOrigin) {
  const double a = 0.5, b = 0.5e-6;
  const Eigen::Vector3d t(1000.0, -700.0, 300.0);
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, -1, 2).normalized()).toRotationMatrix();
  const std::vector<Eigen::Vector3d> v{
      t + r * Eigen::Vector3d(-a / 2, -b / 2, 0), t + r * Eigen::Vector3d(a / 2, -b / 2, 0),
      t + r * Eigen::Vector3d(a / 2, b / 2, 0), t + r * Eigen::Vector3d(-a / 2, b / 2, 0)};
  const PolygonMoments m = polygon_moments_about_centroid(v);
  EXPECT_NEAR(m.area / (a * b), 1.0, 1e-6);
  EXPECT_NEAR(m.polar_moment / (a * b * (a * a + b * b) / 12.0), 1.0, 1e-6);
}

TEST(PolygonMoments, AreaAndCentroidAloneAreTheSameBits) {
  // Oracle: polygon_moments_about_centroid. Random convex polygons (points on an ellipse, sorted
  // by angle), turned and moved far from the origin, from triangles to 12-gons, and a sliver.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 3 + trial % 10;
    std::vector<double> angles;
    for (int i = 0; i < n; ++i) angles.push_back(2.0 * std::acos(-1.0) * u(rng));
    std::sort(angles.begin(), angles.end());
    const double a = 0.01 + u(rng), b = trial % 50 == 0 ? 1e-9 : 0.01 + u(rng);
    const Eigen::Matrix3d r =
        Eigen::AngleAxisd(6.0 * u(rng), Eigen::Vector3d(u(rng), u(rng), 1.0).normalized())
            .toRotationMatrix();
    const Eigen::Vector3d t(100.0 * u(rng), 100.0 * u(rng), 10.0 * u(rng));
    std::vector<Eigen::Vector3d> poly;
    for (double th : angles)
      poly.push_back(t + r * Eigen::Vector3d(a * std::cos(th), b * std::sin(th), 0.0));
    const PolygonMoments full = polygon_moments_about_centroid(poly);
    const PolygonMoments lean = polygon_area_centroid(poly);
    EXPECT_EQ(lean.area, full.area);
    EXPECT_EQ(lean.centroid, full.centroid);
    EXPECT_EQ(lean.polar_moment, 0.0);
    EXPECT_EQ(lean.radial_moment, 0.0);
  }
}

}  // namespace
}  // namespace blockdem
