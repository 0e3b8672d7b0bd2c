// The shear response step without a World, driven along slip paths under the normal load a
// face contact's normal response gives: elastic loading with its stored energy, Coulomb's limit
// μ F_n + c A in full slip, and the stored force carried with the contact frame.
#include "blockdem/response/shear_response.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

// A namespace of this file's own: the unity build (cmake/build_speed.cmake) compiles it together
// with other test files that define helpers of the same names.
namespace blockdem::test::response_shear {
namespace {

constexpr double kSide = 0.046;  // square side a (m)
constexpr double kArea = kSide * kSide;
constexpr double kNormal = 1e10;   // k_n (Pa/m)
constexpr double kShear = 1e9;     // k_s (Pa/m), the paper's Table 2
constexpr double kClosure = 5e-5;  // uniform closure (m): σ_n = 0.5 MPa
const Eigen::Vector3d kUp = Eigen::Vector3d::UnitZ();

// The load of the square [0, a]² under the uniform closure, from the normal response step.
ContactLoad square_load() {
  FaceContactGeometry fc;
  fc.face_type = true;
  ClosureCell cell;
  for (const auto& [x, y] : {std::pair{0.0, 0.0}, {kSide, 0.0}, {kSide, kSide}, {0.0, kSide}}) {
    cell.vertices.push_back(Eigen::Vector3d(x, y, 0.0));
    cell.closures.push_back(kClosure);
  }
  fc.cells.push_back(cell);
  return normal_response(LinearNormal{kNormal}, ContactGeometry{}, fc)->load();
}

ContactMotion slip_along(const Eigen::Vector3d& du) {
  ContactMotion m;
  m.normal = kUp;
  m.slip = du;
  return m;
}

// Cohesionless joint slid along x in steps of 1e-6 m: F = -k_s A u while |F| < μ F_n, the stored
// energy F² / (2 k_s A), then full slip at exactly |F| = μ F_n (Coulomb's law). References:
// the linear shear law with a Mohr-Coulomb cap (Boon et al. 2015, Table 2); 1e-12 relative.
TEST(ShearResponse, ElasticThenCoulombSlipUnderTheFaceLoad) {
  const ContactLoad load = square_load();
  ASSERT_NEAR(load.force, kNormal * kClosure * kArea, 1e-12 * load.force);
  const LinearShear law{kShear, JointStrength::from_friction_deg(30.0)};
  const double mu = std::tan(30.0 * std::numbers::pi / 180.0);
  const double spring = kShear * kArea, limit = mu * load.force;
  ShearState state;
  double u = 0.0;
  bool slid = false;
  for (int i = 0; i < 400; ++i) {
    const ShearResult r = shear_response(state, law, load, slip_along({1e-6, 0.0, 0.0}));
    u += 1e-6;
    EXPECT_NEAR(r.stiffness, spring, 1e-12 * spring);
    if (spring * u < limit * (1 - 1e-12)) {
      EXPECT_FALSE(r.sliding);
      EXPECT_NEAR(state.force.x(), -spring * u, 1e-12 * spring * u);
      const double energy = state.force.squaredNorm() / (2 * spring);
      EXPECT_NEAR(state.elastic_energy, energy, 1e-12 * energy);
    } else if (spring * u > limit * (1 + 1e-12)) {
      slid = true;
      EXPECT_TRUE(r.sliding);
      EXPECT_NEAR(state.force.norm(), limit, 1e-12 * limit);
      EXPECT_LT(state.force.x(), 0.0);
    }
  }
  EXPECT_TRUE(slid);
}

// A bonded joint (cohesion c): the largest force it carries is μ F_n + c A (Coulomb with
// cohesion), reached to within one step's increment k_s A du; the step beyond breaks the bond
// and the force drops to the residual μ F_n. 1e-12 relative for the residual.
TEST(ShearResponse, CohesionRaisesThePeakToMuFnPlusCA) {
  const ContactLoad load = square_load();
  JointStrength strength = JointStrength::from_friction_deg(30.0);
  strength.cohesion = 0.2e6;  // Pa
  const LinearShear law{kShear, strength};
  const double mu = strength.friction_coefficient;
  const double du = 1e-6, spring = kShear * kArea;
  const double peak = mu * load.force + strength.cohesion * kArea;
  ShearState state;
  double largest = 0.0;
  bool broke = false;
  for (int i = 0; i < 2000 && !broke; ++i) {
    const ShearResult r = shear_response(state, law, load, slip_along({du, 0.0, 0.0}));
    broke = r.broke;
    if (!broke) largest = std::max(largest, state.force.norm());
  }
  ASSERT_TRUE(broke);
  EXPECT_LE(largest, peak * (1 + 1e-12));
  EXPECT_GE(largest, peak - spring * du);
  EXPECT_NEAR(state.force.norm(), mu * load.force, 1e-12 * mu * load.force);
}

// The stored state carried into the next frame: a tilt of the normal keeps |F| and puts F in the
// new tangent plane; a spin θ about n turns F by θ. Reference: a rigid rotation; 1e-12.
TEST(ShearResponse, TheStoredForceTurnsWithTheContactFrame) {
  ShearState state;
  state.force = Eigen::Vector3d(100.0, 0.0, 0.0);
  state.elastic_displacement = Eigen::Vector3d(1e-7, 0.0, 0.0);
  const double tilt = 1e-3, theta = 0.25;
  const Eigen::Vector3d tilted(std::sin(tilt), 0.0, std::cos(tilt));
  carry_shear_state(state, kUp, tilted, theta);
  EXPECT_NEAR(state.force.norm(), 100.0, 1e-12 * 100.0);
  EXPECT_NEAR(state.force.dot(tilted), 0.0, 1e-12 * 100.0);
  // The tilt about y takes x to (cos, 0, -sin); the spin then turns it by θ about the new normal.
  const Eigen::Vector3d x_turned(std::cos(tilt), 0.0, -std::sin(tilt));
  EXPECT_NEAR(state.force.dot(x_turned), 100.0 * std::cos(theta), 1e-12 * 100.0);
  EXPECT_NEAR(state.force.dot(tilted.cross(x_turned)), 100.0 * std::sin(theta), 1e-12 * 100.0);
  EXPECT_NEAR(state.elastic_displacement.norm(), 1e-7, 1e-12 * 1e-7);
}

// The frame's spin is the blocks' mean spin about n, ((ω_A + ω_B)/2 · n) dt; the slip is the
// relative velocity's tangential part times dt; the couple moving F from x_f to x_s is
// ((x_s - x_f) × F) · n. Exact values (round-off only).
TEST(ShearResponse, FrameSpinSlipAndCoupleClosedForms) {
  EXPECT_DOUBLE_EQ(frame_spin({0.0, 0.0, 2.0}, {1.0, 0.0, 4.0}, kUp, 0.5), 1.5);
  const Eigen::Vector3d slip = tangential_slip({1.0, -2.0, 7.0}, kUp, 1e-3);
  EXPECT_DOUBLE_EQ(slip.x(), 1e-3);
  EXPECT_DOUBLE_EQ(slip.y(), -2e-3);
  EXPECT_EQ(slip.z(), 0.0);
  EXPECT_DOUBLE_EQ(shear_couple({0.01, 0.0, 0.0}, Eigen::Vector3d::Zero(), {0.0, 50.0, 0.0}, kUp),
                   0.5);
}

}  // namespace
}  // namespace blockdem::test::response_shear
