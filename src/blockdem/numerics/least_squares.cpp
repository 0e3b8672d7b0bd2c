// Linear least squares by column-pivoted QR, and Levenberg-Marquardt through Eigen's MINPACK port
// (see the header for the method and its sources).
#include "blockdem/numerics/least_squares.hpp"

#include <Eigen/QR>
#include <unsupported/Eigen/NonLinearOptimization>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace blockdem {
namespace {

double rms(const Eigen::VectorXd& r) {
  return r.size() == 0 ? 0.0 : std::sqrt(r.squaredNorm() / static_cast<double>(r.size()));
}

}  // namespace

LinearLeastSquaresSolution solve_linear_least_squares(const Eigen::MatrixXd& design_matrix,
                                                      const Eigen::VectorXd& observations,
                                                      double rank_tolerance) {
  const Eigen::Index rows = design_matrix.rows();
  const Eigen::Index cols = design_matrix.cols();
  if (cols == 0) throw std::invalid_argument("linear least squares: design matrix has no columns");
  if (observations.size() != rows) {
    std::ostringstream msg;
    msg << "linear least squares: design matrix has " << rows << " rows but there are "
        << observations.size() << " observations";
    throw std::invalid_argument(msg.str());
  }
  if (rows < cols) {
    std::ostringstream msg;
    msg << "linear least squares: " << rows << " observations cannot determine " << cols
        << " parameters";
    throw std::invalid_argument(msg.str());
  }
  if (!design_matrix.allFinite() || !observations.allFinite()) {
    throw std::invalid_argument("linear least squares: input contains NaN or Inf");
  }
  if (!(rank_tolerance > 0.0 && rank_tolerance < 1.0)) {
    throw std::invalid_argument("linear least squares: rank_tolerance must lie in (0, 1)");
  }

  // Column-pivoted Householder QR; the rank is judged on |R_ii| relative to |R_00|.
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(design_matrix);
  qr.setThreshold(rank_tolerance);
  if (qr.rank() < cols) {
    std::ostringstream msg;
    msg << "linear least squares: design matrix is rank deficient (rank " << qr.rank() << " < "
        << cols << " parameters); the data cannot determine every parameter";
    throw std::invalid_argument(msg.str());
  }

  LinearLeastSquaresSolution solution;
  solution.parameters = qr.solve(observations);
  solution.residuals = design_matrix * solution.parameters - observations;
  solution.rms_residual = rms(solution.residuals);
  return solution;
}

void LevenbergMarquardtOptions::validate() const {
  if (max_evaluations < 2) {
    throw std::invalid_argument("LevenbergMarquardtOptions.max_evaluations must be >= 2");
  }
  if (!(gradient_tolerance >= 0.0)) {
    throw std::invalid_argument("LevenbergMarquardtOptions.gradient_tolerance must be >= 0");
  }
  if (!(step_tolerance >= 0.0)) {
    throw std::invalid_argument("LevenbergMarquardtOptions.step_tolerance must be >= 0");
  }
  if (!(cost_tolerance >= 0.0)) {
    throw std::invalid_argument("LevenbergMarquardtOptions.cost_tolerance must be >= 0");
  }
  if (!(initial_step_bound > 0.0 && std::isfinite(initial_step_bound))) {
    throw std::invalid_argument(
        "LevenbergMarquardtOptions.initial_step_bound must be positive and finite");
  }
}

std::string to_string(LevenbergMarquardtTermination termination) {
  switch (termination) {
    case LevenbergMarquardtTermination::gradient_small:
      return "gradient_small";
    case LevenbergMarquardtTermination::step_small:
      return "step_small";
    case LevenbergMarquardtTermination::cost_stalled:
      return "cost_stalled";
    case LevenbergMarquardtTermination::machine_precision:
      return "machine_precision";
    case LevenbergMarquardtTermination::max_evaluations:
      return "max_evaluations";
    case LevenbergMarquardtTermination::non_finite:
      return "non_finite";
  }
  throw std::logic_error("unknown LevenbergMarquardtTermination value");
}

