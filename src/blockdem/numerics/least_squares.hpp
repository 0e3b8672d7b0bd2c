// Least-squares solvers for curve fits: linear least squares by column-pivoted QR, and
// Levenberg-Marquardt (Eigen's MINPACK port) for nonlinear models given residual and Jacobian.
// Used by the line-of-thrust fits and by the joint-law calibration (exponential, power-law fits).
#pragma once

#include <Eigen/Core>

#include <functional>
#include <string>

namespace blockdem {

/// Solution of the linear least-squares problem min ||A p - b||_2.
struct LinearLeastSquaresSolution {
  Eigen::VectorXd parameters;  ///< p minimising the residual norm (units of b / units of A)
  Eigen::VectorXd residuals;   ///< A p - b (units of b)
  double rms_residual = 0.0;   ///< sqrt(mean(residual^2)) (units of b)
};

/// Solves min ||A p - b|| by column-pivoted Householder QR (never the normal equations, whose
/// condition number is the square of A's). Throws std::invalid_argument naming the problem if A
/// has fewer rows than columns, sizes disagree, an entry is not finite, or A is rank deficient
/// (relative threshold `rank_tolerance` on the pivots of R).
LinearLeastSquaresSolution solve_linear_least_squares(const Eigen::MatrixXd& design_matrix,
                                                      const Eigen::VectorXd& observations,
                                                      double rank_tolerance = 1e-12);

/// A nonlinear least-squares model: residuals r(p) (m values) and their Jacobian dr/dp (m x k).
/// The cost minimised is 0.5 ||r(p)||^2.
struct LeastSquaresModel {
  std::function<Eigen::VectorXd(const Eigen::VectorXd&)> residuals;  ///< r(p), size m
  std::function<Eigen::MatrixXd(const Eigen::VectorXd&)> jacobian;   ///< dr/dp, size m x k
};

/// Options of the Levenberg-Marquardt solver, MINPACK's (More, Garbow & Hillstrom 1980, lmder)
/// under readable names. Defaults suit well-scaled fits of a few parameters: the tolerances sit a
/// few orders above round-off, so a fit stops on them rather than on the machine-precision limit.
struct LevenbergMarquardtOptions {
  int max_evaluations = 1000;         ///< residual evaluations, the start included (maxfev) (-)
  double gradient_tolerance = 1e-12;  ///< stop when max_j |cos(angle(r, J_j))| <= this (gtol) (-)
  double step_tolerance = 1e-12;      ///< stop when the trust region <= this * ||D p|| (xtol) (-)
  double cost_tolerance = 1e-14;      ///< stop when actual and predicted relative decrease of
                                      ///< ||r||^2 are both <= this (ftol) (-)
  double initial_step_bound = 100.0;  ///< first trust region = this * ||D p0|| (factor) (-)

  /// Throws std::invalid_argument naming the first option out of range.
  void validate() const;
};

/// How the Levenberg-Marquardt solver stopped.
enum class LevenbergMarquardtTermination {
  gradient_small,     ///< first-order optimality reached (gtol)
  step_small,         ///< the trust region shrank below step_tolerance (xtol, or xtol and ftol)
  cost_stalled,       ///< the cost no longer decreases by more than cost_tolerance (ftol)
  machine_precision,  ///< a tolerance below round-off: no further progress is possible at the
                      ///< optimum found (MINPACK info 6-8); converged to working precision
  max_evaluations,    ///< evaluation limit hit: NOT converged
  non_finite,         ///< the model returned NaN/Inf at the start or a Jacobian: NOT converged
};

/// Text name of a termination reason, e.g. "gradient_small".
std::string to_string(LevenbergMarquardtTermination termination);

/// Result of a Levenberg-Marquardt run.
struct LevenbergMarquardtResult {
  Eigen::VectorXd parameters;  ///< best parameters found (model units)
  Eigen::VectorXd residuals;   ///< r at the best parameters (residual units)
  double rms_residual = 0.0;   ///< sqrt(||r||^2 / m) (residual units)
  int iterations = 0;          ///< accepted steps (-)
  int evaluations = 0;         ///< residual evaluations, the start included (-)
  LevenbergMarquardtTermination termination = LevenbergMarquardtTermination::max_evaluations;
  /// True unless the evaluation limit was hit or the model was not finite.
  bool converged() const {
    return termination != LevenbergMarquardtTermination::max_evaluations &&
           termination != LevenbergMarquardtTermination::non_finite;
  }
};

/// Minimises 0.5 ||r(p)||^2 from `initial_parameters` by Levenberg-Marquardt (Levenberg 1944,
/// Marquardt 1963) in More's trust-region form (More 1978, "The Levenberg-Marquardt algorithm:
/// implementation and theory"), as implemented by MINPACK's lmder and ported to C++ in Eigen's
/// unsupported NonLinearOptimization module: scaling D by the column norms of J, kept
/// non-decreasing; each step from a QR of J. Throws std::invalid_argument if the model is
/// incomplete, the sizes disagree, or there are fewer residuals than parameters. Does not throw on
/// non-convergence: check `converged()`.
LevenbergMarquardtResult levenberg_marquardt(const LeastSquaresModel& model,
                                             const Eigen::VectorXd& initial_parameters,
                                             const LevenbergMarquardtOptions& options = {});

/// Uncertainty of least-squares parameters from the Jacobian J at the optimum (the linearised
/// model; Seber & Wild, Nonlinear Regression, Wiley 1989, section 2.1.3, eq 2.21): covariance
/// C = s² (JᵀJ)⁻¹ with s² = ||r||² / (m − k), formed from the R factor of a QR of J as
/// R⁻¹ R⁻ᵀ (never JᵀJ itself). The 95% interval of p_j is p_j ± t s_j, t the 0.975 quantile of
/// Student's t with m − k degrees of freedom.
struct ParameterUncertainty {
  Eigen::MatrixXd covariance;        ///< (parameter units squared)
  Eigen::VectorXd standard_errors;   ///< sqrt of the diagonal (parameter units)
  Eigen::VectorXd lower95, upper95;  ///< the 95% intervals (parameter units)
  int degrees_of_freedom = 0;        ///< m − k (-)
};

/// Throws std::invalid_argument when m <= k, sizes disagree or J is rank deficient.
ParameterUncertainty parameter_uncertainty(const Eigen::MatrixXd& jacobian,
                                           const Eigen::VectorXd& residuals,
                                           const Eigen::VectorXd& parameters);

/// The 0.975 quantile of Student's t with `degrees_of_freedom` >= 1: tabulated to 3 decimals up
/// to 30, above by the Cornish-Fisher expansion of Abramowitz & Stegun 26.7.5 (error < 1e-4).
double student_t_975(int degrees_of_freedom);

/// Central-difference Jacobian of `residuals` at `parameters`, step h_j = step * max(1, |p_j|).
/// Meant for checking analytic Jacobians in tests and for quick prototypes.
Eigen::MatrixXd finite_difference_jacobian(
    const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& residuals,
    const Eigen::VectorXd& parameters, double step = 1e-6);

}  // namespace blockdem
