// Parameter standard errors from the Jacobian (numerics/least_squares.hpp) against a Monte-Carlo
// repetition of synthetic data with known parameters and noise.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <random>

#include "blockdem/numerics/least_squares.hpp"

namespace blockdem {
namespace {

// y = a exp(b x) + e, e ~ N(0, sigma²), 20 points on [0, 1], a = 2, b = 1.5, sigma = 0.05,
// fitted by Levenberg-Marquardt 400 times with fresh noise (fixed seed). References:
// - the spread of the fitted parameters over the repetitions is what the Jacobian's standard
//   error predicts (linearised model, Seber & Wild 1989, section 2.1.3): their ratio within
//   10% (the sample standard deviation of 400 draws is itself uncertain by 1/sqrt(800) = 3.5%,
//   the linearisation adds a little);
// - the 95% intervals cover the true value in 95% of the repetitions: between 91.5% and 98.5%
//   (three binomial standard deviations of 400 trials, 1.1% each).
TEST(ParameterUncertainty, StandardErrorsMatchMonteCarloSpreadAndIntervalsCover) {
  const double a = 2.0, b = 1.5, sigma = 0.05;
  const int m = 20, trials = 400;
  Eigen::VectorXd x(m);
  for (int i = 0; i < m; ++i) x(i) = static_cast<double>(i) / (m - 1);
  std::mt19937 rng(12345);
  std::normal_distribution<double> noise(0.0, sigma);
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(2), sum2 = Eigen::VectorXd::Zero(2);
  Eigen::VectorXd se_sum = Eigen::VectorXd::Zero(2);
  int covered_a = 0, covered_b = 0;
  for (int t = 0; t < trials; ++t) {
    Eigen::VectorXd y(m);
    for (int i = 0; i < m; ++i) y(i) = a * std::exp(b * x(i)) + noise(rng);
    LeastSquaresModel model;
    model.residuals = [&](const Eigen::VectorXd& p) -> Eigen::VectorXd {
      return (p(0) * (p(1) * x.array()).exp() - y.array()).matrix();
    };
    model.jacobian = [&](const Eigen::VectorXd& p) -> Eigen::MatrixXd {
      Eigen::MatrixXd j(m, 2);
      j.col(0) = (p(1) * x.array()).exp().matrix();
      j.col(1) = (p(0) * x.array() * (p(1) * x.array()).exp()).matrix();
      return j;
    };
    const auto fit = levenberg_marquardt(model, Eigen::Vector2d(1.0, 1.0));
    ASSERT_TRUE(fit.converged());
    const ParameterUncertainty u =
        parameter_uncertainty(model.jacobian(fit.parameters), fit.residuals, fit.parameters);
    EXPECT_EQ(u.degrees_of_freedom, m - 2);
    sum += fit.parameters;
    sum2 += fit.parameters.cwiseProduct(fit.parameters);
    se_sum += u.standard_errors;
    covered_a += (u.lower95(0) <= a && a <= u.upper95(0)) ? 1 : 0;
    covered_b += (u.lower95(1) <= b && b <= u.upper95(1)) ? 1 : 0;
  }
  const Eigen::VectorXd mean = sum / trials;
  const Eigen::VectorXd spread =
      ((sum2 - trials * mean.cwiseProduct(mean)) / (trials - 1)).cwiseSqrt();
  const Eigen::VectorXd predicted = se_sum / trials;
  for (int j = 0; j < 2; ++j) {
    EXPECT_NEAR(predicted(j) / spread(j), 1.0, 0.10) << "parameter " << j;
  }
  EXPECT_NEAR(mean(0), a, 3 * spread(0) / std::sqrt(trials));
  EXPECT_NEAR(mean(1), b, 3 * spread(1) / std::sqrt(trials));
  EXPECT_GE(covered_a, static_cast<int>(0.915 * trials));
  EXPECT_LE(covered_a, static_cast<int>(0.985 * trials));
  EXPECT_GE(covered_b, static_cast<int>(0.915 * trials));
  EXPECT_LE(covered_b, static_cast<int>(0.985 * trials));
}

// A straight line y = p0 + p1 x: the covariance is s² (XᵀX)⁻¹ in closed form (Seber & Wild,
// eq 2.21 for a linear model); tolerance round-off (1e-12 relative).
TEST(ParameterUncertainty, LinearModelCovarianceIsClosedForm) {
  Eigen::MatrixXd X(5, 2);
  X << 1, 0, 1, 1, 1, 2, 1, 3, 1, 5;
  const Eigen::VectorXd r = (Eigen::VectorXd(5) << 0.1, -0.2, 0.05, 0.15, -0.1).finished();
  const ParameterUncertainty u = parameter_uncertainty(X, r, Eigen::Vector2d(1.0, 2.0));
  const Eigen::Matrix2d expected = r.squaredNorm() / 3.0 * (X.transpose() * X).inverse();
  EXPECT_LT((u.covariance - expected).norm(), 1e-12 * expected.norm());
  EXPECT_NEAR(u.upper95(1) - 2.0, 3.182 * std::sqrt(expected(1, 1)), 1e-12);
}

// Student's t quantile: the table and the expansion agree where they meet (t(30) = 2.042), and
// the expansion tends to the normal quantile 1.95996.
TEST(ParameterUncertainty, StudentQuantile) {
  EXPECT_NEAR(student_t_975(31), 2.0395, 5e-4);
  EXPECT_NEAR(student_t_975(60), 2.0003, 5e-4);
  EXPECT_NEAR(student_t_975(100000), 1.95996, 1e-4);
  EXPECT_THROW(student_t_975(0), std::invalid_argument);
}

}  // namespace
}  // namespace blockdem
