// Twisting resistance of a face-integrated contact: a cube pressed on a base, its contact cells'
// polar and radial moments against the square's closed forms, and the twisting kernel driven
// with them: elastic M = k_s J θ (J = a⁴/6, 1%) and full slip M = μ σ_n ∫ r dA (2%).
#include "blockdem/response/face_twist.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <utility>
#include <vector>

#include "blockdem/contact/twist.hpp"
#include "support/random_shapes.hpp"

// A namespace of this file's own: the unity build (cmake/build_speed.cmake) compiles it together
// with other test files that define helpers of the same names.
namespace blockdem::test::response_face_twist {
namespace {

constexpr double kSide = 0.046;    // cube side a (m)
constexpr double kClosure = 1e-5;  // uniform closure g0 (m)
const double kJ = std::pow(kSide, 4) / 6.0;
const double kRadial = std::pow(kSide, 3) * (std::sqrt(2.0) + std::asinh(1.0)) / 6.0;

// A cube (B) on a wide base (A, top at z = 0), pressed in by kClosure, spun by `spin` about z and
// moved sideways by `offset`; the contact is the cube's whole bottom face.
struct Pressed {
  FaceContactGeometry cells;
  Eigen::Vector3d centre;
};
Pressed cube_on_base(double spin, const Eigen::Vector3d& offset) {
  const auto base = test_shapes::box({0.1, 0.1, 0.05}, Eigen::Matrix3d::Identity(), {0, 0, -0.05});
  const Eigen::Matrix3d r = Eigen::AngleAxisd(spin, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d centre = offset + Eigen::Vector3d(0, 0, kSide / 2 - kClosure);
  const auto cube = test_shapes::box(Eigen::Vector3d::Constant(kSide / 2), r, centre);
  Pressed p;
  const Eigen::Vector3d origin(offset.x(), offset.y(), -kClosure / 2);
  p.cells = face_contact_geometry(base, cube, origin, Eigen::Vector3d::UnitZ(), 1.0);
  p.centre = origin;
  return p;
}

TEST(FaceTwist, SquareContactMomentsMatchClosedForms) {
  const LinearNormal law{10e9};
  const Pressed p = cube_on_base(0.3, {0.01, -0.02, 0});
  ASSERT_TRUE(p.cells.face_type);
  const std::span<const ClosureCell> cells(p.cells.cells.data(), p.cells.cells.size());
  const FaceTwistMoments m = face_twist_moments(cells, law, p.centre);
  EXPECT_NEAR(m.compressed_area / (kSide * kSide), 1.0, 1e-12);
  EXPECT_NEAR(m.polar_moment / kJ, 1.0, 1e-10);
  EXPECT_NEAR(m.radial_moment / kRadial, 1.0, 1e-10);
  // Uniform stress k g0: ∫ σ_n r dA = k g0 ∫ r dA; the closed forms of a linear stress within
  // 1e-10 (round-off), the exponential law's chord (exact at a uniform closure) likewise.
  EXPECT_NEAR(m.radial_normal_moment / (law.stiffness * kClosure * kRadial), 1.0, 1e-10);
  const ExponentialNormal exponential = ExponentialNormal::eq3();
  EXPECT_NEAR(face_twist_moments(cells, exponential, p.centre).radial_normal_moment /
                  (normal_stress(exponential, kClosure) * kRadial),
              1.0, 1e-10);
}

// The exponential law over a partly open square (the closure rising from 0 to 5e-5 m across it,
// b Δg = 3.7; no chord), split in two cells, about a point off its centre: ∫ σ_n r dA by the
// closed radial integrals against the midpoint rule on a 1000 x 1000 grid (its error about
// 1e-6 here, from the kink of r at the point; 5e-7 measured); within 1e-5.
TEST(FaceTwist, RadialNormalMomentOfAPartlyOpenExponentialJoint) {
  const ExponentialNormal law = ExponentialNormal::eq3();
  const double slope = 5e-5 / kSide;
  std::vector<ClosureCell> cells;
  for (int half = 0; half < 2; ++half) {
    const double x0 = half * kSide / 2, x1 = x0 + kSide / 2;
    ClosureCell cell;
    for (const auto& [x, y] : {std::pair{x0, 0.0}, {x1, 0.0}, {x1, kSide}, {x0, kSide}}) {
      cell.vertices.push_back(Eigen::Vector3d(x, y, 0.0));
      cell.closures.push_back(slope * x);
    }
    cells.push_back(cell);
  }
  const Eigen::Vector3d centre(0.3 * kSide, 0.6 * kSide, 0.0);
  const int n = 1000;
  const double h = kSide / n;
  double oracle = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const Eigen::Vector3d y((i + 0.5) * h, (j + 0.5) * h, 0.0);
      oracle += normal_stress(law, slope * y.x()) * (y - centre).norm() * h * h;
    }
  }
  EXPECT_NEAR(face_twist_moments(cells, law, centre).radial_normal_moment / oracle, 1.0, 1e-5);
}

TEST(FaceTwist, CubeTwistedOnABase) {
  const LinearNormal law{10e9};
  const double ks = 1e9, mu = std::tan(40.0 * 3.14159265358979323846 / 180.0);
  const double sigma = law.stiffness * kClosure;
  const Pressed p = cube_on_base(0.0, Eigen::Vector3d::Zero());
  const std::span<const ClosureCell> cells(p.cells.cells.data(), p.cells.cells.size());
  const FaceTwistMoments m = face_twist_moments(cells, law, p.centre);
  auto twist = [&](double theta, int steps) {
    TwistState s;
    TwistResult r;
    for (int i = 0; i < steps; ++i) {
      TwistIncrement inc;
      inc.spin = theta / steps;
      inc.shear_stiffness = ks;
      inc.polar_moment = m.polar_moment;
      inc.radial_normal_moment = m.radial_normal_moment;
      inc.friction_coefficient = mu;
      r = update_twist(s, inc);
    }
    return std::pair{s.moment, r.sliding};
  };
  // Elastic: M = -k_s J θ with J = a⁴/6, within 1%.
  const auto [elastic, slid] = twist(1e-7, 10);
  EXPECT_FALSE(slid);
  EXPECT_NEAR(elastic / (-ks * kJ * 1e-7), 1.0, 1e-2);
  // Full slip: |M| = μ σ_n ∫ r dA over the square, within 2%.
  // (slip starts at θ = μ σ_n ∫ r dA / (k_s J) = 4.2e-3 rad).
  const auto [limit, sliding] = twist(1e-2, 100);
  EXPECT_TRUE(sliding);
  EXPECT_NEAR(-limit / (mu * sigma * kRadial), 1.0, 2e-2);
}

}  // namespace
}  // namespace blockdem::test::response_face_twist
