// Our Levenberg-Marquardt (numerics/least_squares.hpp) against Eigen's own, the MINPACK port in
// Eigen's unsupported NonLinearOptimization module (libeigen3-dev), used here as an oracle.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <unsupported/Eigen/NonLinearOptimization>

#include "blockdem/numerics/least_squares.hpp"

namespace blockdem {
namespace {

// Adapts a LeastSquaresModel to Eigen's functor interface.
struct EigenFunctor {
  const LeastSquaresModel* model = nullptr;
  int m = 0;
  int values() const { return m; }
  int operator()(const Eigen::VectorXd& x, Eigen::VectorXd& f) const {
    f = model->residuals(x);
    return 0;
  }
  int df(const Eigen::VectorXd& x, Eigen::MatrixXd& j) const {
    j = model->jacobian(x);
    return 0;
  }
};

Eigen::VectorXd eigen_minimum(const LeastSquaresModel& model, int m, Eigen::VectorXd x) {
  EigenFunctor f{&model, m};
  Eigen::LevenbergMarquardt<EigenFunctor> lm(f);
  lm.parameters.xtol = 1e-14;
  lm.parameters.ftol = 1e-14;
  lm.parameters.maxfev = 2000;
  const auto status = lm.minimize(x);
  EXPECT_GT(static_cast<int>(status), 0) << "Eigen's LM failed";
  EXPECT_LT(static_cast<int>(status), 5) << "Eigen's LM stopped on its limit";
  return x;
}

// Rosenbrock's valley as residuals r = (10 (p1 - p0²), 1 - p0) from (-1.2, 1) (Moré, Garbow &
// Hillstrom 1981, problem 1): both solvers must find the minimum (1, 1); tolerance 1e-10.
TEST(EigenLevenbergMarquardtOracle, RosenbrockSameMinimum) {
  LeastSquaresModel model;
  model.residuals = [](const Eigen::VectorXd& p) -> Eigen::VectorXd {
    return Eigen::Vector2d(10 * (p(1) - p(0) * p(0)), 1 - p(0));
  };
  model.jacobian = [](const Eigen::VectorXd& p) -> Eigen::MatrixXd {
    return (Eigen::Matrix2d() << -20 * p(0), 10, -1, 0).finished();
  };
  const Eigen::Vector2d start(-1.2, 1.0);
  const auto ours = levenberg_marquardt(model, start);
  ASSERT_TRUE(ours.converged());
  const Eigen::VectorXd theirs = eigen_minimum(model, 2, start);
  EXPECT_LT((ours.parameters - Eigen::Vector2d(1, 1)).norm(), 1e-10);
  EXPECT_LT((theirs - Eigen::Vector2d(1, 1)).norm(), 1e-10);
}

// A noisy exponential y = a exp(b x) + e (a = 2, b = 1.5, σ = 0.05, 20 points, fixed seed), the
// shape of the calibration fits: both solvers reach the same least-squares optimum; tolerance
// 1e-8 relative on the parameters (the optimum is well conditioned).
TEST(EigenLevenbergMarquardtOracle, NoisyExponentialSameOptimum) {
  const int m = 20;
  Eigen::VectorXd x(m), y(m);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.05);
  for (int i = 0; i < m; ++i) {
    x(i) = static_cast<double>(i) / (m - 1);
    y(i) = 2.0 * std::exp(1.5 * x(i)) + noise(rng);
  }
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
  const Eigen::Vector2d start(1.0, 1.0);
  const auto ours = levenberg_marquardt(model, start);
  ASSERT_TRUE(ours.converged());
  const Eigen::VectorXd theirs = eigen_minimum(model, m, start);
  EXPECT_LT((ours.parameters - theirs).norm(), 1e-8 * theirs.norm());
}

}  // namespace
}  // namespace blockdem
