// Integrals of the normal laws over triangles and polygons with linear closure: checked against a
// nested-quadrature oracle, against the strip formulas of the antiderivatives, and against the
// closed form of a linear joint hinging open.
#include "blockdem/contact/normal_integral.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "law_test_support.hpp"

namespace blockdem {
namespace normal_integral_test {
namespace {

using test::gauss_legendre;
using test::relative_difference;

/// Oracle: (1/A) int_T w(lambda) sigma(g) dA = 2 int_0^1 int_0^(1-l1) ... dl2 dl1 by nested
/// Gauss-Legendre, with both integrals split where g = 0 meets the integration path, so that
/// every piece is smooth.
TriangleStressMoments oracle(const NormalLaw& law, const Eigen::Vector3d& g) {
  const auto closure = [&](double l1, double l2) {
    return g[0] + l1 * (g[1] - g[0]) + l2 * (g[2] - g[0]);
  };
  // Integrates f(l1, l2) sigma over the triangle with splits at the kink.
  const auto integrate = [&](auto weight) {
    const auto inner = [&](double l1) {
      const double top = 1.0 - l1;
      std::vector<double> cuts = {0.0, top};
      if (g[2] != g[0]) {
        const double l2 = -(g[0] + l1 * (g[1] - g[0])) / (g[2] - g[0]);
        if (l2 > 0.0 && l2 < top) cuts.push_back(l2);
      }
      std::sort(cuts.begin(), cuts.end());
      double sum = 0.0;
      for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
        sum += gauss_legendre(
            [&](double l2) { return weight(l1, l2) * normal_stress(law, closure(l1, l2)); },
            cuts[i], cuts[i + 1], 8);
      }
      return sum;
    };
    // Outer cuts: where g = 0 passes through an end of the inner segment (l2 = 0, l2 = 1 - l1).
    std::vector<double> cuts = {0.0, 1.0};
    if (g[1] != g[0]) cuts.push_back(-g[0] / (g[1] - g[0]));
    if (g[1] != g[2]) cuts.push_back(-g[2] / (g[1] - g[2]));
    std::sort(cuts.begin(), cuts.end());
    double sum = 0.0;
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
      const double lo = std::max(cuts[i], 0.0), hi = std::min(cuts[i + 1], 1.0);
      if (hi > lo) sum += gauss_legendre(inner, lo, hi, 8);
    }
    return 2.0 * sum;
  };
  TriangleStressMoments m;
  m.mean_stress = integrate([](double, double) { return 1.0; });
  m.vertex_weights[0] = integrate([](double l1, double l2) { return 1.0 - l1 - l2; });
  m.vertex_weights[1] = integrate([](double l1, double) { return l1; });
  m.vertex_weights[2] = integrate([](double, double l2) { return l2; });
  return m;
}

const std::array<NormalLaw, 3> kLaws = {NormalLaw{LinearNormal{10e9}},
                                        NormalLaw{ExponentialNormal::eq3()},
                                        NormalLaw{ExponentialNormal::eq4()}};

TEST(NormalIntegral, UniformClosureGivesTheLocalStress) {
  for (const auto& law : kLaws) {
    for (const double g : {1e-9, 2e-5, 9e-5}) {
      const auto m = integrate_normal_stress_over_triangle(law, Eigen::Vector3d::Constant(g));
      const double sigma = normal_stress(law, g);
      EXPECT_LT(relative_difference(m.mean_stress, sigma), 1e-13) << law_name(law) << " " << g;
      for (int i = 0; i < 3; ++i) {
        EXPECT_LT(relative_difference(m.vertex_weights[i], sigma / 3.0), 1e-13);
      }
      EXPECT_DOUBLE_EQ(m.compressed_fraction, 1.0);
    }
  }
}

TEST(NormalIntegral, TrianglesMatchTheQuadratureOracle) {
  // Closed, partly open (one or two vertices open) and nearly uniform triangles; closures up to
  // 0.1 mm, where eq 3 spans exp(7.4) = 1600-fold stress range.
  const std::array<Eigen::Vector3d, 7> cases = {
      Eigen::Vector3d(1e-5, 4e-5, 9e-5),   Eigen::Vector3d(8e-5, -3e-5, 2e-5),
      Eigen::Vector3d(-6e-5, 1e-4, -1e-5), Eigen::Vector3d(0.0, 5e-5, 0.0),
      Eigen::Vector3d(3e-5, 3e-5, 3.1e-5), Eigen::Vector3d(7e-5, 7e-5 + 1e-13, 7e-5 - 1e-13),
      Eigen::Vector3d(2e-7, 9e-5, 9e-5)};
  for (const auto& law : kLaws) {
    for (const auto& g : cases) {
      const auto m = integrate_normal_stress_over_triangle(law, g);
      const auto o = oracle(law, g);
      EXPECT_LT(relative_difference(m.mean_stress, o.mean_stress), 1e-11)
          << law_name(law) << " g = " << g.transpose();
      for (int i = 0; i < 3; ++i) {
        EXPECT_LT(relative_difference(m.vertex_weights[i], o.vertex_weights[i]), 1e-11)
            << law_name(law) << " g = " << g.transpose() << " vertex " << i;
      }
      EXPECT_LT(relative_difference(m.vertex_weights.sum(), m.mean_stress), 1e-13);
    }
  }
}

TEST(NormalIntegral, OpenTriangleCarriesNothing) {
  const auto m =
      integrate_normal_stress_over_triangle(kLaws[1], Eigen::Vector3d(-1e-5, 0.0, -3e-5));
  EXPECT_EQ(m.mean_stress, 0.0);
  EXPECT_EQ(m.compressed_fraction, 0.0);
  EXPECT_EQ(m.vertex_weights, Eigen::Vector3d::Zero());
}

TEST(NormalIntegral, CompressedFractionOfAPartlyOpenTriangle) {
  // g = (1, -1, -1): the compressed part is the corner triangle cut at the edge midpoints.
  const auto m =
      integrate_normal_stress_over_triangle(kLaws[0], Eigen::Vector3d(1e-5, -1e-5, -1e-5));
  EXPECT_DOUBLE_EQ(m.compressed_fraction, 0.25);
}

/// A w x L rectangle in the plane z = 0 with x along L, as polygon vertices in order.
std::vector<Eigen::Vector3d> rectangle(double length, double width) {
  return {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(length, 0, 0),
          Eigen::Vector3d(length, width, 0), Eigen::Vector3d(0, width, 0)};
}

TEST(NormalIntegral, LinearJointHingingOpenAtMidDepth) {
  // Closure g0 (1 - 2x/L): the half x < L/2 is compressed with a triangular stress block, so
  // F = k g0 w L / 4 acting at x = L/6, a third of the compressed length from the edge.
  const double k = 10e9, g0 = 2e-5, length = 0.046, width = 0.046;
  const auto vertices = rectangle(length, width);
  const std::vector<double> closures = {g0, -g0, -g0, g0};
  const auto r = integrate_normal_stress_over_polygon(LinearNormal{k}, vertices, closures);
  EXPECT_LT(relative_difference(r.force, k * g0 * width * length / 4.0), 1e-13);
  ASSERT_TRUE(r.centre_of_pressure.has_value());
  EXPECT_NEAR(r.centre_of_pressure->x(), length / 6.0, 1e-15);
  EXPECT_NEAR(r.centre_of_pressure->y(), width / 2.0, 1e-15);
  EXPECT_NEAR(r.centre_of_pressure->z(), 0.0, 1e-18);
  EXPECT_LT(relative_difference(r.compressed_area, length * width / 2.0), 1e-13);
  EXPECT_LT(relative_difference(r.area, length * width), 1e-15);
  EXPECT_DOUBLE_EQ(r.peak_stress, k * g0);
}

TEST(NormalIntegral, ExponentialStripAgreesWithTheAntiderivatives) {
  // Closure linear in x only: F = w (Phi1(gL) - Phi1(g0)) / s with s = dg/dx, and
  // int x sigma dx = [g Phi1 - Phi2 - g0 Phi1](g0..gL) / s^2.
  const NormalLaw law = ExponentialNormal::eq4();
  const double length = 0.046, width = 0.023, g0 = 9e-5, g_end = -4e-5;
  const double slope = (g_end - g0) / length;
  const auto vertices = rectangle(length, width);
  const auto r = integrate_normal_stress_over_polygon(law, vertices,
                                                      std::vector<double>{g0, g_end, g_end, g0});
  const auto phi1 = [&](double g) { return normal_stress_integral(law, g); };
  const auto phi2 = [&](double g) { return normal_stress_second_integral(law, g); };
  const double force = width * (phi1(g_end) - phi1(g0)) / slope;
  const auto moment_term = [&](double g) { return g * phi1(g) - phi2(g) - g0 * phi1(g); };
  const double x_moment = width * (moment_term(g_end) - moment_term(g0)) / (slope * slope);
  EXPECT_LT(relative_difference(r.force, force), 1e-12);
  ASSERT_TRUE(r.centre_of_pressure.has_value());
  EXPECT_LT(relative_difference(r.centre_of_pressure->x(), x_moment / force), 1e-12);
  EXPECT_NEAR(r.centre_of_pressure->y(), width / 2.0, 1e-15);
  EXPECT_LT(relative_difference(r.compressed_area, width * length * g0 / (g0 - g_end)), 1e-13);
  EXPECT_DOUBLE_EQ(r.peak_stress, normal_stress(law, g0));
}

TEST(NormalIntegral, PolygonResultantIsFrameIndependent) {
  // A hexagon with a tilted closure field, then the same contact rotated and translated: the
  // force is unchanged and the centre of pressure moves with the polygon.
  const NormalLaw law = ExponentialNormal::eq3();
  std::vector<Eigen::Vector3d> hexagon;
  std::vector<double> closures;
  for (int i = 0; i < 6; ++i) {
    const double angle = i * M_PI / 3.0;
    const Eigen::Vector3d p(0.02 * std::cos(angle), 0.015 * std::sin(angle), 0.0);
    hexagon.push_back(p);
    closures.push_back(3e-5 + 2e-3 * p.x() - 1e-3 * p.y());
  }
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  const Eigen::Vector3d shift(0.3, -0.1, 2.0);
  std::vector<Eigen::Vector3d> moved;
  for (const auto& p : hexagon) moved.push_back(rotation * p + shift);
  const auto a = integrate_normal_stress_over_polygon(law, hexagon, closures);
  const auto b = integrate_normal_stress_over_polygon(law, moved, closures);
  EXPECT_LT(relative_difference(b.force, a.force), 1e-13);
  ASSERT_TRUE(a.centre_of_pressure && b.centre_of_pressure);
  EXPECT_LT((*b.centre_of_pressure - (rotation * *a.centre_of_pressure + shift)).norm(), 1e-15);
  // The stress grows with x and falls with y, so the centre of pressure sits at x > 0, y < 0.
  EXPECT_GT(a.centre_of_pressure->x(), 0.0);
  EXPECT_LT(a.centre_of_pressure->y(), 0.0);
}

TEST(NormalIntegral, OpenPolygonHasNoCentreOfPressure) {
  const auto r = integrate_normal_stress_over_polygon(
      LinearNormal{}, rectangle(0.01, 0.01), std::vector<double>{-1e-6, -2e-6, 0.0, -1e-6});
  EXPECT_EQ(r.force, 0.0);
  EXPECT_FALSE(r.centre_of_pressure.has_value());
}

// The polygon dispatches the law once and integrates its fan triangles in line: the same sums,
// bit for bit, as integrating each fan triangle through the public triangle function (compressed
// triangles and partly open ones, both laws).
TEST(NormalIntegral, PolygonIsTheSumOfItsFanTrianglesBitForBit) {
  const std::vector<Eigen::Vector3d> vertices = {{0.0, 0.0, 0.01},
                                                 {0.04, -0.005, 0.012},
                                                 {0.05, 0.03, 0.011},
                                                 {0.02, 0.045, 0.009},
                                                 {-0.01, 0.02, 0.0105}};
  const std::vector<std::vector<double>> fields = {
      {2e-5, 3e-5, 1e-5, 4e-5, 2.5e-5},    // compressed throughout
      {2e-5, -3e-5, 1e-5, -4e-5, 2.5e-5},  // partly open
      {9e-4, 1e-5, 2e-4, 6e-4, 3e-6}};     // widely spread (the exponential law's recursion)
  for (const NormalLaw& law :
       {NormalLaw{LinearNormal{10e9}}, NormalLaw{ExponentialNormal::eq4()}}) {
    for (const auto& closures : fields) {
      double area = 0.0, compressed = 0.0, force = 0.0;
      Eigen::Vector3d moment = Eigen::Vector3d::Zero();
      for (std::size_t k = 1; k + 1 < vertices.size(); ++k) {
        const Eigen::Vector3d& a = vertices[0];
        const Eigen::Vector3d& b = vertices[k];
        const Eigen::Vector3d& c = vertices[k + 1];
        const double triangle = 0.5 * (b - a).cross(c - a).norm();
        const TriangleStressMoments m = integrate_normal_stress_over_triangle(
            law, Eigen::Vector3d(closures[0], closures[k], closures[k + 1]));
        area += triangle;
        compressed += triangle * m.compressed_fraction;
        force += triangle * m.mean_stress;
        moment += triangle *
                  (m.vertex_weights[0] * a + m.vertex_weights[1] * b + m.vertex_weights[2] * c);
      }
      const PolygonStressResultant r =
          integrate_normal_stress_over_polygon(law, vertices, closures);
      EXPECT_EQ(r.area, area);
      EXPECT_EQ(r.compressed_area, compressed);
      ASSERT_GT(force, 0.0);
      EXPECT_EQ(r.force, force);
      ASSERT_TRUE(r.centre_of_pressure.has_value());
      EXPECT_EQ(*r.centre_of_pressure, Eigen::Vector3d(moment / force));
      EXPECT_EQ(r.peak_stress,
                normal_stress(law, *std::max_element(closures.begin(), closures.end())));
    }
  }
}

TEST(NormalIntegral, RejectsMalformedPolygons) {
  const auto square = rectangle(0.01, 0.01);
  EXPECT_THROW(integrate_normal_stress_over_polygon(LinearNormal{}, square,
                                                    std::vector<double>{1e-6, 1e-6, 1e-6}),
               std::invalid_argument);
  EXPECT_THROW(integrate_normal_stress_over_polygon(
                   LinearNormal{}, std::span<const Eigen::Vector3d>(square.data(), 2),
                   std::vector<double>{1e-6, 1e-6}),
               std::invalid_argument);
  EXPECT_THROW(integrate_normal_stress_over_polygon(
                   LinearNormal{}, square, std::vector<double>{1e-6, std::nan(""), 1e-6, 1e-6}),
               std::invalid_argument);
}

}  // namespace
}  // namespace normal_integral_test
}  // namespace blockdem
