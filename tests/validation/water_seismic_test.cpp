// Water in the joints and a pseudo-static earthquake against the closed form of plane failure
// with a tension crack (Hoek & Bray, Rock Slope Engineering, 3rd ed., 1981, ch. 7; Wyllie & Mah,
// 4th ed., 2004, ch. 6). A slope of height H and face angle ψ_f stands on a plane dipping ψ_p; a
// vertical tension crack of depth z behind the crest holds water to a depth z_w, and the water
// seeps along the sliding plane to the toe, its pressure falling linearly from γ_w z_w at the
// crack's foot to zero there. Per metre of slope (block width b = 1 m):
//   W = ½ γ_r H² [(1 − (z/H)²) cot ψ_p − cot ψ_f]   the block's weight,
//   A = (H − z) / sin ψ_p                            the sliding plane's area,
//   U = ½ γ_w z_w A                                  the water force on the sliding plane,
//   V = ½ γ_w z_w²                                   the water force in the crack (horizontal),
// and with a horizontal seismic force α W out of the slope, resolving normal and parallel to the
// plane (a rigid block, Mohr-Coulomb on the plane, no resistance in the crack):
//   F = [c A + (W (cos ψ_p − α sin ψ_p) − U − V sin ψ_p) tan φ] / [W (sin ψ_p + α cos ψ_p) + V cos
//   ψ_p].
// The model makes the same water pressure from a plane water table through the toe and the
// water level in the crack (p = γ_w (z_w(x) − z) is then linear along the sliding plane and
// hydrostatic in the crack). Tolerance: 2% on F (the bisection's bracket is 0.01); the critical
// seismic coefficient k_c (F = 1) within 0.01 of the closed form (bracket 0.005).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "blockdem/numerics/units.hpp"
#include "blockdem/scenario/scenario.hpp"
#include "blockdem/world/stage.hpp"
#include "stability_support.hpp"
#include "support/sanitized_run.hpp"