namespace {

// A LeastSquaresModel in the functor form Eigen's LevenbergMarquardt calls. A Jacobian that is
// not finite stops the run (a negative return is MINPACK's "user asked"); a trial point whose
// residuals are not finite needs nothing: its actual reduction compares false and the step is
// rejected, shrinking the trust region.
struct EigenFunctor {
  const LeastSquaresModel* model = nullptr;
  Eigen::Index m = 0;
  bool jacobian_not_finite = false;
  Eigen::Index values() const { return m; }
  int operator()(const Eigen::VectorXd& p, Eigen::VectorXd& r) const {
    r = model->residuals(p);
    return r.size() == m ? 0 : -1;
  }
  int df(const Eigen::VectorXd& p, Eigen::MatrixXd& jac) {
    jac = model->jacobian(p);
    jacobian_not_finite = !jac.allFinite();
    return jacobian_not_finite ? -1 : 0;
  }
};

LevenbergMarquardtTermination termination_of(Eigen::LevenbergMarquardtSpace::Status status) {
  using Status = Eigen::LevenbergMarquardtSpace::Status;
  switch (status) {
    case Status::CosinusTooSmall:
      return LevenbergMarquardtTermination::gradient_small;
    case Status::RelativeErrorTooSmall:
    case Status::RelativeErrorAndReductionTooSmall:
      return LevenbergMarquardtTermination::step_small;
    case Status::RelativeReductionTooSmall:
      return LevenbergMarquardtTermination::cost_stalled;
    case Status::FtolTooSmall:
    case Status::XtolTooSmall:
    case Status::GtolTooSmall:
      return LevenbergMarquardtTermination::machine_precision;
    case Status::TooManyFunctionEvaluation:
      return LevenbergMarquardtTermination::max_evaluations;
    case Status::UserAsked:
      return LevenbergMarquardtTermination::non_finite;
    default:
      break;
  }
  throw std::logic_error("levenberg_marquardt: Eigen returned status " +
                         std::to_string(static_cast<int>(status)));
}

}  // namespace

LevenbergMarquardtResult levenberg_marquardt(const LeastSquaresModel& model,
                                             const Eigen::VectorXd& initial_parameters,
                                             const LevenbergMarquardtOptions& options) {
  options.validate();
  if (!model.residuals || !model.jacobian) {
    throw std::invalid_argument("levenberg_marquardt: the model needs residuals and jacobian");
  }
  const Eigen::Index k = initial_parameters.size();
  if (k == 0) throw std::invalid_argument("levenberg_marquardt: no parameters to fit");

  LevenbergMarquardtResult result;
  result.parameters = initial_parameters;
  result.residuals = model.residuals(result.parameters);
  result.evaluations = 1;
  const Eigen::Index m = result.residuals.size();
  if (m < k) {
    std::ostringstream msg;
    msg << "levenberg_marquardt: " << m << " residuals cannot determine " << k << " parameters";
    throw std::invalid_argument(msg.str());
  }
  const Eigen::MatrixXd jac = model.jacobian(result.parameters);
  if (jac.rows() != m || jac.cols() != k) {
    std::ostringstream msg;
    msg << "levenberg_marquardt: jacobian is " << jac.rows() << " x " << jac.cols() << ", expected "
        << m << " x " << k;
    throw std::invalid_argument(msg.str());
  }
  if (!result.residuals.allFinite() || !jac.allFinite() || !initial_parameters.allFinite()) {
    result.rms_residual = rms(result.residuals);
    result.termination = LevenbergMarquardtTermination::non_finite;
    return result;
  }
  // An exact fit at the start: nothing to do (MINPACK would divide by ||r|| = 0).
  if (result.residuals.squaredNorm() == 0.0) {
    result.termination = LevenbergMarquardtTermination::gradient_small;
    return result;
  }

  EigenFunctor functor{&model, m};
  Eigen::LevenbergMarquardt<EigenFunctor> lm(functor);
  lm.parameters.maxfev = options.max_evaluations;
  lm.parameters.gtol = options.gradient_tolerance;
  lm.parameters.xtol = options.step_tolerance;
  lm.parameters.ftol = options.cost_tolerance;
  lm.parameters.factor = options.initial_step_bound;
  Eigen::VectorXd p = initial_parameters;
  const auto status = lm.minimize(p);
  result.termination = termination_of(status);
  // Eigen's `iter` starts at 1 and counts accepted steps; fvec holds r at the returned p.
  result.iterations = static_cast<int>(lm.iter - 1);
  result.evaluations = static_cast<int>(lm.nfev);
  result.parameters = p;
  result.residuals = lm.fvec;
  result.rms_residual = rms(result.residuals);
  return result;
}

