// Tests of the continuously-yielding calibration (eq 8 with eq 6, the paper's Fig 4): the
// kernel-driven path against the closed-form monotonic solution, exact recovery, recovery within
// 5 % from data with 2 % noise, the round trip at fine steps, and the rejections.
#include <gtest/gtest.h>

#include <cmath>

#include "blockdem/calibration/cy_calibration.hpp"
#include "blockdem/calibration/shear_path.hpp"
#include "blockdem/lab/shear_test.hpp"
#include "calibration_test_support.hpp"

namespace blockdem {
namespace {

using test::calibration_error;
using test::relative_error;

// Oracle: monotonic shear at constant sigma_n, the continuously-yielding law in closed form.
// tau = mu(beta) sigma_n with u = beta + tau / k_i; beta by bisection (slow, obviously right).
double closed_form_tau(const ContinuouslyYieldingShear& law, double sigma, double u) {
  const double k = law.power_laws.initial_stiffness(sigma);
  const double peak = law.power_laws.peak_displacement(sigma);
  double lo = 0.0;
  double hi = u;
  for (int i = 0; i < 200; ++i) {
    const double beta = 0.5 * (lo + hi);
    (beta + law.friction_coefficient(beta, peak) * sigma / k < u ? lo : hi) = beta;
  }
  return law.friction_coefficient(0.5 * (lo + hi), peak) * sigma;
}

TEST(SimulateMonotonicShear, KernelMatchesTheClosedFormAtAnyStepSize) {
  const ContinuouslyYieldingShear law;  // the paper's eqs 6-8
  const double sigma = 2e4;
  std::vector<double> u;
  for (int i = 0; i <= 30; ++i) u.push_back(3e-6 * i);
  const std::vector<double> coarse = simulate_monotonic_shear(law, sigma, u, 1);
  const std::vector<double> fine = simulate_monotonic_shear(law, sigma, u, 100);
  for (std::size_t i = 0; i < u.size(); ++i) {
    const double expected = closed_form_tau(law, sigma, u[i]);
    EXPECT_NEAR(coarse[i], expected, 1e-9 * sigma) << "u = " << u[i];
    EXPECT_NEAR(fine[i], expected, 1e-9 * sigma) << "u = " << u[i];
  }
  EXPECT_THROW(simulate_monotonic_shear(law, sigma, {2e-6, 1e-6}), std::invalid_argument);
  EXPECT_THROW(simulate_monotonic_shear(law, 0.0, u), std::invalid_argument);
}

TEST(CyCalibration, RecoversFrictionAndEq6ExactlyFromKernelCurves) {
  ContinuouslyYieldingShear law;
  law.strength = JointStrength::from_friction_deg(35.0);
  law.power_laws.peak_coefficient = 3e-6;
  law.power_laws.peak_exponent = 0.15;
  DirectShearData data;
  data.source = "kernel";
  for (double s : {1e4, 5e4, 2.5e5}) {
    DirectShearCurve c;
    c.normal_stress = s;
    for (int i = 0; i < 25; ++i) {
      c.displacement.push_back(5.0 * law.power_laws.peak_displacement(s) * i / 24.0);
      c.lines.push_back(i);
    }
    c.shear_stress = simulate_monotonic_shear(law, s, c.displacement);
    data.curves.push_back(c);
  }
  const CyCalibration cal = calibrate_continuously_yielding(data, CyStiffnessDef{1.9e6, 0.7});
  EXPECT_LT(relative_error(cal.law.strength.friction_deg(), 35.0), 1e-8);
  EXPECT_LT(relative_error(cal.law.power_laws.peak_coefficient, 3e-6), 1e-7);
  EXPECT_LT(relative_error(cal.law.power_laws.peak_exponent, 0.15), 1e-8);
  EXPECT_EQ(cal.law.power_laws.stiffness_coefficient, 1.9e6);
  EXPECT_EQ(cal.law.power_laws.stiffness_exponent, 0.7);
  EXPECT_LT(cal.quality.max_abs_residual, 1e-9);
}

TEST(CyCalibration, RecoversTheScriptsNoiseFreeDataTo1e6) {
  // The script's curves come from the closed form, independent of the C++ kernel.
  const DirectShearData data =
      read_direct_shear(test::synthetic_data("shear --model cy", "cy_exact.csv"));
  const CyCalibration cal = calibrate_continuously_yielding(data, CyStiffnessDef{1.9e6, 0.7});
  EXPECT_LT(relative_error(cal.law.strength.friction_deg(), 40.0), 1e-6);
  EXPECT_LT(relative_error(cal.law.power_laws.peak_coefficient, 2e-6), 1e-6);
  EXPECT_LT(relative_error(cal.law.power_laws.peak_exponent, 0.213), 1e-6);
}

TEST(CyCalibration, RecoversParametersWithin5PercentFrom2PercentNoiseAndRoundTrips) {
  // 5 normal stresses (10 kPa - 1 MPa), 200 rows per curve to 5 u_peak, each shear stress
  // multiplied by (1 + 0.02 z). Over 20 seeds the relative errors of this design have RMS
  // 0.1 % (phi), 1.3 % (C), 0.6 % (D) (docs/calibration.md).
  const std::string design = "shear --model cy --points 200";
  const DirectShearData noisy =
      read_direct_shear(test::synthetic_data(design + " --noise 0.02 --seed 3", "cy_noisy.csv"));
  const CyCalibration cal = calibrate_continuously_yielding(noisy, CyStiffnessDef{1.9e6, 0.7});
  EXPECT_LT(relative_error(cal.law.strength.friction_deg(), 40.0), 0.05);
  EXPECT_LT(relative_error(cal.law.power_laws.peak_coefficient, 2e-6), 0.05);
  EXPECT_LT(relative_error(cal.law.power_laws.peak_exponent, 0.213), 0.05);

  // Round trip at fine steps (50 kernel steps per data interval): within the 2 % noise of the
  // noise-free curves; the misfit to the noisy data is the noise.
  const DirectShearData truth = read_direct_shear(test::synthetic_data(design, "cy_truth.csv"));
  for (std::size_t c = 0; c < truth.curves.size(); ++c) {
    const DirectShearCurve& t = truth.curves[c];
    const std::vector<double> tau =
        simulate_monotonic_shear(cal.law, t.normal_stress, t.displacement, 50);
    for (std::size_t i = 1; i < tau.size(); ++i) {
      EXPECT_LT(relative_error(tau[i], t.shear_stress[i]), 0.02)
          << "sigma_n " << t.normal_stress << " u " << t.displacement[i];
    }
    // 200 rows: the RMS of the 2 % noise itself is 0.02 +- 0.001 (one standard deviation).
    EXPECT_LT(cal.curves[c].quality.rms_relative_residual, 0.025);
    EXPECT_GT(cal.curves[c].quality.rms_relative_residual, 0.016);

    // The same law in `blockdem lab`'s direct shear test (2000 kernel increments to the largest
    // displacement), interpolated linearly at the data's displacements: within the noise too.
    ShearTestDef lab;
    lab.law = cal.law;
    lab.normal_stress = t.normal_stress;
    lab.max_displacement = t.displacement.back();
    const std::vector<ShearPoint> points = run_shear_kernel(lab).points;
    std::size_t k = 1;
    for (std::size_t i = 1; i < t.displacement.size(); ++i) {
      while (k + 1 < points.size() && points[k].shear_displacement < t.displacement[i]) ++k;
      const ShearPoint& p0 = points[k - 1];
      const ShearPoint& p1 = points[k];
      const double f = (t.displacement[i] - p0.shear_displacement) /
                       (p1.shear_displacement - p0.shear_displacement);
      const double tau_lab = p0.shear_stress + f * (p1.shear_stress - p0.shear_stress);
      EXPECT_LT(relative_error(tau_lab, t.shear_stress[i]), 0.02)
          << "lab, sigma_n " << t.normal_stress << " u " << t.displacement[i];
    }
  }
}

TEST(CyCalibration, RejectsBadStiffnessAndCurvesWithoutShearStress) {
  const DirectShearData data =
      read_direct_shear(test::synthetic_data("shear --model cy --points 10", "cy_small.csv"));
  EXPECT_NE(calibration_error([&] {
              calibrate_continuously_yielding(data, CyStiffnessDef{-1.0, 0.7});
            }).find("stiffness_coefficient (A of eq 7"),
            std::string::npos);
  EXPECT_NE(calibration_error([&] {
              calibrate_continuously_yielding(data, CyStiffnessDef{1.9e6, -0.1});
            }).find("stiffness_exponent (B of eq 7"),
            std::string::npos);
  DirectShearData flat = data;
  for (double& tau : flat.curves[1].shear_stress) tau = 0.0;
  const std::string e =
      calibration_error([&] { calibrate_continuously_yielding(flat, CyStiffnessDef{}); });
  EXPECT_NE(e.find("the curve at normal stress 30000 Pa has no positive shear stress"),
            std::string::npos)
      << e;
}

}  // namespace
}  // namespace blockdem
