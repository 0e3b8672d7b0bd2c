// Tests of the line-of-thrust fits: exact curves recovered, noise level reproduced by the RMS,
// implied thrusts against statics (H z = W S / 8) and the catenary's H = q a, degenerate input.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "blockdem/analysis/thrust_line_fit.hpp"

namespace blockdem {
namespace {

constexpr double kSpan = 0.276;  // m, the paper's full-block beam (6 x 46 mm)

// Thrust points at the seven joints of the paper's six-block beam, x = 0, 46, ..., 276 mm.
Eigen::VectorXd joint_abscissae() {
  return Eigen::VectorXd::LinSpaced(7, 0.0, kSpan);
}

Eigen::VectorXd catenary_points(const Eigen::VectorXd& x, double y0, double x0, double a) {
  Eigen::VectorXd y(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) y(i) = y0 - a * (std::cosh((x(i) - x0) / a) - 1.0);
  return y;
}

Eigen::VectorXd gaussian_noise(Eigen::Index n, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  Eigen::VectorXd noise(n);
  for (Eigen::Index i = 0; i < n; ++i) noise(i) = normal(rng);
  return noise;
}

TEST(ParabolaFit, RecoversExactParabola) {
  const double c0 = 0.004, c1 = 0.3, c2 = -1.1;
  const Eigen::VectorXd x = joint_abscissae();
  const Eigen::VectorXd y = (c0 + c1 * x.array() + c2 * x.array().square()).matrix();
  const ParabolaFit fit = fit_parabola(x, y);
  EXPECT_NEAR(fit.c0 / c0, 1.0, 1e-9);
  EXPECT_NEAR(fit.c1 / c1, 1.0, 1e-9);
  EXPECT_NEAR(fit.c2 / c2, 1.0, 1e-9);
  EXPECT_LT(fit.rms_residual, 1e-15);
  EXPECT_TRUE(fit.curvature_resolved);
  EXPECT_NEAR(fit.vertex_x(), -c1 / (2.0 * c2), 1e-12);
}

TEST(ParabolaFit, RmsResidualMatchesNoiseLevel) {
  // 400 points with Gaussian noise sigma: the RMS residual of a 3-parameter fit estimates
  // sigma sqrt((N - 3) / N); its sampling spread is sigma / sqrt(2N) = 3.5 % here.
  const double sigma = 1e-4;  // m
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(400, 0.0, kSpan);
  const Eigen::VectorXd clean = (0.01 + 0.2 * x.array() - 0.8 * x.array().square()).matrix();
  const ParabolaFit fit = fit_parabola(x, clean + gaussian_noise(400, sigma, 12345u));
  EXPECT_NEAR(fit.rms_residual / sigma, 1.0, 0.15);
  // c2 stays near the truth: its standard error is sigma sqrt(180 / N) / dx^2 = 8.8e-4 1/m.
  EXPECT_NEAR(fit.c2, -0.8, 0.006);
}

TEST(CatenaryFit, RecoversExactCatenaryFromParabolaGuess) {
  const double y0 = 0.03, x0 = 0.138, a = 0.8;  // m
  const Eigen::VectorXd x = joint_abscissae();
  const Eigen::VectorXd y = catenary_points(x, y0, x0, a);
  // The parabola's guess differs from the truth, so Levenberg-Marquardt has work to do.
  const CatenaryFit guess = catenary_guess_from_parabola(fit_parabola(x, y));
  EXPECT_GT(std::abs(guess.a / a - 1.0), 1e-4);

  const CatenaryFit fit = fit_catenary(x, y);
  EXPECT_NEAR(fit.y0 / y0, 1.0, 1e-7);
  EXPECT_NEAR(fit.x0 / x0, 1.0, 1e-7);
  EXPECT_NEAR(fit.a / a, 1.0, 1e-7);
  EXPECT_LT(fit.rms_residual, 1e-12);
  EXPECT_GT(fit.iterations, 0);
}

TEST(CatenaryFit, ConvergesFromParabolaGuessForStrongCurvatureAndOffCentreVertex) {
  // a = 0.15 m on a 0.276 m span: (x - x0)/a reaches 1.2, where cosh departs far from a parabola.
  const double y0 = -0.02, x0 = 0.1, a = 0.15;
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(15, 0.0, kSpan);
  const Eigen::VectorXd y = catenary_points(x, y0, x0, a);
  const CatenaryFit guess = catenary_guess_from_parabola(fit_parabola(x, y));
  EXPECT_GT(std::abs(guess.a / a - 1.0), 1e-2);
  const CatenaryFit fit = fit_catenary(x, y);
  EXPECT_NEAR(fit.a / a, 1.0, 1e-7);
  EXPECT_NEAR(fit.x0 / x0, 1.0, 1e-7);
  EXPECT_NEAR(fit.y0 / y0, 1.0, 1e-7);
}

TEST(CatenaryFit, HangingChainHasNegativeParameter) {
  const Eigen::VectorXd x = joint_abscissae();
  const Eigen::VectorXd y = catenary_points(x, 0.0, 0.138, -0.5);
  const CatenaryFit fit = fit_catenary(x, y);
  EXPECT_NEAR(fit.a / -0.5, 1.0, 1e-7);
  EXPECT_NEAR(catenary_implied_thrust(fit, 10.0), 5.0, 5e-7);
}

TEST(CatenaryFit, RmsResidualMatchesNoiseLevel) {
  const double sigma = 5e-5;  // m
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(400, 0.0, kSpan);
  const Eigen::VectorXd y = catenary_points(x, 0.03, 0.138, 0.3) + gaussian_noise(400, sigma, 777u);
  const CatenaryFit fit = fit_catenary(x, y);
  EXPECT_NEAR(fit.rms_residual / sigma, 1.0, 0.15);
  EXPECT_NEAR(fit.a, 0.3, 0.01);
}

TEST(ThrustLineFit, ParabolaThrustSatisfiesHalfSpanStatics) {
  // Thrust line through the abutment points (0, 0), (S, 0) with rise z at midspan: statics of
  // the half span give H z = W S / 8, with W = w S.
  const double z = 0.03;                                               // m
  const double weight = 40.0 * 9.81 * 1207.0 * kSpan * 0.046 * 0.046;  // W at 40 g (N)
  const double w = weight / kSpan;                                     // N/m
  const Eigen::VectorXd x = joint_abscissae();
  const Eigen::VectorXd y = (4.0 * z * x.array() * (kSpan - x.array()) / (kSpan * kSpan)).matrix();
  const ParabolaFit fit = fit_parabola(x, y);
  EXPECT_NEAR(parabola_implied_thrust(fit, w) / (weight * kSpan / (8.0 * z)), 1.0, 1e-9);
}

TEST(ThrustLineFit, CatenaryThrustIsLoadTimesParameterAndParabolaAgreesForShallowLines) {
  // A chain of weight q per arc length with horizontal tension H hangs as a catenary a = H / q.
  const double q = 120.0;       // N/m
  const double thrust = 600.0;  // N -> a = 5 m
  const Eigen::VectorXd x = joint_abscissae();
  const Eigen::VectorXd y = catenary_points(x, 0.02, 0.5 * kSpan, thrust / q);
  const ThrustLineFit fit = fit_thrust_line(x, y, q);
  EXPECT_NEAR(fit.catenary_thrust / thrust, 1.0, 1e-7);
  // Shallow line: slopes |y'| = |sinh(u)| <= 0.028, so the parabola's thrust differs from the
  // catenary's by O(y'^2), here below the square of the largest slope.
  const double max_slope = std::sinh(0.5 * kSpan / (thrust / q));
  const double relative_difference = std::abs(fit.parabola_thrust / fit.catenary_thrust - 1.0);
  EXPECT_LT(relative_difference, max_slope * max_slope);
  EXPECT_GT(relative_difference, 0.0);
}

TEST(ThrustLineFit, RejectsDegenerateInput) {
  const Eigen::VectorXd two = Eigen::VectorXd::LinSpaced(2, 0.0, 1.0);
  EXPECT_THROW(fit_parabola(two, two), std::invalid_argument);
  EXPECT_THROW(fit_catenary(two, two), std::invalid_argument);

  // Four points on only two distinct abscissae cannot fix a parabola.
  const Eigen::VectorXd x_dup = (Eigen::VectorXd(4) << 0.0, 0.0, 1.0, 1.0).finished();
  const Eigen::VectorXd y_dup = (Eigen::VectorXd(4) << 0.0, 0.1, 0.2, 0.3).finished();
  EXPECT_THROW(fit_parabola(x_dup, y_dup), std::invalid_argument);

  EXPECT_THROW(fit_parabola(joint_abscissae(), Eigen::VectorXd::Zero(6)), std::invalid_argument);
  Eigen::VectorXd y_nan = Eigen::VectorXd::Zero(7);
  y_nan(3) = std::nan("");
  EXPECT_THROW(fit_parabola(joint_abscissae(), y_nan), std::invalid_argument);
  EXPECT_THROW(
      fit_thrust_line(joint_abscissae(), catenary_points(joint_abscissae(), 0, 0.1, 1), -1.0),
      std::invalid_argument);
}

TEST(ThrustLineFit, CollinearPointsFailClearly) {
  const Eigen::VectorXd x = joint_abscissae();
  const Eigen::VectorXd y = (0.01 + 0.05 * x.array()).matrix();
  const ParabolaFit parabola = fit_parabola(x, y);
  EXPECT_FALSE(parabola.curvature_resolved);
  EXPECT_LT(parabola.rms_residual, 1e-15);
  EXPECT_THROW(parabola_implied_thrust(parabola, 1.0), std::domain_error);
  EXPECT_THROW(parabola.vertex_x(), std::domain_error);
  EXPECT_THROW(fit_catenary(x, y), std::domain_error);
  try {
    fit_catenary(x, y);
  } catch (const std::domain_error& e) {
    EXPECT_NE(std::string(e.what()).find("collinear"), std::string::npos);
  }
}

}  // namespace
}  // namespace blockdem