double student_t_975(int dof) {
  if (dof < 1) throw std::invalid_argument("student_t_975: degrees of freedom must be >= 1");
  static constexpr double kTable[30] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306,
                                        2.262,  2.228, 2.201, 2.179, 2.160, 2.145, 2.131, 2.120,
                                        2.110,  2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064,
                                        2.060,  2.056, 2.052, 2.048, 2.045, 2.042};
  if (dof <= 30) return kTable[dof - 1];
  // A&S 26.7.5 with x the normal 0.975 quantile.
  const double x = 1.959963984540054, n = dof;
  const double x2 = x * x;
  const double g1 = (x2 + 1) * x / 4;
  const double g2 = ((5 * x2 + 16) * x2 + 3) * x / 96;
  const double g3 = (((3 * x2 + 19) * x2 + 17) * x2 - 15) * x / 384;
  const double g4 = ((((79 * x2 + 776) * x2 + 1482) * x2 - 1920) * x2 - 945) * x / 92160;
  return x + g1 / n + g2 / (n * n) + g3 / (n * n * n) + g4 / (n * n * n * n);
}

ParameterUncertainty parameter_uncertainty(const Eigen::MatrixXd& jacobian,
                                           const Eigen::VectorXd& residuals,
                                           const Eigen::VectorXd& parameters) {
  const Eigen::Index m = jacobian.rows(), k = jacobian.cols();
  if (residuals.size() != m || parameters.size() != k)
    throw std::invalid_argument("parameter_uncertainty: sizes of J, r and p disagree");
  if (m <= k)
    throw std::invalid_argument("parameter_uncertainty: needs more residuals than parameters");
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(jacobian);
  if (qr.rank() < k) throw std::invalid_argument("parameter_uncertainty: J is rank deficient");
  // JᵀJ = P Rᵀ R Pᵀ, so (JᵀJ)⁻¹ = P R⁻¹ R⁻ᵀ Pᵀ.
  const Eigen::MatrixXd r = qr.matrixR().topLeftCorner(k, k).triangularView<Eigen::Upper>();
  const Eigen::MatrixXd r_inv =
      r.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(k, k));
  const Eigen::MatrixXd inner = r_inv * r_inv.transpose();
  const auto& perm = qr.colsPermutation();
  ParameterUncertainty u;
  u.degrees_of_freedom = static_cast<int>(m - k);
  const double s2 = residuals.squaredNorm() / static_cast<double>(u.degrees_of_freedom);
  u.covariance = s2 * (perm * inner * perm.transpose());
  u.standard_errors = u.covariance.diagonal().cwiseSqrt();
  const double t = student_t_975(u.degrees_of_freedom);
  u.lower95 = parameters - t * u.standard_errors;
  u.upper95 = parameters + t * u.standard_errors;
  return u;
}

Eigen::MatrixXd finite_difference_jacobian(
    const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& residuals,
    const Eigen::VectorXd& parameters, double step) {
  if (!(step > 0.0)) throw std::invalid_argument("finite_difference_jacobian: step must be > 0");
  const Eigen::VectorXd r0 = residuals(parameters);
  Eigen::MatrixXd jac(r0.size(), parameters.size());
  for (Eigen::Index j = 0; j < parameters.size(); ++j) {
    const double h = step * std::max(1.0, std::abs(parameters(j)));
    Eigen::VectorXd plus = parameters;
    Eigen::VectorXd minus = parameters;
    plus(j) += h;
    minus(j) -= h;
    jac.col(j) = (residuals(plus) - residuals(minus)) / (2.0 * h);
  }
  return jac;
}

}  // namespace blockdem
