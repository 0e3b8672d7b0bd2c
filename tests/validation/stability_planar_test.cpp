// Strength reduction against Hoek & Bray's planar sliding (Rock Slope Engineering, 3rd ed.,
// ch. 7): a block on a plane dipping psi with friction phi and no cohesion has
// F = W cos(psi) tan(phi) / (W sin(psi)) = tan(phi) / tan(psi), and with cohesion c on the contact
// area A, F = (c A + W cos(psi) tan(phi)) / (W sin(psi)). The incline is modelled by tilting
// gravity over a flat base. Tolerance 2% (the bisection's bracket is 0.01 in F).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include "blockdem/numerics/units.hpp"
#include "stability_support.hpp"
#include "support/sanitized_run.hpp"

namespace blockdem {
namespace {

const char* kStrengthReduction =
    "[[stages]]\nname = \"srm\"\nkind = \"strength_reduction\"\nfactor_bounds = [0.8, 3.0]\n"
    "tolerance = 0.01\nmax_steps = 60000\n";

struct PlanarCase {
  double psi_deg;
  double phi_deg;
};

class PlanarSliding : public ::testing::TestWithParam<PlanarCase> {};

TEST_P(PlanarSliding, FactorOfSafetyIsTanPhiOverTanPsi) {
  const PlanarCase c = GetParam();
  const std::string name = "stab_planar_" + std::to_string(static_cast<int>(c.psi_deg));
  const RunResult r = test::run_text(
      test::incline_scenario(c.psi_deg, c.phi_deg, 0.1, 0.02, kStrengthReduction), name);
  ASSERT_EQ(r.status, RunStatus::completed) << r.message;
  ASSERT_TRUE(r.factor_of_safety.has_value());
  const double expected = std::tan(deg_to_rad(c.phi_deg)) / std::tan(deg_to_rad(c.psi_deg));
  EXPECT_NEAR(*r.factor_of_safety, expected, 0.02 * expected);
  const auto& fos = r.summary["factor_of_safety"];
  EXPECT_LE(fos["last_stable"].get<double>(), expected * 1.005);
  EXPECT_GE(fos["first_failed"].get<double>(), expected * 0.995);
  EXPECT_LE(fos["first_failed"].get<double>() - fos["last_stable"].get<double>(), 0.01 + 1e-12);
  // One CSV row per trial, and the mechanism written.
  const auto out = test::run_folder(name);
  std::ifstream csv(out / "strength_reduction.csv");
  int rows = -1;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, static_cast<int>(fos["trials"].size()));
  EXPECT_TRUE(std::filesystem::exists(out / "mechanism.csv"));
  EXPECT_TRUE(std::filesystem::exists(out / "vtk" / "mechanism.vtk"));
  std::printf("psi %.0f phi %.0f: F = %.4f (closed form %.4f), %zu trials\n", c.psi_deg, c.phi_deg,
              *r.factor_of_safety, expected, fos["trials"].size());
}

INSTANTIATE_TEST_SUITE_P(HoekBray, PlanarSliding,
                         ::testing::Values(PlanarCase{30, 40}, PlanarCase{25, 35}),
                         [](const ::testing::TestParamInfo<PlanarCase>& p) {
                           return "psi" + std::to_string(static_cast<int>(p.param.psi_deg)) +
                                  "_phi" + std::to_string(static_cast<int>(p.param.phi_deg));
                         });

// Where the trials start: from the state before the stage, or from the last stable trial's
// equilibrium (trial_start = "last_stable"). A block on one plane does not slip below the limit,
// so both brackets contain Hoek & Bray's tan 40 / tan 30 = 1.4532 (to the bracket's 0.01 and the
// 0.5% of PlanarSliding), the later ones' trials start settled, and the search takes no more
// steps (on one block the stage's start is settled too: a stable trial may meet the criterion at
// its first check from either start, and the failed trials take as long from either).
TEST(StrengthReductionTrialStart, BothStartsBracketHoekAndBray) {
  if (test::sanitized_run()) GTEST_SKIP() << "two strength reductions: physics, not memory";
  const double expected = std::tan(deg_to_rad(40.0)) / std::tan(deg_to_rad(30.0));
  std::int64_t steps[2] = {0, 0};
  int k = 0;
  for (const std::string start : {"stage_start", "last_stable"}) {
    const RunResult r =
        test::run_text(test::incline_scenario(
                           30, 40, 0.1, 0.02,
                           std::string(kStrengthReduction) + "trial_start = \"" + start + "\"\n"),
                       "stab_trial_start_" + start);
    ASSERT_EQ(r.status, RunStatus::completed) << r.message;
    const auto& fos = r.summary["factor_of_safety"];
    EXPECT_LE(fos["last_stable"].get<double>(), expected * 1.005) << start;
    EXPECT_GE(fos["first_failed"].get<double>(), expected * 0.995) << start;
    EXPECT_LE(fos["first_failed"].get<double>() - fos["last_stable"].get<double>(), 0.01 + 1e-12);
    steps[k++] = r.steps_per_stage.back();
  }
  EXPECT_LE(steps[1], steps[0]);
  std::printf("search steps: stage_start %lld, last_stable %lld\n",
              static_cast<long long>(steps[0]), static_cast<long long>(steps[1]));
}

// How the trials are placed: at the midpoints (factor_search = "bisect") or by the critical
// factor extrapolated from the failed trials' accelerations (the default). A block sliding on one
// plane is a rigid mechanism, a = c (W sin(psi) - W cos(psi) tan(phi) / F), so the extrapolation
// is Hoek & Bray's tan(phi)/tan(psi) but for the trials' elastic start (to 0.5%); both brackets
// contain it (to the 0.5% of PlanarSliding), each contains the other's answer to within the
// tolerance, and the extrapolated search takes fewer steps. With cohesion the joint can break
// (its failed trials slide on the residual strength, whose factor is tan(phi)/tan(psi) = 0.82
// here, not the peak's 1.54), so the search bisects whatever factor_search says: the same trials.
TEST(StrengthReductionSearch, ExtrapolationFindsHoekAndBrayInFewerStepsThanBisection) {
  if (test::sanitized_run()) GTEST_SKIP() << "four strength reductions: physics, not memory";
  struct Case {
    double psi, phi, cohesion;
  };
  for (const Case c : {Case{30.0, 40.0, 0.0}, Case{35.0, 30.0, 200.0}}) {
    const bool breaks = c.cohesion > 0.0;
    const double psi = deg_to_rad(c.psi), phi = deg_to_rad(c.phi);
    const double weight = 2500.0 * 9.81 * 0.1 * 0.1 * 0.02;
    const double expected = (c.cohesion * 0.1 * 0.1 + weight * std::cos(psi) * std::tan(phi)) /
                            (weight * std::sin(psi));
    std::int64_t steps[2] = {0, 0};
    double lo[2] = {0, 0}, hi[2] = {0, 0};
    int k = 0;
    for (const std::string search : {"bisect", "extrapolate"}) {
      const std::string label = search + " psi " + std::to_string(static_cast<int>(c.psi));
      const RunResult r =
          test::run_text(test::incline_scenario(c.psi, c.phi, 0.1, 0.02,
                                                std::string(kStrengthReduction) +
                                                    "factor_search = \"" + search + "\"\n",
                                                0.0, c.cohesion),
                         "stab_search_" + search + std::to_string(static_cast<int>(c.psi)));
      ASSERT_EQ(r.status, RunStatus::completed) << r.message;
      const auto& fos = r.summary["factor_of_safety"];
      EXPECT_EQ(fos["search"], breaks ? "bisect" : search);
      lo[k] = fos["last_stable"].get<double>();
      hi[k] = fos["first_failed"].get<double>();
      EXPECT_LE(lo[k], expected * 1.005) << label;
      EXPECT_GE(hi[k], expected * 0.995) << label;
      EXPECT_LE(hi[k] - lo[k], 0.01 + 1e-12) << label;
      int placed = 0;
      for (const auto& t : fos["trials"]) placed += t["placed_by"].is_number() ? 1 : 0;
      if (search == "extrapolate" && !breaks) {
        EXPECT_GE(placed, 1) << label;
        ASSERT_TRUE(fos["extrapolated"].is_number()) << label;
        const double fc = fos["extrapolated"].get<double>();
        EXPECT_NEAR(fc, expected, 0.005 * expected) << label;
        std::printf("psi %.0f phi %.0f c %.0f Pa: extrapolated F_c = %.5f (closed form %.5f)\n",
                    c.psi, c.phi, c.cohesion, fc, expected);
      } else {
        EXPECT_EQ(placed, 0) << label;
        EXPECT_TRUE(fos["extrapolated"].is_null()) << label;
      }
      steps[k++] = r.steps_per_stage.back();
    }
    // Each answer (the bracket's midpoint) lies in the other's bracket, widened by the tolerance.
    EXPECT_GE(0.5 * (lo[0] + hi[0]), lo[1] - 0.01);
    EXPECT_LE(0.5 * (lo[0] + hi[0]), hi[1] + 0.01);
    if (breaks) {
      EXPECT_EQ(steps[1], steps[0]);
      EXPECT_EQ(lo[1], lo[0]);
      EXPECT_EQ(hi[1], hi[0]);
    } else {
      EXPECT_LT(steps[1], steps[0]);
    }
    std::printf("  bisect [%.5f, %.5f] in %lld steps, extrapolate [%.5f, %.5f] in %lld steps\n",
                lo[0], hi[0], static_cast<long long>(steps[0]), lo[1], hi[1],
                static_cast<long long>(steps[1]));
  }
}

// With cohesion: psi = 35 degrees is steeper than phi = 30 degrees, so the block stands only by
// its cohesion; strength reduction divides c and tan(phi) together.
TEST(PlanarSlidingWithCohesion, FactorOfSafetyMatchesHoekBray) {
  const double psi = deg_to_rad(35.0), phi = deg_to_rad(30.0);
  const double b = 0.1, width = 0.1, h = 0.02, density = 2500.0, cohesion = 200.0;
  const double weight = density * 9.81 * b * width * h;  // (N)
  const double area = b * width;                         // (m^2)
  const double expected =
      (cohesion * area + weight * std::cos(psi) * std::tan(phi)) / (weight * std::sin(psi));
  const RunResult r =
      test::run_text(test::incline_scenario(35.0, 30.0, b, h, kStrengthReduction, 0.0, cohesion),
                     "stab_planar_cohesion");
  ASSERT_EQ(r.status, RunStatus::completed) << r.message;
  ASSERT_TRUE(r.factor_of_safety.has_value());
  EXPECT_NEAR(*r.factor_of_safety, expected, 0.02 * expected);
  std::printf("psi 35 phi 30 c %.0f Pa: F = %.4f (closed form %.4f)\n", cohesion,
              *r.factor_of_safety, expected);
}

// A block on an incline steeper than its friction angle in an equilibrium stage: it slides and
// keeps accelerating (a = g (sin psi - cos psi tan phi) (1 - damping) > 0), a mechanism beyond
// doubt. The stage ends as collapsed soon after the block passes the displacement limit, not at
// max_steps.
TEST(CertainMechanism, EndsTheStageOnceTheLimitIsPassed) {
  const char* equilibrium =
      "[[stages]]\nname = \"hold\"\nkind = \"equilibrium\"\nmax_steps = 500000\n";
  const RunResult r =
      test::run_text(test::incline_scenario(40.0, 30.0, 0.1, 0.02, equilibrium), "certain_slide");
  EXPECT_EQ(r.status, RunStatus::collapsed) << r.message;
  const auto& stage = r.summary["stages"].back();
  EXPECT_LT(stage["steps"].get<std::int64_t>(), 100000) << r.message;
  EXPECT_NE(r.message.find("kept accelerating"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("physical collapse"), std::string::npos) << r.message;
}

}  // namespace
}  // namespace blockdem
