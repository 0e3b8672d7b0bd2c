// Linear least squares by column-pivoted QR and a Levenberg-Marquardt solver (see the header for
// the method and its sources).
#include "blockdem/numerics/least_squares.hpp"

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace blockdem {
namespace {

// Half the squared norm: the cost Levenberg-Marquardt minimises.
double half_squared_norm(const Eigen::VectorXd& r) {
  return 0.5 * r.squaredNorm();
}

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
  if (max_iterations < 1) {
    throw std::invalid_argument("LevenbergMarquardtOptions.max_iterations must be >= 1");
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
  if (!(initial_damping_factor > 0.0 && std::isfinite(initial_damping_factor))) {
    throw std::invalid_argument(
        "LevenbergMarquardtOptions.initial_damping_factor must be positive and finite");
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
    case LevenbergMarquardtTermination::max_iterations:
      return "max_iterations";
    case LevenbergMarquardtTermination::non_finite:
      return "non_finite";
  }
  throw std::logic_error("unknown LevenbergMarquardtTermination value");
}

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
  const Eigen::Index m = result.residuals.size();
  if (m < k) {
    std::ostringstream msg;
    msg << "levenberg_marquardt: " << m << " residuals cannot determine " << k << " parameters";
    throw std::invalid_argument(msg.str());
  }
  Eigen::MatrixXd jac = model.jacobian(result.parameters);
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

  double cost = half_squared_norm(result.residuals);
  // Marquardt scaling: D_jj = ||J_j||^2, never allowed to shrink (MINPACK); 1 for a null column.
  Eigen::VectorXd scaling = jac.colwise().squaredNorm().transpose();
  for (Eigen::Index j = 0; j < k; ++j) {
    if (scaling(j) == 0.0) scaling(j) = 1.0;
  }
  double mu = options.initial_damping_factor;
  double nu = 2.0;

  for (int iter = 0; iter < options.max_iterations; ++iter) {
    result.iterations = iter + 1;
    // First-order optimality: the residual is orthogonal to every column of J (MINPACK's gtol).
    const double r_norm = result.residuals.norm();
    if (r_norm == 0.0) {
      result.termination = LevenbergMarquardtTermination::gradient_small;
      break;
    }
    const Eigen::VectorXd gradient = jac.transpose() * result.residuals;
    double max_cosine = 0.0;
    for (Eigen::Index j = 0; j < k; ++j) {
      const double col_norm = jac.col(j).norm();
      if (col_norm > 0.0) {
        max_cosine = std::max(max_cosine, std::abs(gradient(j)) / (col_norm * r_norm));
      }
    }
    if (max_cosine <= options.gradient_tolerance) {
      result.termination = LevenbergMarquardtTermination::gradient_small;
      break;
    }

    // Damped step from the augmented system [J; sqrt(mu D)] dp = [-r; 0], solved by QR.
    Eigen::MatrixXd augmented(m + k, k);
    augmented.topRows(m) = jac;
    augmented.bottomRows(k) = (mu * scaling).cwiseSqrt().asDiagonal();
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(m + k);
    rhs.head(m) = -result.residuals;
    const Eigen::VectorXd step = augmented.colPivHouseholderQr().solve(rhs);

    // Negligible step: nothing left to gain at this damping.
    if (step.norm() <=
        options.step_tolerance * (result.parameters.norm() + options.step_tolerance)) {
      result.termination = LevenbergMarquardtTermination::step_small;
      break;
    }

    const Eigen::VectorXd trial = result.parameters + step;
    const Eigen::VectorXd trial_residuals = model.residuals(trial);
    const double trial_cost =
        trial_residuals.allFinite() ? half_squared_norm(trial_residuals) : HUGE_VAL;
    // Gain ratio: actual over predicted decrease of the cost (linear model of r).
    const double predicted = cost - half_squared_norm(result.residuals + jac * step);
    const double actual = cost - trial_cost;
    const double gain = predicted > 0.0 ? actual / predicted : -1.0;

    if (actual > 0.0 && gain > 0.0) {
      // Accepted: move, relinearise, relax the damping (Nielsen 1999).
      result.parameters = trial;
      result.residuals = trial_residuals;
      jac = model.jacobian(result.parameters);
      if (!jac.allFinite()) {
        result.termination = LevenbergMarquardtTermination::non_finite;
        break;
      }
      scaling = scaling.cwiseMax(jac.colwise().squaredNorm().transpose());
      const double old_cost = cost;
      cost = trial_cost;
      mu *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * gain - 1.0, 3));
      nu = 2.0;
      if (old_cost - cost <= options.cost_tolerance * old_cost) {
        result.termination = LevenbergMarquardtTermination::cost_stalled;
        break;
      }
    } else {
      // Rejected: stiffen the damping, growing the factor each time.
      mu *= nu;
      nu *= 2.0;
    }
  }
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
