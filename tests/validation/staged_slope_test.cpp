// A cohesive rock slope by the staged workflow (scenarios/examples/slope_staged.toml): gravity
// with elastic joints, the joints' strength given, the slope cut with relaxation, then strength
// reduction. Reference: Hoek & Bray's planar failure with a dry tension crack (Rock Slope
// Engineering, 3rd ed., ch. 7): F = (c A + W cos(psi) tan(phi)) / (W sin(psi)), with W and A
// from the example's geometry, computed here independently of the rock slicing. Tolerance 3% (the
// bisection's bracket is 0.01 in F); measured within 0.1% in both contact modes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "blockdem/numerics/units.hpp"
#include "blockdem/scenario/scenario.hpp"
#include "stability_support.hpp"

namespace blockdem {
namespace staged_slope_test {
namespace {

// The example's geometry: crest line x = 20, z = 40; face dipping 60 degrees east; bedding
// dipping 35 degrees east, daylighting in the face at z = 15; tension crack x = 14; slice 4 m.
double hoek_bray_factor() {
  const double psi = deg_to_rad(35.0), phi = deg_to_rad(35.0), face = deg_to_rad(60.0);
  const double height = 25.0;  // crest above the daylight point (m)
  const double x_daylight = 20.0 + height / std::tan(face);
  const double z_crack_base = 15.0 + (x_daylight - 14.0) * std::tan(psi);
  const double crack_depth = 40.0 - z_crack_base;
  // Hoek & Bray's weight per unit width for a crack in the upper slope surface.
  const double area_section =
      0.5 * height * height *
      ((1.0 - std::pow(crack_depth / height, 2)) / std::tan(psi) - 1.0 / std::tan(face));
  const double width = 4.0, density = 2600.0, g = 9.81, cohesion = 5e4;
  const double weight = density * g * area_section * width;
  const double plane_area = (height - crack_depth) / std::sin(psi) * width;
  return (cohesion * plane_area + weight * std::cos(psi) * std::tan(phi)) /
         (weight * std::sin(psi));
}

class StagedSlope : public ::testing::TestWithParam<ContactMode> {};

TEST_P(StagedSlope, FactorOfSafetyMatchesHoekBrayWithCohesion) {
  const double expected = hoek_bray_factor();
  ASSERT_NEAR(expected, 1.4627, 1e-4);
  Scenario sc =
      load_scenario(std::string(BLOCKDEM_SOURCE_DIR) + "/scenarios/examples/slope_staged.toml");
  sc.settings.contact_mode = GetParam();
  ASSERT_EQ(sc.stages.size(), 4u);
  ASSERT_EQ(sc.stages.back().kind, Stage::Kind::strength_reduction);
  // Bounds nearer the answer than the example's [0.5, 3.0], for fewer trials; the search still
  // checks that the lower one holds and the upper one fails.
  sc.stages.back().strength.lower = 1.3;
  sc.stages.back().strength.upper = 1.6;
  const std::string name =
      std::string("staged_slope_") + (GetParam() == ContactMode::boon2012 ? "boon2012" : "face");
  const auto out = test::run_folder(name);
  std::filesystem::remove_all(out);
  const RunResult r = run_scenario(sc, out);
  ASSERT_EQ(r.status, RunStatus::completed) << r.message;
  ASSERT_TRUE(r.factor_of_safety.has_value());
  // The bond under the sliding block survived gravity and the cut: no bond broke before the
  // strength reduction (cut at once, it breaks in the rebound and the block slides out).
  const auto& stages = r.summary["stages"];
  ASSERT_EQ(stages.size(), 4u);
  EXPECT_EQ(stages[2]["broken_bonds"].get<std::int64_t>(), 0);
  EXPECT_TRUE(stages[2]["in_equilibrium"].get<bool>());
  const auto& fos = r.summary["factor_of_safety"];
  const double f = *r.factor_of_safety;
  std::printf("staged slope (%s): F = %.4f (stable at %.4f, failed at %.4f), Hoek & Bray %.4f\n",
              name.c_str(), f, fos["last_stable"].get<double>(), fos["first_failed"].get<double>(),
              expected);
  EXPECT_NEAR(f, expected, 0.03 * expected);
  // Without the cohesion the answer would be tan(phi) / tan(psi) = 1: the bond carries the rest.
  EXPECT_GT(fos["last_stable"].get<double>(), 1.3);
}

INSTANTIATE_TEST_SUITE_P(BothModes, StagedSlope,
                         ::testing::Values(ContactMode::face_integrated, ContactMode::boon2012),
                         [](const ::testing::TestParamInfo<ContactMode>& p) {
                           return p.param == ContactMode::boon2012 ? std::string("boon2012")
                                                                   : std::string("face_integrated");
                         });

}  // namespace
}  // namespace staged_slope_test
}  // namespace blockdem
