// The virtual laboratory's kernel paths against closed forms: the compression path of the linear
// and exponential normal laws (eqs 1, 3, 4), direct shear with the Mohr-Coulomb, degrading (eq 5)
// and continuously-yielding (eq 8) laws of Boon, Houlsby & Utili (2015); the law-spec parser; the
// joint-law figure data.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "blockdem/lab/compression_test.hpp"
#include "blockdem/lab/joint_law_figures.hpp"
#include "blockdem/lab/law_spec.hpp"
#include "blockdem/lab/shear_test.hpp"
#include "support/temp_path.hpp"

namespace blockdem {
namespace {

const double kTan40 = std::tan(40.0 * std::numbers::pi / 180.0);

template <class Function>
std::string invalid_argument_message(Function&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// --- law specs -------------------------------------------------------------------------------

TEST(LawSpec, ParsesNamesAndNumbersIntoTheFactoriesLaws) {
  const NormalLaw eq4 = normal_law_from_spec("law=exponential,preset=eq4");
  ASSERT_TRUE(std::holds_alternative<ExponentialNormal>(eq4));
  EXPECT_EQ(std::get<ExponentialNormal>(eq4).a, 0.5405e5);
  EXPECT_EQ(std::get<ExponentialNormal>(eq4).b, 3.7e4);

  const NormalLaw lin = normal_law_from_spec(" law = linear , stiffness = 5e9 ");
  ASSERT_TRUE(std::holds_alternative<LinearNormal>(lin));
  EXPECT_EQ(std::get<LinearNormal>(lin).stiffness, 5e9);

  const ShearLaw cy = shear_law_from_spec("law=continuously_yielding,friction_deg=35");
  ASSERT_TRUE(std::holds_alternative<ContinuouslyYieldingShear>(cy));
  EXPECT_EQ(std::get<ContinuouslyYieldingShear>(cy).strength.friction_coefficient,
            std::tan(35.0 * std::numbers::pi / 180.0));
  EXPECT_EQ(std::get<ContinuouslyYieldingShear>(cy).power_laws.stiffness_exponent, 0.7);
}

TEST(LawSpec, RejectsMalformedTextWithTheOffendingItem) {
  EXPECT_NE(invalid_argument_message([] {
              parse_law_spec("normal", "stiffness=1e9");
            }).find("missing 'law=...'"),
            std::string::npos);
  EXPECT_NE(invalid_argument_message([] {
              parse_law_spec("normal", "law=linear,stiffness");
            }).find("'stiffness' is not key=value"),
            std::string::npos);
  EXPECT_NE(invalid_argument_message([] {
              parse_law_spec("normal", "law=linear,,a=1");
            }).find("empty item"),
            std::string::npos);
  EXPECT_NE(invalid_argument_message([] {
              parse_law_spec("shear", "law=linear,c=1,c=2");
            }).find("'c' given twice"),
            std::string::npos);
  EXPECT_NE(invalid_argument_message([] {
              parse_law_spec("shear", "law=linear,stiffness=1e9x");
            }).find("'stiffness' = '1e9x' is not a number"),
            std::string::npos);
  EXPECT_NE(invalid_argument_message([] {
              shear_law_from_spec("law=linear,preset=eq4");
            }).find("has no presets"),
            std::string::npos);
}

TEST(LawSpec, PhysicallyImpossibleValuesAreRejectedNamingLawAndParameter) {
  const std::string negative =
      invalid_argument_message([] { normal_law_from_spec("law=linear,stiffness=-1e9"); });
  EXPECT_NE(negative.find("law 'linear'"), std::string::npos) << negative;
  EXPECT_NE(negative.find("'stiffness'"), std::string::npos) << negative;

  const std::string not_a_number =
      invalid_argument_message([] { normal_law_from_spec("law=exponential,a=nan,b=3.7e4"); });
  EXPECT_NE(not_a_number.find("law 'exponential'"), std::string::npos) << not_a_number;
  EXPECT_NE(not_a_number.find("'a'"), std::string::npos) << not_a_number;

  for (const char* angle : {"0", "90", "-5", "120"}) {
    const std::string text = std::string("law=linear,friction_deg=") + angle;
    const std::string message = invalid_argument_message([&] { shear_law_from_spec(text); });
    EXPECT_NE(message.find("'friction_deg'"), std::string::npos) << text << ": " << message;
  }
  const std::string peak = invalid_argument_message(
      [] { shear_law_from_spec("law=continuously_yielding,peak_coefficient=0"); });
  EXPECT_NE(peak.find("law 'continuously_yielding'"), std::string::npos) << peak;
  EXPECT_NE(peak.find("'peak_coefficient'"), std::string::npos) << peak;
}

// --- compression ---------------------------------------------------------------------------

TEST(CompressionKernel, ClosureAtStressInvertsTheLawsInClosedForm) {
  // Linear: u = sigma / k. Exponential: u = ln(1 + sigma / a) / b.
  EXPECT_NEAR(closure_at_stress(LinearNormal{10e9}, 1e6), 1e-4, 1e-4 * 1e-12);
  const ExponentialNormal eq4 = ExponentialNormal::eq4();
  for (double s : {1e3, 1e5, 1e6, 5e6}) {
    const double exact = std::log1p(s / eq4.a) / eq4.b;
    EXPECT_NEAR(closure_at_stress(eq4, s), exact, 1e-12 * exact) << s;
  }
  EXPECT_THROW(closure_at_stress(eq4, 0.0), std::invalid_argument);
  EXPECT_THROW(closure_at_stress(eq4, std::nan("")), std::invalid_argument);
}

TEST(CompressionKernel, PathLoadsAndUnloadsAlongEqs3And4) {
  CompressionTestDef def;
  def.law = ExponentialNormal::eq3();
  def.max_stress = 2e6;
  def.cycles = 2;
  def.steps_per_branch = 20;
  const CompressionCurve curve = run_compression_kernel(def);
  ASSERT_EQ(curve.points.size(), 1u + 2u * 2u * 20u);
  EXPECT_NEAR(curve.max_stress, 2e6, 2e6 * 1e-12);
  const ExponentialNormal law = ExponentialNormal::eq3();
  for (const auto& p : curve.points) {
    // Eq 3 (the integral of eq 1) and its tangent stiffness k0 + c sigma (eq 1).
    EXPECT_NEAR(p.normal_stress, law.a * std::expm1(law.b * p.closure), 1e-9 * curve.max_stress);
    EXPECT_NEAR(p.tangent_stiffness, 4e9 + 7.4e4 * p.normal_stress, 1e-9 * p.tangent_stiffness);
    EXPECT_GE(p.closure, 0.0);
    EXPECT_LE(p.closure, curve.max_closure * (1 + 1e-15));
  }
  // Zero closure at the start and after each unloading branch; the maximum in the middle.
  EXPECT_EQ(curve.points.front().closure, 0.0);
  EXPECT_EQ(curve.points[20].closure, curve.max_closure);
  EXPECT_EQ(curve.points[40].closure, 0.0);
  EXPECT_EQ(curve.points[40].branch, PathBranch::unloading);
  EXPECT_EQ(curve.points[41].cycle, 2);
  EXPECT_EQ(curve.points.back().closure, 0.0);
}

TEST(CompressionKernel, ValidateNamesTheParameter) {
  CompressionTestDef both;
  both.max_closure = 1e-5;
  both.max_stress = 1e6;
  EXPECT_NE(invalid_argument_message([&] { both.validate(); }).find("exactly one of max_closure"),
            std::string::npos);
  CompressionTestDef negative;
  negative.max_stress = -1.0;
  EXPECT_NE(invalid_argument_message([&] { negative.validate(); }).find("max_stress"),
            std::string::npos);
  CompressionTestDef cycles;
  cycles.max_closure = 1e-5;
  cycles.cycles = 0;
  EXPECT_NE(invalid_argument_message([&] { cycles.validate(); }).find("cycles"), std::string::npos);
}

// --- shear ------------------------------------------------------------------------------------

TEST(ShearKernel, LinearLawFollowsKUThenSlidesAtSigmaTanPhi) {
  ShearTestDef def;
  def.law = LinearShear{1e9, JointStrength::from_friction_deg(40.0)};
  def.normal_stress = 0.5e6;
  def.max_displacement = 1e-3;
  def.steps = 500;
  const ShearCurve curve = run_shear_kernel(def);
  const double cap = 0.5e6 * kTan40;
  for (const auto& p : curve.points) {
    const double u = p.shear_displacement;
    EXPECT_NEAR(p.shear_stress, std::min(1e9 * u, cap), 1e-9 * cap) << u;
    // After yield the slip is everything the elastic spring does not take.
    EXPECT_NEAR(p.plastic_slip, std::max(0.0, u - cap / 1e9), 1e-12) << u;
    EXPECT_NEAR(p.mobilised_friction, p.shear_stress / 0.5e6, 1e-15);
  }
  EXPECT_NEAR(curve.points.back().mobilised_friction, kTan40, 1e-12);
  EXPECT_NEAR(curve.peak_shear_stress, cap, 1e-9 * cap);
}

TEST(ShearKernel, ContinuouslyYieldingFollowsTheExactMonotonicSolution) {
  // Eq 8 with plastic slip beta at constant sigma_n: |tau| = mu(beta) sigma_n and
  // u = beta + mu(beta) sigma_n / k_s,initial (docs/joint-laws.md).
  const ContinuouslyYieldingShear law;
  ShearTestDef def;
  def.law = law;
  def.normal_stress = 20e3;
  def.max_displacement = 0.2e-3;
  def.steps = 300;
  const ShearCurve curve = run_shear_kernel(def);
  const double k = law.power_laws.initial_stiffness(20e3);
  const double peak = law.power_laws.peak_displacement(20e3);
  for (const auto& p : curve.points) {
    const double mu = law.friction_coefficient(p.plastic_slip, peak);
    EXPECT_NEAR(p.mobilised_friction, mu, 1e-9) << p.shear_displacement;
    EXPECT_NEAR(p.shear_displacement, p.plastic_slip + mu * 20e3 / k, 1e-9 * def.max_displacement);
  }
  // 0.2 mm is 12 u_peak: the friction is within exp(-11) of tan 40.
  EXPECT_NEAR(curve.points.back().mobilised_friction, kTan40, 1e-4);
}

TEST(ShearKernel, DegradingStiffnessFallsLinearlyToZeroAtUPeak) {
  // Eq 5 at 20 kPa, where the peak k u_peak / 2 stays below the 40 degree cap: each increment's
  // d tau / d u equals k_s,initial (1 - u/u_peak) at its midpoint, and zero beyond u_peak.
  const DegradingShear law;
  const double sigma = 20e3;
  const double k = law.power_laws.initial_stiffness(sigma);
  const double peak = law.power_laws.peak_displacement(sigma);
  ASSERT_LT(0.5 * k * peak, sigma * kTan40);
  ShearTestDef def;
  def.law = law;
  def.normal_stress = sigma;
  def.max_displacement = 1.5 * peak;
  def.steps = 300;
  const ShearCurve curve = run_shear_kernel(def);
  for (std::size_t i = 1; i < curve.points.size(); ++i) {
    const double mid =
        0.5 * (curve.points[i - 1].shear_displacement + curve.points[i].shear_displacement);
    const double expected = mid < peak ? k * (1.0 - mid / peak) : 0.0;
    // The increment that straddles u_peak averages the two sides.
    if (std::abs(mid - peak) < def.max_displacement / def.steps) continue;
    EXPECT_NEAR(curve.points[i].step_stiffness, expected, 1e-6 * k) << mid;
  }
  EXPECT_NEAR(curve.peak_shear_stress, 0.5 * k * peak, 1e-9 * k * peak);
}

TEST(ShearKernel, CyclicPathReturnsToZeroAndReYieldsOnTheOppositeSide) {
  ShearTestDef def;
  def.law = LinearShear{1e9, JointStrength::from_friction_deg(40.0)};
  def.normal_stress = 1e5;
  def.max_displacement = 1e-3;
  def.steps = 100;
  def.cycles = 2;
  const std::vector<double> inc = shear_path_increments(def);
  ASSERT_EQ(inc.size(), 2u * 4u * 100u);
  const ShearCurve curve = run_shear_kernel(def);
  EXPECT_NEAR(curve.points[100].shear_displacement, 1e-3, 1e-15);
  EXPECT_NEAR(curve.points[300].shear_displacement, -1e-3, 1e-15);
  EXPECT_NEAR(curve.points.back().shear_displacement, 0.0, 1e-15);
  EXPECT_EQ(curve.points[400].cycle, 1);
  EXPECT_EQ(curve.points[401].cycle, 2);
  // Sliding at +cap at +max and at -cap at -max (Mohr-Coulomb, no hardening).
  EXPECT_NEAR(curve.points[100].shear_stress, 1e5 * kTan40, 1e-6);
  EXPECT_NEAR(curve.points[300].shear_stress, -1e5 * kTan40, 1e-6);
}

TEST(ShearKernel, ValidateNamesTheParameter) {
  ShearTestDef def;
  def.max_displacement = 1e-3;
  def.normal_stress = -1.0;
  EXPECT_NE(invalid_argument_message([&] { def.validate(); }).find("normal_stress"),
            std::string::npos);
  def.normal_stress = 1e4;
  def.max_displacement = std::nan("");
  EXPECT_NE(invalid_argument_message([&] { def.validate(); }).find("max_displacement"),
            std::string::npos);
}

// --- figure data ----------------------------------------------------------------------------

TEST(JointLawFigures, WritesTheFourTablesWithUnitsInTheHeaders) {
  const std::filesystem::path dir = test::temp_path("lab_figures");
  std::filesystem::create_directories(dir);
  JointLawFiguresDef def;
  def.steps = 20;
  const auto files = write_joint_law_figure_data(dir, def);
  ASSERT_EQ(files.size(), 4u);
  const char* headers[] = {
      "law,closure_m,normal_stress_Pa",
      ("normal_stress_Pa,shear_displacement_m,shear_stiffness_Pa_per_m,"
       "capped_shear_stiffness_Pa_per_m,initial_stiffness_Pa_per_m,peak_displacement_m"),
      "normal_stress_Pa,eq7_initial_stiffness_Pa_per_m,eq2_stiffness_Pa_per_m",
      "normal_stress_Pa,shear_displacement_m,shear_stress_Pa,mobilised_friction,plastic_slip_m"};
  for (std::size_t i = 0; i < files.size(); ++i) {
    std::ifstream in(files[i]);
    std::string header;
    std::getline(in, header);
    EXPECT_EQ(header, headers[i]) << files[i];
    std::size_t rows = 0;
    for (std::string line; std::getline(in, line);) ++rows;
    EXPECT_GT(rows, 20u) << files[i];
  }
}

}  // namespace
}  // namespace blockdem
