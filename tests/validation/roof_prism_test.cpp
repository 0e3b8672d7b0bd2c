// A symmetric roof prism clamped by the horizontal in-situ stress (Bray's relaxation analysis,
// Brady & Brown, Rock Mechanics for Underground Mining, the symmetric triangular roof prism): a
// prism of half-apex angle α between two fixed abutments, its joints prestressed by σ_xx = σ_h,
// loaded by its own weight. Moving down by δ, each joint opens by δ sin α and slips δ cos α, so
// N = N0 - K_n δ sin α, S = S0 + K_s δ cos α with N0 = H0 cos α, S0 = H0 sin α, and the prism
// slides when S = N tan φ, at the load
//   P = (2 H0 / D) (K_s cos²α + K_n sin²α) sin(φ - α),  D = K_s cos α cos φ + K_n sin α sin φ.
// The collapse search of the model brackets the gravity at which the prism falls out.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "stability_support.hpp"

namespace blockdem {
namespace roof_prism_test {
namespace {

constexpr double kAlpha = 20.0 * std::numbers::pi / 180.0;  // half-apex angle
constexpr double kPhi = 35.0 * std::numbers::pi / 180.0;    // joint friction
constexpr double kSigma = 1e5;                              // σ_h (Pa)
constexpr double kHeight = 1.0, kHalfBase = 0.5, kLength = 1.0, kDensity = 2600.0;

// The prism |x| <= 0.5 - z tan α, 0 <= z <= 1, 0 <= y <= 1, between fixed abutments out to
// |x| = 1.5; joint k_n = 1e10 Pa/m and k_s = k_n / ratio.
std::string prism(double ratio) {
  const double top = kHalfBase - kHeight * std::tan(kAlpha);
  std::ostringstream s;
  s.precision(17);
  const auto prism_block = [&](const std::string& name, double sign, bool abutment) {
    // The corners in x-z of the trapezoid, extruded along y.
    const double xs[4] = {abutment ? sign * kHalfBase : -kHalfBase,
                          abutment ? sign * 1.5 : kHalfBase, abutment ? sign * 1.5 : top,
                          abutment ? sign * top : -top};
    const double zs[4] = {0.0, 0.0, kHeight, kHeight};
    s << "[[blocks]]\nname = \"" << name << "\"\ndensity = " << kDensity
      << "\nshape = \"vertices\"\nvertices = [";
    for (double y : {0.0, kLength}) {
      for (int k = 0; k < 4; ++k) s << "[" << xs[k] << ", " << y << ", " << zs[k] << "], ";
    }
    s << "]\n" << (abutment ? "motion = \"fixed\"\n" : "");
  };
  s << "[settings]\ndamping = 0.7\ncontact_mode = \"face_integrated\"\n"
    << "[[joint_laws]]\nname = \"joint\"\nnormal = { law = \"linear\", stiffness = 1e10 }\n"
    << "shear = { law = \"linear\", stiffness = " << 1e10 / ratio << ", friction_deg = 35 }\n";
  prism_block("prism", 1.0, false);
  prism_block("east", 1.0, true);
  prism_block("west", -1.0, true);
  s << "[in_situ]\nstress = { xx = " << kSigma << " }\n"
    << "[[stages]]\nname = \"clamped\"\nkind = \"steps\"\nsteps = 10\n"
    << "[[stages]]\nname = \"load\"\ngravity = [0, 0, -98.1]\nramp_steps = 4000\n"
    << "find_collapse = true\ncollapse_tolerance = 0.005\nmax_steps = 200000\n";
  return s.str();
}

// The closed form of the collapse load, as a multiple of the prism's weight at 1 g.
double collapse_g(double ratio) {
  const double ks = 1.0, kn = ratio;  // only the ratio matters
  const double h0 = kSigma * kHeight * kLength;
  const double d = ks * std::cos(kAlpha) * std::cos(kPhi) + kn * std::sin(kAlpha) * std::sin(kPhi);
  const double p =
      2.0 * h0 / d *
      (ks * std::cos(kAlpha) * std::cos(kAlpha) + kn * std::sin(kAlpha) * std::sin(kAlpha)) *
      std::sin(kPhi - kAlpha);
  const double top = kHalfBase - kHeight * std::tan(kAlpha);
  const double weight = kDensity * 9.81 * kLength * kHeight * (kHalfBase + top);
  return p / weight;
}

TEST(RoofPrism, CollapseLoadMatchesBraysRelaxationAnalysis) {
  for (const double ratio : {0.25, 1.0, 4.0}) {
    SCOPED_TRACE("k_n / k_s = " + std::to_string(ratio));
    const RunResult r = test::run_text(prism(ratio), "roof_prism");
    ASSERT_EQ(r.status, RunStatus::collapsed) << r.message;
    ASSERT_TRUE(r.collapse.has_value());
    const auto [lo, hi] = *r.collapse;
    const double expected = collapse_g(ratio);
    EXPECT_NEAR(0.5 * (lo + hi), expected, 0.01 * expected) << "[" << lo << ", " << hi << "]";
  }
}

}  // namespace
}  // namespace roof_prism_test
}  // namespace blockdem
