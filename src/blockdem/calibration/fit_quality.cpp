// Goodness of fit and power-law fits in logarithms (see the header).
#include "blockdem/calibration/fit_quality.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "blockdem/calibration/calibration_data.hpp"
#include "blockdem/contact/law_params.hpp"
#include "blockdem/numerics/least_squares.hpp"

namespace blockdem {

std::vector<double> relative_weights(const std::vector<double>& observed) {
  double largest = 0.0;
  for (double y : observed) {
    if (!std::isfinite(y)) throw std::invalid_argument("relative_weights: a value is not finite");
    largest = std::max(largest, std::abs(y));
  }
  if (!(largest > 0.0)) throw std::invalid_argument("relative_weights: every value is zero");
  std::vector<double> weights;
  for (double y : observed) {
    weights.push_back(1.0 / std::max(std::abs(y), kRelativeWeightFloor * largest));
  }
  return weights;
}

FitQuality fit_quality(const std::vector<double>& observed, const std::vector<double>& model) {
  if (observed.size() != model.size() || observed.size() < 2) {
    throw std::invalid_argument("fit_quality: needs two equally long vectors of at least 2 values");
  }
  const double n = static_cast<double>(observed.size());
  double mean = 0.0;
  for (double y : observed) mean += y / n;
  FitQuality q;
  double ss_res = 0.0;
  double ss_tot = 0.0;
  for (std::size_t i = 0; i < observed.size(); ++i) {
    const double r = model[i] - observed[i];
    q.residuals.push_back(r);
    ss_res += r * r;
    ss_tot += (observed[i] - mean) * (observed[i] - mean);
    q.max_abs_residual = std::max(q.max_abs_residual, std::abs(r));
  }
  q.rms_residual = std::sqrt(ss_res / n);
  double largest = 0.0;
  for (double y : observed) largest = std::max(largest, std::abs(y));
  if (largest > 0.0) {
    const std::vector<double> w = relative_weights(observed);
    double ss_rel = 0.0;
    for (std::size_t i = 0; i < observed.size(); ++i) {
      ss_rel += (w[i] * q.residuals[i]) * (w[i] * q.residuals[i]);
    }
    q.rms_relative_residual = std::sqrt(ss_rel / n);
  }
  if (ss_tot > 0.0) {
    q.r_squared = 1.0 - ss_res / ss_tot;
  } else {
    q.r_squared = ss_res == 0.0 ? 1.0 : -std::numeric_limits<double>::infinity();
  }
  return q;
}

double PowerLawFit::evaluate(double sigma) const {
  return reference_value * std::pow(sigma / reference_stress, exponent);
}

PowerLawFit fit_power_law(const std::vector<double>& stress, const std::vector<double>& value,
                          const std::string& what) {
  if (stress.size() != value.size()) {
    throw std::invalid_argument("fit_power_law: stress and value differ in size");
  }
  if (stress.size() < 2) {
    throw CalibrationError("power-law fit of " + what + ": needs at least 2 points, got " +
                           std::to_string(stress.size()));
  }
  const auto m = static_cast<Eigen::Index>(stress.size());
  double mean_log_stress = 0.0;
  for (std::size_t i = 0; i < stress.size(); ++i) {
    if (!(stress[i] > 0.0 && std::isfinite(stress[i]))) {
      throw CalibrationError("power-law fit of " + what + ": normal stress " +
                             format_value(stress[i]) + " Pa must be positive and finite");
    }
    if (!(value[i] > 0.0 && std::isfinite(value[i]))) {
      throw CalibrationError("power-law fit of " + what + ": the value " + format_value(value[i]) +
                             " at normal stress " + format_value(stress[i]) +
                             " Pa must be positive and finite to take its logarithm");
    }
    mean_log_stress += std::log(stress[i]) / static_cast<double>(m);
  }
  const double reference_stress = std::exp(mean_log_stress);
  Eigen::MatrixXd design(m, 2);
  Eigen::VectorXd log_value(m);
  for (Eigen::Index i = 0; i < m; ++i) {
    design(i, 0) = 1.0;
    design(i, 1) = std::log(stress[static_cast<std::size_t>(i)] / reference_stress);
    log_value(i) = std::log(value[static_cast<std::size_t>(i)]);
  }
  if (design.col(1).cwiseAbs().maxCoeff() == 0.0) {
    throw CalibrationError("power-law fit of " + what +
                           ": all points share one normal stress; the exponent is undetermined");
  }
  const LinearLeastSquaresSolution solution = solve_linear_least_squares(design, log_value);
  PowerLawFit fit;
  fit.reference_stress = reference_stress;
  fit.reference_value = std::exp(solution.parameters(0));
  fit.exponent = solution.parameters(1);
  fit.coefficient = fit.reference_value * std::pow(reference_stress, -fit.exponent);
  std::vector<double> observed(stress.size());
  std::vector<double> model(stress.size());
  for (std::size_t i = 0; i < stress.size(); ++i) {
    observed[i] = log_value(static_cast<Eigen::Index>(i));
    model[i] = observed[i] + solution.residuals(static_cast<Eigen::Index>(i));
  }
  const FitQuality q = fit_quality(observed, model);
  fit.r_squared = q.r_squared;
  fit.rms_log_residual = q.rms_residual;
  if (m > 2) {
    const ParameterUncertainty u =
        parameter_uncertainty(design, solution.residuals, solution.parameters);
    fit.exponent_standard_error = u.standard_errors(1);
    fit.exponent_lower95 = u.lower95(1);
    fit.exponent_upper95 = u.upper95(1);
    fit.reference_value_lower95 = std::exp(u.lower95(0));
    fit.reference_value_upper95 = std::exp(u.upper95(0));
  }
  return fit;
}

}  // namespace blockdem
