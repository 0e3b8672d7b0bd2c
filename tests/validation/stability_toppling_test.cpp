// Toppling against sliding of a block on an incline (Hoek & Bray, Rock Slope Engineering, 3rd
// ed., the sliding/toppling chart of the toppling chapter, after Ashby 1971): a block of base b
// (along the dip) and height h on a plane dipping psi with friction phi is stable when psi < phi
// and b/h > tan(psi), slides when psi > phi and b/h > tan(psi), topples when psi < phi and b/h <
// tan(psi), and slides and topples when both are exceeded. Five (b/h, psi, phi) points, one or more
// per region, must fall in their region: failed or not (the run's status) and how (rotation above
// 0.05 rad is toppling). For the stable point strength reduction gives the sliding factor
// tan(phi)/tan(psi) within 2%.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "blockdem/numerics/units.hpp"
#include "blockdem/world/stability.hpp"
#include "stability_support.hpp"

namespace blockdem {
namespace {

enum class Region { stable, sliding, toppling, sliding_and_toppling };

struct ChartPoint {
  double b_over_h;
  double psi_deg;
  double phi_deg;
  Region region;
};

class ToppleOrSlide : public ::testing::TestWithParam<ChartPoint> {};

TEST_P(ToppleOrSlide, ModeMatchesTheChart) {
  const ChartPoint p = GetParam();
  // The chart's region from the two inequalities.
  const bool slides = p.psi_deg > p.phi_deg;
  const bool topples = p.b_over_h < std::tan(deg_to_rad(p.psi_deg));
  const Region chart = slides ? (topples ? Region::sliding_and_toppling : Region::sliding)
                              : (topples ? Region::toppling : Region::stable);
  ASSERT_EQ(chart, p.region) << "the test point is not in the region it claims";

  const double h = 0.1;
  Scenario sc = parse_scenario(test::incline_scenario(p.psi_deg, p.phi_deg, p.b_over_h * h, h, ""),
                               "chart.toml");
  World w = build_world(sc);
  ASSERT_EQ(sc.stages.size(), 2u);
  ASSERT_TRUE(run_stage(w, sc.stages[0]).converged);
  Stage tilt = sc.stages[1];
  tilt.stop_on_mechanism = true;
  std::optional<MotionMonitor> monitor;
  const StageResult r = run_stage(w, tilt, {}, &monitor);
  const Block& b = w.blocks()[1];
  const double rotation = b.rotation_since_start().norm();
  const double slip = b.position.x() - b.initial_position.x();
  std::printf("b/h %.2f psi %g phi %g: %s, rotation %.3f rad, slip %.4f m\n", p.b_over_h, p.psi_deg,
              p.phi_deg, r.converged ? "stable" : to_string(classify_failure(*monitor, false)),
              rotation, slip);
  if (p.region == Region::stable) {
    ASSERT_TRUE(r.converged) << r.message;
    EXPECT_LT(rotation, 1e-3);
    // Sliding controls the factor of safety: tan(phi)/tan(psi), 2%.
    const double expected = std::tan(deg_to_rad(p.phi_deg)) / std::tan(deg_to_rad(p.psi_deg));
    Stage trial = tilt;
    trial.ramp_steps = 0;
    const StabilitySearch sr =
        strength_reduction(w, trial, {0}, 0.5 * expected, 2.0 * expected, 0.01, {});
    const double F = 0.5 * (sr.last_stable + sr.first_failed);
    EXPECT_NEAR(F, expected, 0.02 * expected);
    return;
  }
  ASSERT_FALSE(r.converged) << "must fail";
  EXPECT_EQ(classify_failure(*monitor, false), FailureKind::collapsed);
  if (p.region == Region::sliding) {
    EXPECT_LT(rotation, 0.05) << "slides without toppling";
    EXPECT_GT(slip, 0.0);
  } else {
    EXPECT_GT(rotation, 0.05) << "topples";
  }
}

INSTANTIATE_TEST_SUITE_P(HoekBray, ToppleOrSlide,
                         ::testing::Values(ChartPoint{1.0, 20, 35, Region::stable},
                                           ChartPoint{1.0, 30, 20, Region::sliding},
                                           ChartPoint{0.4, 30, 40, Region::toppling},
                                           ChartPoint{0.4, 35, 25, Region::sliding_and_toppling},
                                           ChartPoint{0.6, 25, 40, Region::stable}),
                         [](const ::testing::TestParamInfo<ChartPoint>& p) {
                           return "point" + std::to_string(p.index);
                         });

// Strength reduction on a block that topples whatever its friction (the chart's toppling region:
// b/h = 0.4 < tan 30 = 0.577 with phi = 40 > psi = 30): F = 0.5 (friction tan 40 x 2, 59 degrees)
// fails as F = 2 does, so the bounds cannot bracket a factor of safety. With a lower bound <= 1
// the error says that the model is unstable with its full strength, not that the lower bound
// should be lowered, which cannot help.
TEST(ToppleOrSlide, StrengthReductionOfAToppleSaysUnstableWithFullStrength) {
  const double h = 0.1;
  Scenario sc = parse_scenario(test::incline_scenario(30, 40, 0.4 * h, h, ""), "topple.toml");
  World w = build_world(sc);
  ASSERT_TRUE(run_stage(w, sc.stages[0]).converged);
  std::string message;
  try {
    strength_reduction(w, sc.stages[1], {0}, 0.5, 2.0, 0.01, {});
  } catch (const std::invalid_argument& e) {
    message = e.what();
  }
  std::printf("%s\n", message.c_str());
  EXPECT_NE(message.find("F = 0.5 was collapsed"), std::string::npos) << message;
  EXPECT_NE(message.find("unstable with its full strength"), std::string::npos) << message;
  EXPECT_NE(message.find("no strength reduction can help"), std::string::npos) << message;
  EXPECT_EQ(message.find("lower the lower bound"), std::string::npos) << message;
}

}  // namespace
}  // namespace blockdem