namespace blockdem::test::water_seismic {
namespace {

constexpr double kG = 9.81;
constexpr double kRock = 2600.0, kWater = 1000.0;
constexpr double kHeight = 30.0, kFaceDeg = 60.0, kPlaneDeg = 30.0, kCrack = 10.0;

struct Slope {
  double friction_deg = 35.0;
  double cohesion = 50e3;    ///< (Pa)
  double water_depth = 0.0;  ///< z_w in the crack (m)
  double seismic = 0.0;      ///< α = k_h
};

// Hoek & Bray's forces per metre of slope: W, A, U, V (N/m, m²/m), and sin, cos ψ_p, tan φ.
struct Forces {
  double w, area, u, v, sp, cp, tf;
};

Forces forces(const Slope& s) {
  const double pp = deg_to_rad(kPlaneDeg), pf = deg_to_rad(kFaceDeg);
  const double zr = kCrack / kHeight;
  Forces f{};
  f.w =
      0.5 * kRock * kG * kHeight * kHeight * ((1.0 - zr * zr) / std::tan(pp) - 1.0 / std::tan(pf));
  f.area = (kHeight - kCrack) / std::sin(pp);
  f.u = 0.5 * kWater * kG * s.water_depth * f.area;
  f.v = 0.5 * kWater * kG * s.water_depth * s.water_depth;
  f.sp = std::sin(pp);
  f.cp = std::cos(pp);
  f.tf = std::tan(deg_to_rad(s.friction_deg));
  return f;
}

// Hoek & Bray's factor of safety.
double closed_form(const Slope& s) {
  const Forces f = forces(s);
  const double a = s.seismic;
  return (s.cohesion * f.area + (f.w * (f.cp - a * f.sp) - f.u - f.v * f.sp) * f.tf) /
         (f.w * (f.sp + a * f.cp) + f.v * f.cp);
}

// The k_h at which F = 1: N(α) = D(α) is linear in α,
//   α = [c A + (W cos ψ_p − U − V sin ψ_p) tan φ − W sin ψ_p − V cos ψ_p]
//       / [W (cos ψ_p + sin ψ_p tan φ)].
double critical_coefficient(const Slope& s) {
  const Forces f = forces(s);
  return (s.cohesion * f.area + (f.w * f.cp - f.u - f.v * f.sp) * f.tf - f.w * f.sp - f.v * f.cp) /
         (f.w * (f.cp + f.sp * f.tf));
}

// A stage's water table through the toe and the water level z_w in the crack (a plane
// containing y), and the water's density.
std::string water_keys(double water_depth) {
  const double tp = std::tan(deg_to_rad(kPlaneDeg));
  const double xk = (kHeight - kCrack) / tp, zb = kHeight - kCrack;
  std::ostringstream t;
  t.precision(15);
  t << "water_table = { point = [0.0, 0.0, 0.0], normal = [" << -(zb + water_depth) / xk
    << ", 0.0, 1.0] }\nwater_density = " << kWater << "\n";
  return t.str();
}

// The slope as a scenario: the sliding block (toe at the origin, the slope face dipping west,
// x east), a fixed base whose top is the sliding plane, the water table and `stages`.
std::string slope_scenario(const Slope& s, const std::string& mode, const std::string& stages) {
  const double tp = std::tan(deg_to_rad(kPlaneDeg)), tf = std::tan(deg_to_rad(kFaceDeg));
  const double xc = kHeight / tf;             // the crest
  const double xk = (kHeight - kCrack) / tp;  // the crack
  const double zb = kHeight - kCrack;         // the crack's foot
  std::ostringstream t;
  t.precision(15);
  const auto prism = [&t](const std::vector<std::array<double, 2>>& xz) {
    t << "vertices = [";
    for (const double y : {0.0, 1.0}) {
      for (const auto& p : xz) t << "[" << p[0] << ", " << y << ", " << p[1] << "], ";
    }
    t << "]\n";
  };
  t << "[settings]\ndamping = 0.7\ncontact_mode = \"" << mode << "\"\n";
  t << "[[materials]]\nname = \"rock\"\ndensity = " << kRock << "\n";
  t << "[[joint_laws]]\nname = \"joint\"\nnormal = { law = \"linear\", stiffness = 2e9 }\n"
    << "shear = { law = \"linear\", stiffness = 2e8, friction_deg = " << s.friction_deg
    << ", cohesion = " << s.cohesion << " }\n";
  t << "[[blocks]]\nname = \"base\"\nmaterial = \"rock\"\nshape = \"vertices\"\nmotion = "
       "\"fixed\"\n";
  prism({{-10.0, -10.0 * tp}, {xk + 10.0, (xk + 10.0) * tp}, {xk + 10.0, -20.0}, {-10.0, -20.0}});
  t << "[[blocks]]\nname = \"slide\"\nmaterial = \"rock\"\nshape = \"vertices\"\n";
  prism({{0.0, 0.0}, {xk, zb}, {xk, kHeight}, {xc, kHeight}});
  t << "[[stages]]\nname = \"settle\"\ngravity = [0.0, 0.0, " << -kG << "]\n";
  // Then the water: the table through the toe and the water level in the crack (a plane
  // containing y). Applied in one stage with gravity, the loads' transient broke part of the
  // joint's cohesive bond that the static loads leave intact (the fully filled crack then gave
  // F = 1.05 instead of 1.20).
  if (s.water_depth > 0.0) t << "[[stages]]\nname = \"flood\"\n" << water_keys(s.water_depth);
  t << stages;
  return t.str();
}

std::string reduction_stage(double seismic) {
  std::ostringstream t;
  t << "[[stages]]\nname = \"srm\"\nkind = \"strength_reduction\"\nfactor_bounds = [0.5, 3.0]\n"
    << "tolerance = 0.01\nmax_steps = 60000\n";
  if (seismic > 0.0)
    t << "seismic_kh = " << seismic << "\nseismic_direction_deg = 270\nramp_steps = 2000\n";
  return t.str();
}

struct Case {
  const char* mode;
  double water_depth;
  double seismic;
};

// Printed in the cases' CTest names (gtest_discover_tests): the fields, not the bytes of the
// mode's address, so that a name is the same from build to build (tests/costs/ names them).
void PrintTo(const Case& c, std::ostream* os) {
  *os << c.mode << " zw " << c.water_depth << " kh " << c.seismic;
}

class PlaneFailureWithWater : public ::testing::TestWithParam<Case> {};

TEST_P(PlaneFailureWithWater, FactorOfSafetyMatchesHoekBray) {
  const Case c = GetParam();
  Slope s;
  s.water_depth = c.water_depth;
  s.seismic = c.seismic;
  const std::string name = std::string("water_hb_") + c.mode + "_" +
                           std::to_string(static_cast<int>(10 * c.water_depth)) + "_" +
                           std::to_string(static_cast<int>(100 * c.seismic));
  const RunResult r = run_text(slope_scenario(s, c.mode, reduction_stage(c.seismic)), name);
  ASSERT_EQ(r.status, RunStatus::completed) << r.message;
  ASSERT_TRUE(r.factor_of_safety.has_value());
  const double expected = closed_form(s);
  EXPECT_NEAR(*r.factor_of_safety, expected, 0.02 * expected);
  std::printf("%s z_w %.1f m k_h %.2f: F = %.4f (Hoek & Bray %.4f, %+.2f%%)\n", c.mode,
              c.water_depth, c.seismic, *r.factor_of_safety, expected,
              100.0 * (*r.factor_of_safety / expected - 1.0));
}

INSTANTIATE_TEST_SUITE_P(HoekBray, PlaneFailureWithWater,
                         ::testing::Values(Case{"face_integrated", 0.0, 0.0},
                                           Case{"face_integrated", 5.0, 0.0},
                                           Case{"face_integrated", 10.0, 0.0},
                                           Case{"face_integrated", 0.0, 0.1},
                                           Case{"face_integrated", 10.0, 0.1},
                                           Case{"boon2012", 10.0, 0.0}, Case{"boon2012", 5.0, 0.1}),
                         [](const ::testing::TestParamInfo<Case>& p) {
                           return std::string(p.param.mode) + "_zw" +
                                  std::to_string(static_cast<int>(p.param.water_depth)) + "_kh" +
                                  std::to_string(static_cast<int>(100 * p.param.seismic));
                         });

// The critical seismic coefficient k_c (F = 1 at full strength), found by find_collapse on k_h,
// against the closed form solved for α: half-filled crack.
TEST(PlaneFailureWithWater, CriticalSeismicCoefficientMatchesHoekBray) {
  Slope s;
  s.water_depth = 5.0;
  const double expected = critical_coefficient(s);
  const std::string stages =
      "[[stages]]\nname = \"quake\"\nseismic_kh = 0.5\nseismic_direction_deg = 270\nramp_steps = "
      "2000\n"
      "find_collapse = true\ncollapse_tolerance = 0.005\nmax_steps = 60000\n";
  const RunResult r = run_text(slope_scenario(s, "face_integrated", stages), "water_hb_kc");
  ASSERT_EQ(r.status, RunStatus::collapsed) << r.message;
  ASSERT_TRUE(r.collapse.has_value());
  const double kc = 0.5 * (r.collapse->first + r.collapse->second);
  EXPECT_NEAR(kc, expected, 0.01);
  EXPECT_EQ(r.summary["collapse"]["unit"], "seismic_kh");
  std::printf("k_c = %.4f (bracket %.4f to %.4f; Hoek & Bray %.4f)\n", kc, r.collapse->first,
              r.collapse->second, expected);
}

// Water that arrives in a strength reduction's trials (the stage sets the table; the model
// settled dry): with ramp_steps the pressure rises from none to the stage's over the ramp in every
// trial, and the factor of safety is Hoek & Bray's with the crack full (tolerance 2%, as above).
// Applied at once, the water is a sudden load whose transient overshoots the static one, so a
// trial can only fail sooner: without the ramp the factor is lower than with it by more than the
// bisection's bracket (0.01), the overshoot that the ramp avoids.
TEST(PlaneFailureWithWater, WaterRampedInTheTrialsMatchesHoekBray) {
  // Its length serves the physics (two strength reductions, one with a 5000-step ramp); the
  // ramp's code runs under the sanitizers in WaterRamp* and the collapse search's ramp test.
  if (test::sanitized_run()) GTEST_SKIP() << "two long strength reductions; physics only";
  Slope s;
  s.water_depth = 10.0;
  const double expected = closed_form(s);
  Slope dry = s;
  dry.water_depth = 0.0;
  double factor[2] = {0.0, 0.0};
  for (const int ramp : {5000, 0}) {
    std::string stages = reduction_stage(0.0) + water_keys(s.water_depth);
    if (ramp > 0) stages += "ramp_steps = " + std::to_string(ramp) + "\n";
    const RunResult r = run_text(slope_scenario(dry, "face_integrated", stages),
                                 "water_hb_trial_ramp_" + std::to_string(ramp));
    ASSERT_EQ(r.status, RunStatus::completed) << r.message;
    ASSERT_TRUE(r.factor_of_safety.has_value());
    factor[ramp > 0 ? 0 : 1] = *r.factor_of_safety;
    std::printf("water in the trials, ramp_steps %d: F = %.4f (Hoek & Bray %.4f, %+.2f%%)\n", ramp,
                *r.factor_of_safety, expected, 100.0 * (*r.factor_of_safety / expected - 1.0));
  }
  EXPECT_NEAR(factor[0], expected, 0.02 * expected);
  EXPECT_LT(factor[1], factor[0] - 0.01);
}

// The same critical coefficient when the quake stage also brings the water in over its ramp (the
// model settled dry): the search's first trial ramps the water in from none with its k_h, and
// the later trials start from the last stable one, which carries it (tolerance 0.01, as above).
TEST(PlaneFailureWithWater, CriticalSeismicCoefficientWithTheWaterRampedInTheSearch) {
  Slope s;
  s.water_depth = 5.0;
  const double expected = critical_coefficient(s);
  Slope dry = s;
  dry.water_depth = 0.0;
  const std::string stages =
      "[[stages]]\nname = \"quake\"\nseismic_kh = 0.5\nseismic_direction_deg = 270\n"
      "ramp_steps = 2000\nfind_collapse = true\ncollapse_tolerance = 0.005\nmax_steps = 60000\n" +
      water_keys(s.water_depth);
  const RunResult r = run_text(slope_scenario(dry, "face_integrated", stages), "water_hb_kc_ramp");
  ASSERT_EQ(r.status, RunStatus::collapsed) << r.message;
  ASSERT_TRUE(r.collapse.has_value());
  const double kc = 0.5 * (r.collapse->first + r.collapse->second);
  EXPECT_NEAR(kc, expected, 0.01);
  std::printf("water ramped in the search: k_c = %.4f (bracket %.4f to %.4f; Hoek & Bray %.4f)\n",
              kc, r.collapse->first, r.collapse->second, expected);
}

// Archimedes and effective stress: a block 1 × 1 × 0.5 m (2600 kg/m³) resting on a fixed base in
// water whose level table stands 2 m above it (every face below it) feels the water's force
// ρ_w g V upward, and the joint carries the submerged weight (ρ_r − ρ_w) g V, the effective
// stress σ' = σ − p times the area, with σ the total stress (the rock's weight plus the water
// column above). Half submerged (table 0.25 m above the base), the water force is ρ_w g V/2. In
// both contact modes; tolerances 1e-9 on the water force (exact integration) and 1e-4 on the
// joint force (the equilibrium's unbalanced-force tolerance 1e-6), and the energy budget
// balances with the water's work in load_work (residual below 1e-3 of its largest term).
std::string submerged_block(const std::string& mode, double table_z) {
  std::ostringstream t;
  t << "[settings]\ndamping = 0.7\ncontact_mode = \"" << mode << "\"\n"
    << "water_table = { point = [0.0, 0.0, " << table_z << "], normal = [0.0, 0.0, 1.0] }\n"
    << "water_density = 1000.0\n"
    << "[[materials]]\nname = \"rock\"\ndensity = 2600.0\n"
    << "[[joint_laws]]\nname = \"joint\"\nnormal = { law = \"linear\", stiffness = 1e10 }\n"
    << "shear = { law = \"linear\", stiffness = 1e9, friction_deg = 30 }\n"
    << "[[blocks]]\nname = \"base\"\nmaterial = \"rock\"\nsize = [3.0, 3.0, 1.0]\n"
    << "position = [0.0, 0.0, -0.5]\nmotion = \"fixed\"\n"
    << "[[blocks]]\nname = \"block\"\nmaterial = \"rock\"\nsize = [1.0, 1.0, 0.5]\n"
    << "position = [0.0, 0.0, 0.25]\n"
    << "[[stages]]\nname = \"settle\"\ngravity = [0.0, 0.0, -9.81]\nunbalanced_tolerance = 1e-6\n";
  return t.str();
}

class SubmergedBlock : public ::testing::TestWithParam<const char*> {};

TEST_P(SubmergedBlock, WaterForceIsArchimedesAndTheJointCarriesTheEffectiveWeight) {
  const double volume = 0.5, g = kG;
  for (const double table_z : {2.0, 0.25}) {
    SCOPED_TRACE(table_z);
    const Scenario sc = parse_scenario(submerged_block(GetParam(), table_z), "submerged.toml");
    World w = build_world(sc);
    const StageResult r = run_stage(w, sc.stages[0]);
    ASSERT_TRUE(r.converged) << r.message;
    // V_sub (m³, over the 1 m² base) at the level of the forces: the block has sunk into its
    // joint by the closure, about 1e-6 m.
    const int i = w.find_block("block");
    const Block& b = w.blocks()[static_cast<std::size_t>(i)];
    const double bottom = w.level_state(i).position.z() - 0.25;
    const double submerged = table_z >= 0.5 ? volume : table_z - bottom;
    const double buoyancy = kWater * g * submerged;
    EXPECT_NEAR(b.water_force().z(), buoyancy, 1e-9 * buoyancy);
    EXPECT_NEAR(b.water_force().head<2>().norm(), 0.0, 1e-9 * buoyancy);
    EXPECT_NEAR(w.total_water_force().z(), buoyancy, 1e-9 * buoyancy);
    // The joint: the effective weight; its mean normal stress is σ' = σ − p.
    const auto contacts = w.contacts();
    ASSERT_EQ(contacts.size(), 1u);
    const double effective = kRock * g * volume - buoyancy;
    EXPECT_NEAR(contacts[0]->normal_force, effective, 1e-4 * effective);
    if (table_z >= 0.5) {
      // Over the joint's 1 m²: σ the rock and the water above it, p the water at z = 0.
      const double total = kRock * g * volume + kWater * g * (table_z - volume);
      const double p = kWater * g * table_z;
      EXPECT_NEAR(contacts[0]->normal_force, total - p, 1e-4 * effective);
    }
    const EnergyBudget& e = w.energy_budget();
    EXPECT_LT(e.load_work, 0.0);  // the upward water force as the block settled onto its joint
    EXPECT_NEAR(e.water_work, e.load_work, 1e-9 * std::abs(e.load_work));  // the only load
    EXPECT_LT(std::abs(e.residual()), 1e-3 * e.scale());
    std::printf(
        "%s table %.2f m: water force %.6f N (rho_w g V_sub %.6f N), joint %.4f N "
        "(effective weight %.4f N), energy residual %.2e of %.3e J\n",
        GetParam(), table_z, b.water_force().z(), buoyancy, contacts[0]->normal_force, effective,
        e.residual(), e.scale());
  }
}

INSTANTIATE_TEST_SUITE_P(BothModes, SubmergedBlock,
                         ::testing::Values("face_integrated", "boon2012"));

// A water table that changes over a stage's ramp_steps: the pressure moves linearly from the one
// before the stage to the stage's, p = (1 - f) p_before + f p_stage at step k, f = k / ramp_steps.
// The block above, half submerged (table 0.25 m above its base) and settled, then wholly
// submerged (table at 2 m) over a ramp of 200 steps, then dry ("none") over 100: its water force
// is Archimedes' rho_w g V_sub under each table (V_sub at the block's pose), so at step k of a
// ramp it is (1 - f) rho_w g V_sub,before + f rho_w g V_sub,stage. Then a stage that keeps it dry
// over a ramp of 50 (the same water: nothing to ramp, no force), one that floods it from dry over
// 40 steps, and three without a ramp (Archimedes' force under the new table, or none, from their
// first step): the table lowered to 0.25 m, drained, and raised to 2 m from dry. Tolerance 1e-9 of
// rho_w g V (the integration is exact; round-off).
const std::string kRiseAndDrain =
    "[[stages]]\nname = \"rise\"\nkind = \"steps\"\nsteps = 300\nramp_steps = 200\n"
    "water_table = { point = [0.0, 0.0, 2.0], normal = [0.0, 0.0, 1.0] }\n"
    "[[stages]]\nname = \"drain\"\nkind = \"steps\"\nsteps = 150\nramp_steps = 100\n"
    "water_table = \"none\"\n"
    "[[stages]]\nname = \"dry\"\nkind = \"steps\"\nsteps = 60\nramp_steps = 50\n"
    "water_table = \"none\"\n"
    "[[stages]]\nname = \"flood\"\nkind = \"steps\"\nsteps = 60\nramp_steps = 40\n"
    "water_table = { point = [0.0, 0.0, 2.0], normal = [0.0, 0.0, 1.0] }\n"
    "[[stages]]\nname = \"lower\"\nkind = \"steps\"\nsteps = 40\nramp_steps = 0\n"
    "water_table = { point = [0.0, 0.0, 0.25], normal = [0.0, 0.0, 1.0] }\n"
    "[[stages]]\nname = \"empty\"\nkind = \"steps\"\nsteps = 30\nramp_steps = 0\n"
    "water_table = \"none\"\n"
    "[[stages]]\nname = \"fill\"\nkind = \"steps\"\nsteps = 30\nramp_steps = 0\n"
    "water_table = { point = [0.0, 0.0, 2.0], normal = [0.0, 0.0, 1.0] }\n";

class WaterRamp : public ::testing::TestWithParam<const char*> {};

TEST_P(WaterRamp, ArchimedesForceFollowsThePressureRampedBetweenTwoTables) {
  const Scenario sc =
      parse_scenario(submerged_block(GetParam(), 0.25) + kRiseAndDrain, "ramp.toml");
  World w = build_world(sc);
  ASSERT_TRUE(run_stage(w, sc.stages[0]).converged);
  const int i = w.find_block("block");
  // rho_w g V_sub for a level table at z_w, the block's base at the level of the forces.
  const auto buoyancy = [&w, i](double table_z) {
    const double bottom = w.level_state(i).position.z() - 0.25;
    return kWater * kG * std::clamp(table_z - bottom, 0.0, 0.5);
  };
  // Rise (0.25 m to 2 m), drain (2 m to none), stay dry, flood (none to 2 m), then at once: lower
  // (to 0.25 m), empty (none) and fill (2 m).
  struct Ramp {
    double before_z, stage_z;  // none: -inf
  };
  const Ramp ramps[] = {{0.25, 2.0}, {2.0, -INFINITY},  {-INFINITY, -INFINITY}, {-INFINITY, 2.0},
                        {2.0, 0.25}, {0.25, -INFINITY}, {-INFINITY, 2.0}};
  double worst = 0.0;
  int checked = 0;
  for (int s = 1; s <= 7; ++s) {
    const Stage& stage = sc.stages[static_cast<std::size_t>(s)];
    const Ramp ramp = ramps[s - 1];
    const StepFn on_step = [&](const World&, const Stage&, std::int64_t k) {
      const double f =
          stage.ramp_steps > 0
              ? std::min(1.0, static_cast<double>(k) / static_cast<double>(stage.ramp_steps))
              : 1.0;
      const double expected = (1.0 - f) * buoyancy(ramp.before_z) + f * buoyancy(ramp.stage_z);
      const Eigen::Vector3d force = w.blocks()[static_cast<std::size_t>(i)].water_force();
      const double error = (force - Eigen::Vector3d(0.0, 0.0, expected)).norm();
      worst = std::max(worst, error / (kWater * kG * 0.5));
      ++checked;
      EXPECT_LE(error, 1e-9 * kWater * kG * 0.5) << stage.name << " step " << k;
    };
    const StageResult r = run_stage(w, stage, {}, nullptr, {}, nullptr, on_step);
    ASSERT_TRUE(r.converged) << r.message;
    EXPECT_FALSE(w.settings().water_ramp.has_value());
    // Dry after the drain: no water force at all.
    if (s == 3) {
      EXPECT_EQ(w.blocks()[static_cast<std::size_t>(i)].water_force(), Eigen::Vector3d::Zero());
    }
  }
  EXPECT_EQ(checked, 670);
  std::printf("%s: %d steps, largest error %.2e of rho_w g V\n", GetParam(), checked, worst);
}

INSTANTIATE_TEST_SUITE_P(BothModes, WaterRamp, ::testing::Values("face_integrated", "boon2012"));

// A box on a plane dipping θ = 25° (friction φ = 35°, no cohesion) under a horizontal seismic
// coefficient k out of the slope: resolving the weight W and k W normal and parallel to the plane,
//   F = (cos θ − k sin θ) tan φ / (sin θ + k cos θ),
// and F = 1 at k_c = tan(φ − θ) (the pseudo-static sliding block; Wyllie & Mah 2004, ch. 6).
// Tolerance 1% on F (bracket 0.005) and 0.005 on k_c (bracket 0.002); both contact modes.
std::string incline_block(const std::string& mode, const std::string& stages) {
  const double theta = deg_to_rad(25.0), tp = std::tan(theta);
  const double h = 0.2;
  std::ostringstream t;
  t.precision(15);
  t << "[settings]\ndamping = 0.7\ncontact_mode = \"" << mode << "\"\n"
    << "[[materials]]\nname = \"rock\"\ndensity = 2600.0\n"
    << "[[joint_laws]]\nname = \"joint\"\nnormal = { law = \"linear\", stiffness = 1e10 }\n"
    << "shear = { law = \"linear\", stiffness = 1e9, friction_deg = 35 }\n"
    << "[[blocks]]\nname = \"base\"\nmaterial = \"rock\"\nshape = \"vertices\"\n"
    << "motion = \"fixed\"\nvertices = [";
  for (const double y : {-0.5, 0.5}) {
    t << "[-2, " << y << ", " << -2 * tp << "], [2, " << y << ", " << 2 * tp << "], [2, " << y
      << ", -3], [-2, " << y << ", -3], ";
  }
  // The box turned by -θ about y (its x axis along the plane, up-dip east), resting on it.
  t << "]\n[[blocks]]\nname = \"block\"\nmaterial = \"rock\"\nsize = [0.4, 0.2, " << h
    << "]\nrotation_axis = [0.0, 1.0, 0.0]\nrotation_deg = -25.0\nposition = ["
    << -0.5 * h * std::sin(theta) << ", 0.0, " << 0.5 * h * std::cos(theta) << "]\n"
    << "[[stages]]\nname = \"settle\"\ngravity = [0.0, 0.0, " << -kG << "]\n"
    << stages;
  return t.str();
}

class SeismicIncline : public ::testing::TestWithParam<const char*> {};

TEST_P(SeismicIncline, FactorOfSafetyAndCriticalCoefficientMatchTheClosedForm) {
  const double theta = deg_to_rad(25.0), tf = std::tan(deg_to_rad(35.0)), k = 0.1;
  const double expected =
      (std::cos(theta) - k * std::sin(theta)) * tf / (std::sin(theta) + k * std::cos(theta));
  const RunResult r =
      run_text(incline_block(GetParam(),
                             "[[stages]]\nname = \"srm\"\nkind = \"strength_reduction\"\n"
                             "factor_bounds = [0.5, 3.0]\ntolerance = 0.005\nmax_steps = 60000\n"
                             "seismic_kh = 0.1\nseismic_direction_deg = 270\nramp_steps = 2000\n"),
               std::string("seismic_incline_") + GetParam());
  ASSERT_EQ(r.status, RunStatus::completed) << r.message;
  ASSERT_TRUE(r.factor_of_safety.has_value());
  EXPECT_NEAR(*r.factor_of_safety, expected, 0.01 * expected);
  const RunResult c = run_text(
      incline_block(GetParam(),
                    "[[stages]]\nname = \"quake\"\nseismic_kh = 0.4\nseismic_direction_deg = "
                    "270\nramp_steps = 2000\nfind_collapse = true\ncollapse_tolerance = 0.002\n"
                    "max_steps = 60000\n"),
      std::string("seismic_incline_kc_") + GetParam());
  ASSERT_EQ(c.status, RunStatus::collapsed) << c.message;
  ASSERT_TRUE(c.collapse.has_value());
  const double kc = 0.5 * (c.collapse->first + c.collapse->second);
  const double kc_expected = std::tan(deg_to_rad(35.0 - 25.0));
  EXPECT_NEAR(kc, kc_expected, 0.005);
  std::printf("%s: F = %.4f (closed form %.4f, %+.2f%%), k_c = %.4f (tan(phi - theta) = %.4f)\n",
              GetParam(), *r.factor_of_safety, expected,
              100.0 * (*r.factor_of_safety / expected - 1.0), kc, kc_expected);
}

INSTANTIATE_TEST_SUITE_P(BothModes, SeismicIncline,
                         ::testing::Values("face_integrated", "boon2012"));

// A stack of three blocks 1 × 1 × 0.5 m wholly below a level water table given as a surface
// through points: the assembly stays at rest (the buoyancy and the joints' pressures balance the
// weight with the joints' effective forces), each joint carrying the submerged weight of the
// blocks above it, (ρ_r − ρ_w) g V per block (tolerance 1e-4; displacements below 1e-5 m).
TEST(SubmergedAssembly, StaysAtRestWithEachJointCarryingTheSubmergedWeightAbove) {
  std::ostringstream t;
  t << "[settings]\ndamping = 0.7\n"
    << "water_table = { points = [[-5, -5, 4], [5, -5, 4], [5, 5, 4], [-5, 5, 4], [0, 1, 4]] }\n"
    << "[[materials]]\nname = \"rock\"\ndensity = 2600.0\n"
    << "[[joint_laws]]\nname = \"joint\"\nnormal = { law = \"linear\", stiffness = 1e10 }\n"
    << "shear = { law = \"linear\", stiffness = 1e9, friction_deg = 30 }\n"
    << "[[blocks]]\nname = \"base\"\nmaterial = \"rock\"\nsize = [3.0, 3.0, 1.0]\n"
    << "position = [0.0, 0.0, -0.5]\nmotion = \"fixed\"\n";
  for (int k = 0; k < 3; ++k) {
    t << "[[blocks]]\nname = \"b" << k << "\"\nmaterial = \"rock\"\nsize = [1.0, 1.0, 0.5]\n"
      << "position = [0.0, 0.0, " << 0.25 + 0.5 * k << "]\n";
  }
  t << "[[stages]]\nname = \"settle\"\ngravity = [0.0, 0.0, " << -kG
    << "]\nunbalanced_tolerance = 1e-6\n";
  const Scenario sc = parse_scenario(t.str(), "stack.toml");
  World w = build_world(sc);
  const StageResult r = run_stage(w, sc.stages[0]);
  ASSERT_TRUE(r.converged) << r.message;
  const double submerged_weight = (kRock - kWater) * kG * 0.5;  // per block (N)
  const auto contacts = w.contacts();
  ASSERT_EQ(contacts.size(), 3u);
  for (const Contact* c : contacts) {
    // Joint (a, b) with b the upper block: it carries the blocks from b up.
    const int above = 3 - (c->b - 1);
    EXPECT_NEAR(c->normal_force, above * submerged_weight, 1e-4 * submerged_weight)
        << c->a << "-" << c->b;
  }
  for (std::size_t i = 1; i < w.blocks().size(); ++i) {
    const Block& b = w.blocks()[i];
    EXPECT_LT((b.position - b.initial_position).norm(), 1e-5) << b.name;
    EXPECT_NEAR(b.water_force().z(), kWater * kG * 0.5, 1e-9 * kWater * kG * 0.5) << b.name;
  }
}

// A reservoir against an exposed face, and uplift under a block (the sliding of a gravity dam's
// block on its foundation; e.g. Wyllie & Mah 2004, ch. 6, for the water forces): a block b = 10 m
// long and H = 10 m high (2600 kg/m³, 1 m wide) holds water h = 8 m deep against its upstream
// face, drained at its downstream toe. The water table is a surface through points: level at h
// upstream of the block, falling linearly across it to the foundation at its downstream face,
// so the upstream face carries P = ½ γ_w h², the base the uplift U = ½ γ_w h b, and the
// downstream face nothing. With friction φ = 10° and no cohesion, F = (W − U) tan φ / P, the
// strength-reduction factor within 2% (bracket 0.01), in both contact modes. The table stays
// where it is given: a block that slides away from the reservoir carries less of it, so a trial
// counts as failed once the block has slid 0.05 m (displacement_limit).
class Reservoir : public ::testing::TestWithParam<const char*> {};

TEST_P(Reservoir, FactorOfSafetyOfABlockPushedByAReservoirWithUplift) {
  const double b = 10.0, h = 8.0, height = 10.0;
  std::ostringstream t;
  t.precision(15);
  t << "[settings]\ndamping = 0.7\ncontact_mode = \"" << GetParam() << "\"\n"
    << "[[materials]]\nname = \"rock\"\ndensity = " << kRock << "\n"
    << "[[joint_laws]]\nname = \"joint\"\nnormal = { law = \"linear\", stiffness = 2e9 }\n"
    << "shear = { law = \"linear\", stiffness = 2e8, friction_deg = 10 }\n"
    << "[[blocks]]\nname = \"foundation\"\nmaterial = \"rock\"\nsize = [40.0, 3.0, 4.0]\n"
    << "position = [" << 0.5 * b << ", 0.0, -2.0]\nmotion = \"fixed\"\n"
    << "[[blocks]]\nname = \"dam\"\nmaterial = \"rock\"\nsize = [" << b << ", 1.0, " << height
    << "]\nposition = [" << 0.5 * b << ", 0.0, " << 0.5 * height << "]\n"
    << "[[stages]]\nname = \"settle\"\ngravity = [0.0, 0.0, " << -kG << "]\n"
    << "[[stages]]\nname = \"fill\"\nwater_table = { points = [[0, -5, " << h << "], [0, 5, " << h
    << "], [" << b << ", -5, 0], [" << b << ", 5, 0]] }\n"
    << "[[stages]]\nname = \"srm\"\nkind = \"strength_reduction\"\nfactor_bounds = [0.5, 3.0]\n"
    << "tolerance = 0.01\nmax_steps = 60000\ndisplacement_limit = 0.05\n";
  const RunResult r = run_text(t.str(), std::string("reservoir_") + GetParam());
  ASSERT_EQ(r.status, RunStatus::completed) << r.message;
  ASSERT_TRUE(r.factor_of_safety.has_value());
  const double w = kRock * kG * b * height, u = 0.5 * kWater * kG * h * b;
  const double p = 0.5 * kWater * kG * h * h;
  const double expected = (w - u) * std::tan(deg_to_rad(10.0)) / p;
  EXPECT_NEAR(*r.factor_of_safety, expected, 0.02 * expected);
  // The water's force on the block: P downstream (+x) and U up.
  const auto& water = r.summary["water_force_vector_N"];
  EXPECT_NEAR(water[0].get<double>(), p, 1e-3 * p);
  EXPECT_NEAR(water[2].get<double>(), u, 1e-3 * u);
  std::printf(
      "%s: F = %.4f (closed form %.4f, %+.2f%%), water force (%.1f, %.1f) N (P %.1f, U %.1f)\n",
      GetParam(), *r.factor_of_safety, expected, 100.0 * (*r.factor_of_safety / expected - 1.0),
      water[0].get<double>(), water[2].get<double>(), p, u);
}

INSTANTIATE_TEST_SUITE_P(BothModes, Reservoir, ::testing::Values("face_integrated", "boon2012"));

}  // namespace
}  // namespace blockdem::test::water_seismic
