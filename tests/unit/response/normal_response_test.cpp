// The normal response step without a World, driven along closure paths: the point contact's
// σ_n(δ) A_c and the face contact's integrated force, centre of pressure, stiffness and stored
// energy against closed forms for a square contact.
#include "blockdem/response/normal_response.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "square_cells.hpp"

// A namespace of this file's own: the unity build (cmake/build_speed.cmake) compiles it together
// with other test files that define helpers of the same names.
namespace blockdem::test::response_normal {
namespace {

constexpr double kSide = 0.046;      // square side a (m), the paper's blocks
constexpr double kStiffness = 1e10;  // k_n (Pa/m)
constexpr double kArea = kSide * kSide;

// A point contact at the origin whose slice is the square [-a/2, a/2]² in the plane z = 0.
ContactGeometry square_point_contact(double overlap) {
  ContactGeometry g;
  g.touching = true;
  g.overlap = overlap;
  g.area = kArea;
  const double h = kSide / 2;
  g.slice.vertices = SliceVertices{{-h, -h}, {h, -h}, {h, h}, {-h, h}};
  return g;
}

// The square [0, a]² as two cells, the closure g0 + slope x (m).
FaceContactGeometry square_cells(double g0, double slope) {
  return test::square_cells(kSide, g0, slope);
}

// Loading path of a point contact under the linear law: F_n = k_n δ A_c at every closure, the
// spring k_n A_c, and the stored energy ½ F_n δ = F_n² / (2 k_n A_c). Reference: the linear law
// (Boon et al. 2015, Table 2) over the slice; 1e-12 relative (round-off).
TEST(NormalResponse, PointContactUnderTheLinearLawIsAPlainSpring) {
  const NormalLaw law = LinearNormal{kStiffness};
  for (int i = 1; i <= 20; ++i) {
    const double overlap = 1e-6 * i;
    const NormalResponse r = point_normal_response(law, square_point_contact(overlap));
    const double force = kStiffness * overlap * kArea;
    EXPECT_FALSE(r.integrated);
    EXPECT_NEAR(r.force, force, 1e-12 * force);
    EXPECT_NEAR(r.stress, kStiffness * overlap, 1e-12 * kStiffness * overlap);
    EXPECT_NEAR(r.stiffness, kStiffness * kArea, 1e-12 * kStiffness * kArea);
    const double energy = force * force / (2 * kStiffness * kArea);
    EXPECT_NEAR(r.energy, energy, 1e-12 * energy);
    // The shear spring at the slice's centroid, the force at x_c (both the origin here).
    EXPECT_LT(r.shear_point.norm(), 1e-15);
    EXPECT_EQ(r.force_point, Eigen::Vector3d::Zero());
  }
}

// The exponential law at a point contact: F_n = a (exp(b δ) - 1) A_c and the spring
// a b exp(b δ) A_c (Boon et al. 2015, eq 3 integrated); 1e-12 relative.
TEST(NormalResponse, PointContactUnderTheExponentialLaw) {
  const ExponentialNormal e = ExponentialNormal::eq3();
  const NormalLaw law = e;
  const double overlap = 2e-5;
  const NormalResponse r = point_normal_response(law, square_point_contact(overlap));
  const double force = e.a * std::expm1(e.b * overlap) * kArea;
  EXPECT_NEAR(r.force, force, 1e-12 * force);
  const double spring = e.a * e.b * std::exp(e.b * overlap) * kArea;
  EXPECT_NEAR(r.stiffness, spring, 1e-12 * spring);
}

// A face contact under a uniform closure g: F_n = k_n g a² at the square's centre, the shear
// spring at the same centre, the spring k_n a², and the energy ∫ ½ k_n g² dA = F_n² / (2 k_n a²).
// 1e-12 relative; the points to 1e-12 a.
TEST(NormalResponse, FaceContactUnderAUniformClosure) {
  const NormalLaw law = LinearNormal{kStiffness};
  const Eigen::Vector3d centre(kSide / 2, kSide / 2, 0.0);
  for (const double g : {1e-6, 5e-6, 2e-5}) {
    const FaceContactGeometry fc = square_cells(g, 0.0);
    const std::optional<NormalResponse> r = normal_response(law, ContactGeometry{}, fc);
    ASSERT_TRUE(r.has_value());
    EXPECT_TRUE(r->integrated);
    const double force = kStiffness * g * kArea;
    EXPECT_NEAR(r->force, force, 1e-12 * force);
    EXPECT_NEAR(r->compressed_area, kArea, 1e-12 * kArea);
    EXPECT_NEAR(r->stiffness, kStiffness * kArea, 1e-12 * kStiffness * kArea);
    const double energy = force * force / (2 * kStiffness * kArea);
    EXPECT_NEAR(r->energy, energy, 1e-12 * energy);
    EXPECT_LT((r->force_point - centre).norm(), 1e-12 * kSide);
    EXPECT_LT((r->shear_point - centre).norm(), 1e-12 * kSide);
  }
}

// A hinging joint, closure g = s x (zero along the edge x = 0): F_n = k_n s a³ / 2, the centre of
// pressure at x = 2a/3 (the centroid of a triangular load), the shear spring at the area's
// centroid x = a/2, σ_n = F_n / a², the peak closure s a and the spring k_n a². 1e-12 relative.
TEST(NormalResponse, FaceContactOfAHingingJoint) {
  const NormalLaw law = LinearNormal{kStiffness};
  const double s = 1e-3;  // closure gradient (m/m)
  const std::optional<NormalResponse> r =
      normal_response(law, ContactGeometry{}, square_cells(0.0, s));
  ASSERT_TRUE(r.has_value());
  const double force = kStiffness * s * std::pow(kSide, 3) / 2;
  EXPECT_NEAR(r->force, force, 1e-12 * force);
  EXPECT_NEAR(r->compressed_area, kArea, 1e-12 * kArea);
  EXPECT_NEAR(r->stress, force / kArea, 1e-12 * force / kArea);
  EXPECT_NEAR(r->peak_closure, s * kSide, 1e-12 * s * kSide);
  EXPECT_NEAR(r->force_point.x(), 2 * kSide / 3, 1e-12 * kSide);
  EXPECT_NEAR(r->force_point.y(), kSide / 2, 1e-12 * kSide);
  EXPECT_NEAR(r->shear_point.x(), kSide / 2, 1e-12 * kSide);
  EXPECT_NEAR(r->shear_point.y(), kSide / 2, 1e-12 * kSide);
  EXPECT_NEAR(r->stiffness, kStiffness * kArea, 1e-12 * kStiffness * kArea);
}

// A face contact with zero closure everywhere has no normal response (the world then looks for a
// bond that holds the faces); a contact without a face is a point contact.
TEST(NormalResponse, NoClosureNoResponseAndNoFaceIsAPointContact) {
  const NormalLaw law = LinearNormal{kStiffness};
  EXPECT_FALSE(normal_response(law, ContactGeometry{}, square_cells(0.0, 0.0)).has_value());
  const std::optional<NormalResponse> point =
      normal_response(law, square_point_contact(1e-6), FaceContactGeometry{});
  ASSERT_TRUE(point.has_value());
  EXPECT_FALSE(point->integrated);
  EXPECT_NEAR(point->force, kStiffness * 1e-6 * kArea, 1e-12 * kStiffness * 1e-6 * kArea);
}

}  // namespace
}  // namespace blockdem::test::response_normal
