// Tests of the QR linear least squares and the Levenberg-Marquardt solver against exact data,
// the normal-equations optimality condition and classic test problems.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "blockdem/numerics/least_squares.hpp"

namespace blockdem {
namespace {

// The exponential normal law of the paper, sigma = a [exp(b u) - 1] (eq. 3: a = k0 / c with
// k0 = 4e9 Pa/m, c = 7.4e4 1/m; b = c). The calibration module fits exactly this by LM.
LeastSquaresModel exponential_law_model(const Eigen::VectorXd& u, const Eigen::VectorXd& sigma) {
  LeastSquaresModel model;
  model.residuals = [u, sigma](const Eigen::VectorXd& p) -> Eigen::VectorXd {
    return (p(0) * ((p(1) * u.array()).exp() - 1.0) - sigma.array()).matrix();
  };
  model.jacobian = [u](const Eigen::VectorXd& p) -> Eigen::MatrixXd {
    Eigen::MatrixXd jac(u.size(), 2);
    jac.col(0) = ((p(1) * u.array()).exp() - 1.0).matrix();
    jac.col(1) = (p(0) * u.array() * (p(1) * u.array()).exp()).matrix();
    return jac;
  };
  return model;
}

TEST(LinearLeastSquares, RecoversExactLineAndSatisfiesNormalEquations) {
  // Exact data on y = 2 + 3 x: the solution is exact and the residual vanishes.
  Eigen::MatrixXd a(5, 2);
  Eigen::VectorXd y(5);
  for (int i = 0; i < 5; ++i) {
    a(i, 0) = 1.0;
    a(i, 1) = 0.5 * i;
    y(i) = 2.0 + 3.0 * a(i, 1);
  }
  const LinearLeastSquaresSolution exact = solve_linear_least_squares(a, y);
  EXPECT_NEAR(exact.parameters(0), 2.0, 1e-14);
  EXPECT_NEAR(exact.parameters(1), 3.0, 1e-14);
  EXPECT_LT(exact.rms_residual, 1e-14);

  // Perturbed data: the least-squares residual is orthogonal to the columns, A^T r = 0.
  const Eigen::VectorXd perturbation =
      (Eigen::VectorXd(5) << 0.1, -0.3, 0.2, 0.05, -0.1).finished();
  const LinearLeastSquaresSolution fit = solve_linear_least_squares(a, y + perturbation);
  EXPECT_LT((a.transpose() * fit.residuals).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_GT(fit.rms_residual, 0.01);
  EXPECT_NEAR(fit.rms_residual, std::sqrt(fit.residuals.squaredNorm() / 5.0), 1e-15);
}

TEST(LinearLeastSquares, RejectsBadProblemsWithClearErrors) {
  Eigen::MatrixXd rank_deficient(4, 2);
  rank_deficient << 1, 2, 2, 4, 3, 6, 4, 8;  // second column = 2 x first
  const Eigen::VectorXd y = Eigen::VectorXd::Ones(4);
  EXPECT_THROW(solve_linear_least_squares(rank_deficient, y), std::invalid_argument);
  try {
    solve_linear_least_squares(rank_deficient, y);
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("rank deficient"), std::string::npos);
  }
  EXPECT_THROW(solve_linear_least_squares(Eigen::MatrixXd::Ones(1, 2), Eigen::VectorXd::Ones(1)),
               std::invalid_argument);
  EXPECT_THROW(
      solve_linear_least_squares(Eigen::MatrixXd::Identity(3, 2), Eigen::VectorXd::Ones(2)),
      std::invalid_argument);
  Eigen::VectorXd with_nan = Eigen::VectorXd::Ones(3);
  with_nan(1) = std::nan("");
  EXPECT_THROW(solve_linear_least_squares(Eigen::MatrixXd::Identity(3, 2), with_nan),
               std::invalid_argument);
}

TEST(LevenbergMarquardt, RecoversExponentialJointLawFromExactData) {
  const double a_true = 4e9 / 7.4e4;  // Pa
  const double b_true = 7.4e4;        // 1/m
  Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(12, 0.0, 6e-5);
  Eigen::VectorXd sigma = (a_true * ((b_true * u.array()).exp() - 1.0)).matrix();
  // Start 50 % off in a (Pa) and 30 % off in b (1/m).
  const Eigen::Vector2d start(0.5 * a_true, 1.3 * b_true);
  const LevenbergMarquardtResult result =
      levenberg_marquardt(exponential_law_model(u, sigma), start);
  ASSERT_TRUE(result.converged()) << to_string(result.termination);
  EXPECT_NEAR(result.parameters(0) / a_true, 1.0, 1e-9);
  EXPECT_NEAR(result.parameters(1) / b_true, 1.0, 1e-9);
  EXPECT_LT(result.rms_residual, 1e-9 * sigma.maxCoeff());
}

TEST(LevenbergMarquardt, SolvesRosenbrockFromTheClassicStart) {
  // Rosenbrock's function as least squares: r = (10 (p1 - p0^2), 1 - p0); minimum 0 at (1, 1).
  LeastSquaresModel model;
  model.residuals = [](const Eigen::VectorXd& p) -> Eigen::VectorXd {
    return Eigen::Vector2d(10.0 * (p(1) - p(0) * p(0)), 1.0 - p(0));
  };
  model.jacobian = [](const Eigen::VectorXd& p) -> Eigen::MatrixXd {
    return (Eigen::Matrix2d() << -20.0 * p(0), 10.0, -1.0, 0.0).finished();
  };
  const LevenbergMarquardtResult result = levenberg_marquardt(model, Eigen::Vector2d(-1.2, 1.0));
  ASSERT_TRUE(result.converged()) << to_string(result.termination);
  EXPECT_NEAR(result.parameters(0), 1.0, 1e-9);
  EXPECT_NEAR(result.parameters(1), 1.0, 1e-9);
  EXPECT_GT(result.iterations, 2);  // the curved valley needs real iterations
}

TEST(LevenbergMarquardt, ReportsIterationLimitAndNonFiniteStart) {
  const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(8, 0.0, 6e-5);
  const Eigen::VectorXd sigma = (5e4 * ((7e4 * u.array()).exp() - 1.0)).matrix();
  LevenbergMarquardtOptions options;
  options.max_evaluations = 2;
  const LevenbergMarquardtResult limited =
      levenberg_marquardt(exponential_law_model(u, sigma), Eigen::Vector2d(1e4, 1e4), options);
  EXPECT_FALSE(limited.converged());
  EXPECT_EQ(limited.termination, LevenbergMarquardtTermination::max_evaluations);

  const LevenbergMarquardtResult nan_start =
      levenberg_marquardt(exponential_law_model(u, sigma), Eigen::Vector2d(std::nan(""), 1e4));
  EXPECT_FALSE(nan_start.converged());
  EXPECT_EQ(nan_start.termination, LevenbergMarquardtTermination::non_finite);

  LeastSquaresModel incomplete;
  EXPECT_THROW(levenberg_marquardt(incomplete, Eigen::Vector2d(1, 1)), std::invalid_argument);
  options.max_evaluations = 1;
  EXPECT_THROW(levenberg_marquardt(exponential_law_model(u, sigma), Eigen::Vector2d(1, 1), options),
               std::invalid_argument);
}

TEST(FiniteDifferenceJacobian, MatchesAnalyticJacobian) {
  const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(6, 0.0, 6e-5);
  const Eigen::VectorXd sigma = Eigen::VectorXd::Zero(6);
  const LeastSquaresModel model = exponential_law_model(u, sigma);
  const Eigen::Vector2d p(5.4e4, 7.4e4);
  const Eigen::MatrixXd analytic = model.jacobian(p);
  const Eigen::MatrixXd numeric = finite_difference_jacobian(model.residuals, p, 1e-7);
  EXPECT_LT((analytic - numeric).norm(), 1e-6 * analytic.norm());
}

}  // namespace
}  // namespace blockdem
