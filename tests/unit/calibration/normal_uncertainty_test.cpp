// Parameter uncertainty in the calibration: the normal calibration's standard errors and 95%
// intervals of a and b checked against a Monte-Carlo repetition of synthetic column tests; the
// power laws' exponent interval against the closed form of linear regression.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "blockdem/calibration/fit_quality.hpp"
#include "blockdem/calibration/normal_calibration.hpp"

namespace blockdem {
namespace {

// Synthetic column tests made with the paper's eq 4 law (a = 54050 Pa, b = 3.7e4 1/m), E, H, N
// of the default column, 40 stresses from 10 kPa to 2 MPa, and 2% noise proportional to the
// joint closure (the noise model the relative residuals assume). 200 repetitions with fresh
// noise (fixed seed). References: the spread of the fitted a and b equals the mean predicted
// standard error within 15% (sampling error of 200 draws 5%, plus the delta method's
// linearisation); the 95% intervals cover the true values in 90.5% to 99.5% of the repetitions
// (three binomial standard deviations of 200 trials, 1.5% each).
TEST(NormalCalibrationUncertainty, MatchesMonteCarloRepetition) {
  const double a = 54050.0, b = 3.7e4, noise = 0.02;
  const ColumnTestDef test;
  const int rows = 40, trials = 200;
  std::mt19937 rng(2015);
  std::normal_distribution<double> unit(0.0, 1.0);
  double sum_a = 0, sum2_a = 0, sum_b = 0, sum2_b = 0, se_a = 0, se_b = 0;
  int covered_a = 0, covered_b = 0;
  for (int t = 0; t < trials; ++t) {
    ColumnCompressionData data;
    data.source = "synthetic";
    for (int i = 0; i < rows; ++i) {
      const double s = 1e4 * std::pow(200.0, static_cast<double>(i) / (rows - 1));
      const double u = std::log1p(s / a) / b * (1.0 + noise * unit(rng));
      data.stress.push_back(s);
      data.displacement.push_back(s * test.height / test.modulus + test.joints * u);
      data.lines.push_back(i + 2);
    }
    const NormalCalibration cal = calibrate_normal(data, test);
    sum_a += cal.exponential.a;
    sum2_a += cal.exponential.a * cal.exponential.a;
    sum_b += cal.exponential.b;
    sum2_b += cal.exponential.b * cal.exponential.b;
    se_a += cal.a_standard_error;
    se_b += cal.b_standard_error;
    EXPECT_LT(cal.a_lower95, cal.exponential.a);
    EXPECT_GT(cal.a_upper95, cal.exponential.a);
    covered_a += (cal.a_lower95 <= a && a <= cal.a_upper95) ? 1 : 0;
    covered_b += (cal.b_lower95 <= b && b <= cal.b_upper95) ? 1 : 0;
  }
  const double n = trials;
  const double spread_a = std::sqrt((sum2_a - sum_a * sum_a / n) / (n - 1));
  const double spread_b = std::sqrt((sum2_b - sum_b * sum_b / n) / (n - 1));
  EXPECT_NEAR(se_a / n / spread_a, 1.0, 0.15);
  EXPECT_NEAR(se_b / n / spread_b, 1.0, 0.15);
  EXPECT_GE(covered_a, 181);
  EXPECT_LE(covered_a, 199);
  EXPECT_GE(covered_b, 181);
  EXPECT_LE(covered_b, 199);
}

// y = C sigma^D with scatter, fitted in logs: a straight line ln y = ln y_ref + D ln(sigma /
// sigma_ref). Closed form of simple linear regression: se(D) = s / sqrt(sum (x_i - mean x)^2),
// s^2 = sum r_i^2 / (n - 2), x = ln sigma; the 95% interval is D +- t(0.975, n - 2) se(D) with
// t(3) = 3.182. Tolerance 1e-10 relative (round-off).
TEST(PowerLawUncertainty, ExponentIntervalIsLinearRegressionClosedForm) {
  const std::vector<double> stress = {1e5, 2e5, 4e5, 8e5, 1.6e6};
  const std::vector<double> scatter = {0.03, -0.02, 0.01, -0.04, 0.02};
  std::vector<double> value;
  for (std::size_t i = 0; i < stress.size(); ++i)
    value.push_back(2e-3 * std::pow(stress[i], 0.4) * std::exp(scatter[i]));
  const PowerLawFit fit = fit_power_law(stress, value, "test");
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < stress.size(); ++i) {
    mx += std::log(stress[i]) / 5;
    my += std::log(value[i]) / 5;
  }
  double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < stress.size(); ++i) {
    sxx += std::pow(std::log(stress[i]) - mx, 2);
    sxy += (std::log(stress[i]) - mx) * (std::log(value[i]) - my);
  }
  const double slope = sxy / sxx;
  double ss = 0;
  for (std::size_t i = 0; i < stress.size(); ++i) {
    ss += std::pow(std::log(value[i]) - my - slope * (std::log(stress[i]) - mx), 2);
  }
  const double se = std::sqrt(ss / 3) / std::sqrt(sxx);
  EXPECT_NEAR(fit.exponent, slope, 1e-10 * slope);
  EXPECT_NEAR(fit.exponent_standard_error, se, 1e-10 * se);
  EXPECT_NEAR(fit.exponent_upper95 - fit.exponent, 3.182 * se, 1e-10 * se);
  EXPECT_NEAR(fit.exponent - fit.exponent_lower95, 3.182 * se, 1e-10 * se);
  // ln y_ref = mean of ln y, se = s / sqrt(n).
  EXPECT_NEAR(std::log(fit.reference_value_upper95), my + 3.182 * std::sqrt(ss / 3 / 5), 1e-10);
}

}  // namespace
}  // namespace blockdem
