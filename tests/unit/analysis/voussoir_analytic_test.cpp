// Tests of the Diederichs & Kaiser (1999) voussoir beam: hand-worked iteration, the stiff limit
// minimised analytically, the lever-arm cubic as an oracle, 1/E scaling of the deflection, the
// snap-through limit, statics and input checks.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "blockdem/analysis/voussoir_analytic.hpp"

namespace blockdem {
namespace {

// A 10 m span, 1 m thick hard-rock beam, gamma = 26 kN/m^3.
VoussoirBeamDef rock_beam(double modulus) {
  VoussoirBeamDef beam;
  beam.span = 10.0;
  beam.depth = 1.0;
  beam.unit_weight = 26000.0;
  beam.rock_mass_modulus = modulus;
  return beam;
}

// Independent oracle: eliminating f_m, f_av and dL, the converged lever arm solves
// Z^3 - Z0^2 Z + K = 0 with K = gamma S^3 (2/3 + n) L / (32 n E). Its largest root, by the
// trigonometric formula for a depressed cubic, is Z = (2 Z0 / sqrt 3) cos(acos(c) / 3) with
// c = -3 sqrt(3) K / (2 Z0^3); no real positive root once c < -1 (snap-through): NaN then.
double lever_arm_from_cubic(const VoussoirBeamDef& beam, double n) {
  const double z0 = beam.depth * (1.0 - 2.0 * n / 3.0);
  const double length = beam.span + 8.0 * z0 * z0 / (3.0 * beam.span);
  const double k = beam.unit_weight * std::pow(beam.span, 3) * (2.0 / 3.0 + n) * length /
                   (32.0 * n * beam.rock_mass_modulus);
  const double c = -3.0 * std::numbers::sqrt3 * k / (2.0 * z0 * z0 * z0);
  if (c < -1.0) return std::nan("");
  return 2.0 * z0 / std::numbers::sqrt3 * std::cos(std::acos(c) / 3.0);
}

TEST(VoussoirAnalytic, FirstIterationMatchesHandCalculation) {
  // S = 10 m, T = 1 m, gamma = 26 kN/m^3, E = 1 GPa, n = 0.75, by hand:
  //   Z0 = T (1 - 2n/3) = 0.5 m;  L = S + 8 Z0^2 / (3S) = 10 + 2/30 = 10.066667 m
  //   f_m = gamma S^2 / (4 n Z0) = 2.6e6 / 1.5 = 1.733333e6 Pa
  //   f_av = f_m (2/3 + 0.75) / 3 = 0.4722222 f_m = 818518.5 Pa
  //   dL = f_av L / E = 8.239753e-3 m
  //   Z1 = sqrt(3S/8 (8 Z0^2/(3S) - dL)) = sqrt(0.25 - 3.75 * 8.239753e-3) = sqrt(0.2191007)
  //      = 0.4680822 m
  VoussoirSolverOptions one_step;
  one_step.max_iterations = 1;
  const VoussoirTrial first = voussoir_trial(rock_beam(1e9), 0.75, one_step);
  EXPECT_EQ(first.status, VoussoirTrialStatus::iteration_limit);
  EXPECT_DOUBLE_EQ(first.initial_lever_arm, 0.5);
  EXPECT_NEAR(first.arch_length, 10.066667, 1e-6);
  EXPECT_NEAR(first.lever_arm, 0.4680822, 1e-7);

  // Converged: the cubic Z^3 - 0.25 Z + 0.01544954 = 0 has its largest root at Z = 0.4656403 m,
  // where f_m = gamma S^2 / (4 n Z) = 1.861236e6 Pa.
  const VoussoirTrial converged = voussoir_trial(rock_beam(1e9), 0.75);
  ASSERT_EQ(converged.status, VoussoirTrialStatus::converged);
  EXPECT_NEAR(converged.lever_arm, 0.4656403, 1e-7);
  EXPECT_NEAR(converged.max_stress / 1.861236e6, 1.0, 1e-6);
}

TEST(VoussoirAnalytic, ConvergedLeverArmIsLargestRootOfTheCubic) {
  // Both outcomes occur on this grid: at E = 0.3 GPa the larger n have no root.
  int converged = 0, snapped = 0;
  for (const double modulus : {3e8, 1e9, 1e10}) {
    for (const double n : {0.2, 0.5, 0.75, 0.95}) {
      const VoussoirBeamDef beam = rock_beam(modulus);
      const VoussoirTrial trial = voussoir_trial(beam, n);
      const double oracle = lever_arm_from_cubic(beam, n);
      if (std::isnan(oracle)) {
        EXPECT_EQ(trial.status, VoussoirTrialStatus::snap_through) << "E " << modulus << " n " << n;
        ++snapped;
        continue;
      }
      ASSERT_EQ(trial.status, VoussoirTrialStatus::converged) << "E " << modulus << " n " << n;
      EXPECT_NEAR(trial.lever_arm / oracle, 1.0, 1e-11) << "E " << modulus << " n " << n;
      ++converged;
    }
  }
  EXPECT_GT(converged, 8);
  EXPECT_GT(snapped, 0);
}

TEST(VoussoirAnalytic, StiffLimitMatchesAnalyticMinimiser) {
  // As E -> infinity, dL -> 0 and Z -> Z0 = T (1 - 2n/3), so f_m = gamma S^2 / (4 T g(n)) with
  // g(n) = n - 2n^2/3. g'(n) = 1 - 4n/3 = 0 gives n = 3/4, g = 3/8, Z = T/2, hence
  //   f_m = 2 gamma S^2 / (3 T) = 1.733333e6 Pa, thrust f_m n T / 2 = gamma S^2 / 4 = 650 kN/m.
  const VoussoirBeamDef beam = rock_beam(1e20);
  const VoussoirResult result = solve_voussoir_beam(beam);
  ASSERT_EQ(result.status, VoussoirStatus::stable);
  const VoussoirEquilibrium& eq = *result.equilibrium;
  EXPECT_NEAR(eq.n, 0.75, 1e-6);
  EXPECT_NEAR(eq.lever_arm, 0.5, 1e-6);
  EXPECT_LT(eq.midspan_deflection, 1e-12);
  EXPECT_GE(eq.midspan_deflection, 0.0);
  const double gamma = beam.unit_weight, s = beam.span, t = beam.depth;
  EXPECT_NEAR(eq.max_stress / (2.0 * gamma * s * s / (3.0 * t)), 1.0, 1e-10);
  EXPECT_NEAR(eq.thrust_per_width / (gamma * s * s / 4.0), 1.0, 1e-9);
}

TEST(VoussoirAnalytic, DeflectionScalesAsInverseModulusForStiffBeams) {
  // For large E, Z = Z0 - K / (2 Z0^2) + O(K^2) at n = 3/4 (n shifts by O(1/E), which changes the
  // deflection only at O(1/E^2) because n = 3/4 is stationary). With Z0 = T/2,
  // L = S + 2 T^2 / (3 S) and K = 17 gamma S^3 L / (288 E):
  //   deflection * E -> 17 gamma S^3 L / (144 T^2).
  const VoussoirBeamDef beam = rock_beam(1e12);
  const double s = beam.span, t = beam.depth;
  const double length = s + 2.0 * t * t / (3.0 * s);
  const double limit = 17.0 * beam.unit_weight * s * s * s * length / (144.0 * t * t);
  const VoussoirResult stiff = solve_voussoir_beam(beam);
  const VoussoirResult stiffer = solve_voussoir_beam(rock_beam(2e12));
  ASSERT_EQ(stiff.status, VoussoirStatus::stable);
  ASSERT_EQ(stiffer.status, VoussoirStatus::stable);
  const double d1 = stiff.equilibrium->midspan_deflection;
  const double d2 = stiffer.equilibrium->midspan_deflection;
  EXPECT_NEAR(d1 * 1e12 / limit, 1.0, 1e-3);
  EXPECT_NEAR(d1 / d2, 2.0, 2e-3);
}

TEST(VoussoirAnalytic, ThrustSatisfiesHalfSpanMomentEquilibrium) {
  // The thrust acts at lever arm Z between midspan (top) and abutment (bottom); the half span's
  // moment balance is H Z = W S / 8 with W = gamma T S per unit width.
  const VoussoirBeamDef beam = rock_beam(5e8);
  const VoussoirResult result = solve_voussoir_beam(beam);
  ASSERT_EQ(result.status, VoussoirStatus::stable);
  const VoussoirEquilibrium& eq = *result.equilibrium;
  const double weight = beam.unit_weight * beam.depth * beam.span;
  EXPECT_NEAR(eq.thrust_per_width * eq.lever_arm / (weight * beam.span / 8.0), 1.0, 1e-12);
  EXPECT_NEAR(eq.midspan_deflection, eq.initial_lever_arm - eq.lever_arm, 1e-15);
  EXPECT_GT(eq.midspan_deflection, 0.0);
  // The chosen n is a minimum of f_m: its neighbours have larger f_m.
  for (const double dn : {-1e-3, 1e-3}) {
    const VoussoirTrial neighbour = voussoir_trial(beam, eq.n + dn);
    ASSERT_EQ(neighbour.status, VoussoirTrialStatus::converged);
    EXPECT_GT(neighbour.max_stress, eq.max_stress);
  }
}

TEST(VoussoirAnalytic, SafetyFactorsFollowTheirDefinitions) {
  VoussoirBeamDef beam = rock_beam(5e8);
  beam.compressive_strength = 100e6;
  beam.friction_angle = 35.0 * std::numbers::pi / 180.0;
  beam.width = 4.0;
  const VoussoirResult result = solve_voussoir_beam(beam);
  ASSERT_EQ(result.status, VoussoirStatus::stable);
  const VoussoirEquilibrium& eq = *result.equilibrium;
  EXPECT_NEAR(*eq.crushing_safety_factor, 100e6 / eq.max_stress, 1e-12);
  // H tan(phi) / (gamma T S / 2) with H = gamma T S^2 / (8 Z) reduces to S tan(phi) / (4 Z).
  EXPECT_NEAR(*eq.sliding_safety_factor /
                  (beam.span * std::tan(*beam.friction_angle) / (4.0 * eq.lever_arm)),
              1.0, 1e-12);
  EXPECT_DOUBLE_EQ(*eq.thrust, 4.0 * eq.thrust_per_width);
}

TEST(VoussoirAnalytic, SnapThroughForVerySoftRockMass) {
  const VoussoirBeamDef beam = rock_beam(1e6);
  const VoussoirResult result = solve_voussoir_beam(beam);
  EXPECT_EQ(result.status, VoussoirStatus::snap_through);
  EXPECT_FALSE(result.equilibrium.has_value());
  EXPECT_EQ(result.feasible_n_count, 0);
  EXPECT_GT(result.scanned_n_count, 999);
  EXPECT_LT(result.buckling.modulus_safety_factor, 1.0);
  EXPECT_LT(result.buckling.span_safety_factor, 1.0);
  const nlohmann::ordered_json report = voussoir_report_json(beam, result);
  EXPECT_EQ(report["status"], "snap_through");
  EXPECT_TRUE(report["n"].is_null());
  EXPECT_TRUE(report["max_stress_Pa"].is_null());
}

TEST(VoussoirAnalytic, CriticalModulusAndSpanBracketTheSnapThrough) {
  // The closed-form fold E_crit = min_n 3 sqrt(3) gamma S^3 (2/3 + n) L / (64 n Z0^3) must agree
  // with the iteration: just above it a solution exists, just below none.
  const VoussoirResult reference = solve_voussoir_beam(rock_beam(1e9));
  const double e_crit = reference.buckling.critical_modulus;
  // Brute force over a fine grid of n, written out here independently of the library.
  double e_grid = HUGE_VAL;
  const double g = 26000.0, s = 10.0, t = 1.0;
  for (int i = 1; i <= 100000; ++i) {
    const double n = i * 1e-5;
    const double z0 = t * (1.0 - 2.0 * n / 3.0);
    const double length = s + 8.0 * z0 * z0 / (3.0 * s);
    e_grid = std::min(e_grid, 3.0 * std::sqrt(3.0) * g * s * s * s * (2.0 / 3.0 + n) * length /
                                  (64.0 * n * z0 * z0 * z0));
  }
  EXPECT_NEAR(e_crit / e_grid, 1.0, 1e-8);
  EXPECT_LE(e_crit, e_grid);
  EXPECT_EQ(solve_voussoir_beam(rock_beam(1.001 * e_crit)).status, VoussoirStatus::stable);
  EXPECT_EQ(solve_voussoir_beam(rock_beam(0.999 * e_crit)).status, VoussoirStatus::snap_through);

  // At a single n, the iteration converges just above E_crit(n), with Z >= Z0 / sqrt 3 (the
  // fold), and snaps through just below.
  const double n = 0.5;
  const double e_n = voussoir_critical_modulus(rock_beam(1e9), n);
  const VoussoirTrial above = voussoir_trial(rock_beam(1.001 * e_n), n);
  ASSERT_EQ(above.status, VoussoirTrialStatus::converged);
  EXPECT_GE(above.lever_arm, above.initial_lever_arm / std::numbers::sqrt3);
  EXPECT_EQ(voussoir_trial(rock_beam(0.999 * e_n), n).status, VoussoirTrialStatus::snap_through);

  // The critical span at E = 1 GPa: just shorter is stable, just longer snaps through.
  const double s_crit = reference.buckling.critical_span;
  VoussoirBeamDef shorter = rock_beam(1e9);
  shorter.span = s_crit * (1.0 - 1e-3);
  VoussoirBeamDef longer = rock_beam(1e9);
  longer.span = s_crit * (1.0 + 1e-3);
  EXPECT_EQ(solve_voussoir_beam(shorter).status, VoussoirStatus::stable);
  EXPECT_EQ(solve_voussoir_beam(longer).status, VoussoirStatus::snap_through);
}

TEST(VoussoirAnalytic, RockMassModulusHelpers) {
  // Table 2 joints, k_n = 10 GPa/m at 46 mm spacing: E_rm = 0.46 GPa.
  EXPECT_NEAR(rock_mass_modulus_rigid_blocks(10e9, 0.046), 4.6e8, 1e-3);
  // Elastic blocks in series: compliances add, so E_rm < both; stiff blocks recover k_n s.
  EXPECT_NEAR(rock_mass_modulus(5.6e9, 10e9, 0.046), 1.0 / (1.0 / 5.6e9 + 1.0 / 4.6e8), 1e-3);
  EXPECT_NEAR(rock_mass_modulus(1e30, 10e9, 0.046) / 4.6e8, 1.0, 1e-12);
  EXPECT_THROW(rock_mass_modulus_rigid_blocks(-1.0, 0.046), std::invalid_argument);
  EXPECT_THROW(rock_mass_modulus_rigid_blocks(10e9, 0.0), std::invalid_argument);
  EXPECT_THROW(rock_mass_modulus(0.0, 10e9, 0.046), std::invalid_argument);
}

TEST(VoussoirAnalytic, RejectsInvalidInputNamingEachParameter) {
  auto message_of = [](const VoussoirBeamDef& beam) -> std::string {
    try {
      solve_voussoir_beam(beam);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  VoussoirBeamDef beam = rock_beam(1e9);
  beam.span = -1.0;
  EXPECT_NE(message_of(beam).find("span"), std::string::npos);
  beam = rock_beam(1e9);
  beam.depth = 0.0;
  EXPECT_NE(message_of(beam).find("depth"), std::string::npos);
  beam = rock_beam(1e9);
  beam.unit_weight = std::nan("");
  EXPECT_NE(message_of(beam).find("unit_weight"), std::string::npos);
  beam = rock_beam(0.0);
  EXPECT_NE(message_of(beam).find("rock_mass_modulus"), std::string::npos);
  beam = rock_beam(1e9);
  beam.friction_angle = std::numbers::pi / 2.0;
  EXPECT_NE(message_of(beam).find("friction_angle"), std::string::npos);
  beam = rock_beam(1e9);
  beam.compressive_strength = -5.0;
  EXPECT_NE(message_of(beam).find("compressive_strength"), std::string::npos);
  // Every bad parameter is listed, not only the first.
  VoussoirBeamDef all_bad;
  const std::string all = message_of(all_bad);
  for (const char* name : {"span", "depth", "unit_weight", "rock_mass_modulus"}) {
    EXPECT_NE(all.find(name), std::string::npos) << name;
  }
  EXPECT_THROW(voussoir_trial(rock_beam(1e9), 0.0), std::invalid_argument);
  EXPECT_THROW(voussoir_trial(rock_beam(1e9), 1.5), std::invalid_argument);
  VoussoirSolverOptions bad_options;
  bad_options.n_step = 0.0;
  EXPECT_THROW(solve_voussoir_beam(rock_beam(1e9), bad_options), std::invalid_argument);
}

TEST(VoussoirAnalytic, JsonReportCarriesUnitsAndInputs) {
  VoussoirBeamDef beam = rock_beam(1e9);
  beam.width = 2.0;
  const VoussoirResult result = solve_voussoir_beam(beam);
  const nlohmann::ordered_json report = voussoir_report_json(beam, result);
  EXPECT_EQ(report["status"], "stable");
  EXPECT_DOUBLE_EQ(report["n"].get<double>(), result.equilibrium->n);
  EXPECT_DOUBLE_EQ(report["lever_arm_m"].get<double>(), result.equilibrium->lever_arm);
  EXPECT_DOUBLE_EQ(report["midspan_deflection_m"].get<double>(),
                   result.equilibrium->midspan_deflection);
  EXPECT_DOUBLE_EQ(report["max_stress_Pa"].get<double>(), result.equilibrium->max_stress);
  EXPECT_DOUBLE_EQ(report["thrust_N"].get<double>(), 2.0 * report["thrust_N_per_m"].get<double>());
  EXPECT_TRUE(report["crushing_safety_factor"].is_null());
  EXPECT_DOUBLE_EQ(report["inputs"]["span_m"].get<double>(), 10.0);
  EXPECT_DOUBLE_EQ(report["buckling"]["critical_modulus_Pa"].get<double>(),
                   result.buckling.critical_modulus);
}

}  // namespace
}  // namespace blockdem
