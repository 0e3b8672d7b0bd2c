// Contact geometry of two unit cubes in face, edge and vertex contact (mode boon2012) against
// hand-computed point, normal, overlap and area.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "blockdem/collision/boon2012.hpp"
#include "blockdem/geometry/polyhedron.hpp"
#include "support/dense_solves.hpp"

namespace blockdem {
namespace {

// Planes of a unit cube rotated by r and centred at c.
std::vector<Halfspace> cube(const Eigen::Matrix3d& r, const Eigen::Vector3d& c) {
  return copy_planes(Polyhedron::box({1, 1, 1}).transformed(r, c));
}

// Gradient of the barrier -Σ ln(d - n·x): zero at the analytic centre.
Eigen::Vector3d barrier_gradient(const std::vector<Halfspace>& a, const std::vector<Halfspace>& b,
                                 const Eigen::Vector3d& x) {
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  for (const auto* set : {&a, &b}) {
    for (const auto& p : *set) g += p.normal / p.slack(x);
  }
  return g;
}

// Minimiser of the barrier along the z axis through (0, 0), by bisection on its derivative:
// the hand-side of the analytic centre when symmetry puts it on that axis.
double centre_on_z_axis(const std::vector<Halfspace>& a, const std::vector<Halfspace>& b, double lo,
                        double hi) {
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (barrier_gradient(a, b, {0, 0, mid}).z() > 0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

const Boon2012Settings kSettings{};  // r_round = 0.2 mm

// Face to face: B above A, overlapping by h. The slab A∩B is 1 x 1 x h; every plane pair is
// symmetric about the slab's mid-plane, so x_c = (0, 0, 0.5 - h/2); n = +z; δ = h; A_c = 1.
TEST(ContactGeometryValidation, FaceToFace) {
  const double h = 1e-4;
  const auto a = cube(Eigen::Matrix3d::Identity(), {0, 0, 0});
  const auto b = cube(Eigen::Matrix3d::Identity(), {0, 0, 1 - h});
  const ContactGeometry g = boon2012_contact(a, b, 4.0, kSettings);
  ASSERT_TRUE(g.touching);
  EXPECT_LT((g.point - Eigen::Vector3d(0, 0, 0.5 - h / 2)).norm(), 1e-12);
  EXPECT_LT((g.normal - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  EXPECT_NEAR(g.overlap, h, 1e-12);
  EXPECT_NEAR(g.area, 1.0, 1e-12);
  EXPECT_NEAR(g.inscribed_radius, h / 2, 1e-12);
}

// Face to face with B shifted sideways by s: the overlap is (1 - s) x 1 x h, A_c = 1 - s.
TEST(ContactGeometryValidation, FaceToFaceShifted) {
  const double h = 1e-4, s = 0.3;
  const auto a = cube(Eigen::Matrix3d::Identity(), {0, 0, 0});
  const auto b = cube(Eigen::Matrix3d::Identity(), {s, 0, 1 - h});
  const ContactGeometry g = boon2012_contact(a, b, 4.0, kSettings);
  ASSERT_TRUE(g.touching);
  EXPECT_LT((g.normal - Eigen::Vector3d::UnitZ()).norm(), 1e-9);
  EXPECT_NEAR(g.overlap, h, 1e-12);
  EXPECT_NEAR(g.area, 1.0 - s, 1e-12);
  EXPECT_LT(barrier_gradient(a, b, g.point).norm(), 1e-6 * (1.0 / h));
}

// Edge to face: B turned 45° about x, its lowest edge (along x) a depth h into A's top face.
// A∩B is a prism of triangular section (apex down, 45° sides) and length 1. By symmetry x_c is
// on the z axis; the rounded normal is +z; the chord along z is h; the slice at height z_c is a
// 1 x 2(z_c - z_apex) rectangle.
TEST(ContactGeometryValidation, EdgeToFace) {
  const double h = 1e-4;
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const double z_apex = 0.5 - h;
  const auto a = cube(Eigen::Matrix3d::Identity(), {0, 0, 0});
  const auto b = cube(r, {0, 0, z_apex + std::sqrt(0.5)});
  const ContactGeometry g = boon2012_contact(a, b, 4.0, kSettings);
  ASSERT_TRUE(g.touching);
  const double z_c = centre_on_z_axis(a, b, z_apex + 1e-15, 0.5 - 1e-15);
  EXPECT_LT((g.point - Eigen::Vector3d(0, 0, z_c)).norm(), 1e-10);
  EXPECT_LT((g.normal - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  EXPECT_NEAR(g.overlap, h, 1e-12);
  EXPECT_NEAR(g.area, 2.0 * (z_c - z_apex), 1e-12);
}

// Vertex to face: B turned so that a body diagonal is vertical, its lowest vertex a depth h into
// A's top face. A∩B is a triangular pyramid; near the vertex B's three faces make the slice at
// depth t above the apex (normal to the diagonal) an equilateral triangle of side t√6, area
// (3√3/2) t². x_c is the analytic centre (barrier gradient zero), n is the diagonal +z to within
// the asymmetry of the far planes, the chord along n is h / n_z.
TEST(ContactGeometryValidation, VertexToFace) {
  const double h = 1e-4;
  // Rotation taking the diagonal (1,1,1)/√3 to -z, so the vertex (-½,-½,-½)... is the lowest.
  const Eigen::Matrix3d r =
      test::quaternion_between(Eigen::Vector3d(1, 1, 1).normalized(), Eigen::Vector3d::UnitZ())
          .toRotationMatrix();
  const double half_diagonal = std::sqrt(3.0) / 2;
  const double z_apex = 0.5 - h;
  const auto a = cube(Eigen::Matrix3d::Identity(), {0, 0, 0});
  const auto b = cube(r, {0, 0, z_apex + half_diagonal});
  const ContactGeometry g = boon2012_contact(a, b, 4.0, kSettings);
  ASSERT_TRUE(g.touching);
  // Analytic centre: the barrier's gradient vanishes (relative to its terms, ~1/h).
  EXPECT_LT(barrier_gradient(a, b, g.point).norm() * h, 1e-8);
  EXPECT_GT(g.point.z(), z_apex);
  EXPECT_LT(g.point.z(), 0.5);
  // Normal: A's top face and B's three faces near the vertex (the diagonal): +z.
  EXPECT_GT(g.normal.z(), 1 - 1e-6);
  EXPECT_NEAR(g.overlap, h / g.normal.z(), 1e-6 * h);
  const double t = g.point.z() - z_apex;
  EXPECT_NEAR(g.area, 1.5 * std::sqrt(3.0) * t * t, 1e-3 * g.area);
}

// Apart and touching: no contact.
TEST(ContactGeometryValidation, SeparatedAndTouchingCubesHaveNoContact) {
  const auto a = cube(Eigen::Matrix3d::Identity(), {0, 0, 0});
  EXPECT_FALSE(boon2012_contact(a, cube(Eigen::Matrix3d::Identity(), {0, 0, 1.001}), 4.0, kSettings)
                   .touching);
  EXPECT_FALSE(
      boon2012_contact(a, cube(Eigen::Matrix3d::Identity(), {0, 0, 1.0}), 4.0, kSettings).touching);
}

}  // namespace
}  // namespace blockdem
