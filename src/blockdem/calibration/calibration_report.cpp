// Joint-law blocks, JSON reports, fit CSVs and the plot-script runner of the calibration
// commands (see the header and docs/calibration.md).
#include "blockdem/calibration/calibration_report.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "blockdem/calibration/shear_path.hpp"
#include "blockdem/contact/law_table.hpp"
#include "blockdem/io/csv.hpp"

namespace blockdem {
namespace {

constexpr const char* kCitation =
    "Boon C.W., Houlsby G.T., Utili S. (2015) DEM modelling of a jointed rock beam with emphasis "
    "on interface properties. Geotechnique Letters 5:49-55.";
// Points of the smooth model curves in the CSVs.
constexpr int kCurvePoints = 201;

// A value rounded to 7 significant digits, as in law_number.
double rounded(double value) {
  return std::stod(law_number(value));
}

nlohmann::ordered_json number_or_null(double value) {
  return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
}

nlohmann::ordered_json quality_json(const FitQuality& q, const std::string& unit) {
  nlohmann::ordered_json out;
  out["r_squared"] = number_or_null(q.r_squared);
  out["rms_residual_" + unit] = q.rms_residual;
  out["max_abs_residual_" + unit] = q.max_abs_residual;
  out["rms_relative_residual"] = q.rms_relative_residual;
  return out;
}

nlohmann::ordered_json power_law_json(const PowerLawFit& fit, const std::string& unit) {
  nlohmann::ordered_json out;
  out["coefficient"] = fit.coefficient;
  out["exponent"] = fit.exponent;
  out["reference_stress_Pa"] = fit.reference_stress;
  out["value_at_reference_stress_" + unit] = fit.reference_value;
  out["r_squared_of_log"] = number_or_null(fit.r_squared);
  out["rms_log_residual"] = fit.rms_log_residual;
  out["exponent_standard_error"] = fit.exponent_standard_error;
  out["exponent_interval95"] = {fit.exponent_lower95, fit.exponent_upper95};
  out["value_at_reference_stress_interval95_" + unit] = {fit.reference_value_lower95,
                                                         fit.reference_value_upper95};
  return out;
}

nlohmann::ordered_json data_json(const std::string& source,
                                 const std::vector<std::string>& comments, std::size_t rows) {
  nlohmann::ordered_json out;
  out["file"] = source;
  out["rows"] = rows;
  out["comments"] = comments;
  const bool synthetic = std::any_of(comments.begin(), comments.end(), [](const std::string& c) {
    return c.find("SYNTHETIC") != std::string::npos;
  });
  out["synthetic"] = synthetic;
  return out;
}

// A law's table as a joint-law block: "<section> = { law = "<name>", key = value, ... }" and the
// same keys in JSON (values rounded as in law_number). The keys come from the law's table.
template <class Law>
JointLawBlock law_block(const std::string& section, const Law& law) {
  JointLawBlock block;
  const std::string name(LawTraits<Law>::name);
  block.json[section]["law"] = name;
  block.toml = section + " = { law = \"" + name + "\"";
  for (const LawValue& v : law_values(law)) {
    const std::string key(v.key);
    block.json[section][key] = rounded(v.value);
    block.toml += ", " + key + " = " + law_number(v.value);
  }
  block.toml += " }";
  return block;
}

nlohmann::ordered_json block_json(const JointLawBlock& block) {
  nlohmann::ordered_json out;
  out["json"] = block.json;
  out["toml"] = block.toml;
  return out;
}

// kCurvePoints values evenly spaced on [0, top].
std::vector<double> grid(double top) {
  std::vector<double> out;
  for (int i = 0; i < kCurvePoints; ++i) out.push_back(top * i / (kCurvePoints - 1));
  return out;
}

double largest(const std::vector<double>& values) {
  return *std::max_element(values.begin(), values.end());
}

}  // namespace

std::string law_number(double value) {
  std::array<char, 64> buffer{};
  std::snprintf(buffer.data(), buffer.size(), "%.7g", value);
  std::string text(buffer.data());
  if (text.find_first_of(".eEn") == std::string::npos) text += ".0";
  return text;
}

JointLawBlock joint_law_block(const ExponentialNormal& law) {
  return law_block("normal", law);
}

JointLawBlock joint_law_block(const DegradingShear& law) {
  return law_block("shear", law);
}

JointLawBlock joint_law_block(const ContinuouslyYieldingShear& law) {
  return law_block("shear", law);
}

nlohmann::ordered_json normal_report(const ColumnCompressionData& data,
                                     const NormalCalibration& cal) {
  nlohmann::ordered_json out;
  out["command"] = "calibrate normal";
  out["data"] = data_json(data.source, data.comments, data.stress.size());
  out["inputs"]["modulus_Pa"] = cal.test.modulus;
  out["inputs"]["height_m"] = cal.test.height;
  out["inputs"]["joints"] = cal.test.joints;
  out["method"] =
      "joint closure u = (d - sigma H / E) / N; sigma = a [exp(b u) - 1] (eqs 3-4) fitted by "
      "Levenberg-Marquardt on the closure, residuals relative to the measured closure; linear "
      "law sigma = k u for comparison, same residuals";
  nlohmann::ordered_json& e = out["exponential"];
  e["a_Pa"] = cal.exponential.a;
  e["b_per_m"] = cal.exponential.b;
  e["a_standard_error_Pa"] = cal.a_standard_error;
  e["b_standard_error_per_m"] = cal.b_standard_error;
  e["a_interval95_Pa"] = {cal.a_lower95, cal.a_upper95};
  e["b_interval95_per_m"] = {cal.b_lower95, cal.b_upper95};
  e["uncertainty"] =
      "standard errors and 95% intervals from the Jacobian at the optimum, s^2 (J^T J)^-1 over "
      "(ln a, ln b), Student t with m - 2 degrees of freedom";
  e["k0_Pa_per_m"] = cal.exponential.a * cal.exponential.b;
  e["c_per_m"] = cal.exponential.b;
  e["tangent_stiffness"] = "k_n = k0 + c sigma_n (eq 1 form): k0 = a b, c = b";
  e["fit"] = quality_json(cal.exponential_quality, "m");
  e["fit"]["residuals_m"] = cal.exponential_quality.residuals;
  e["iterations"] = cal.iterations;
  e["termination"] = cal.termination;
  nlohmann::ordered_json& l = out["linear"];
  l["stiffness_Pa_per_m"] = cal.linear.stiffness;
  l["fit"] = quality_json(cal.linear_quality, "m");
  l["fit"]["residuals_m"] = cal.linear_quality.residuals;
  out["joint_law"] = block_json(joint_law_block(cal.exponential));
  nlohmann::ordered_json linear_block;
  linear_block["normal"]["law"] = "linear";
  linear_block["normal"]["stiffness"] = rounded(cal.linear.stiffness);
  out["linear_joint_law"]["json"] = linear_block;
  out["linear_joint_law"]["toml"] =
      "normal = { law = \"linear\", stiffness = " + law_number(cal.linear.stiffness) + " }";
  out["citation"] = std::string(kCitation) + " Eqs 1, 3-4 and Fig 1.";
  return out;
}

nlohmann::ordered_json shear_report(const DirectShearData& data, const ShearCalibration& cal) {
  nlohmann::ordered_json out;
  std::size_t rows = 0;
  for (const auto& curve : data.curves) rows += curve.displacement.size();
  out["command"] = "calibrate shear";
  out["data"] = data_json(data.source, data.comments, rows);
  out["method"] =
      "per normal stress, eq 5 integrated, tau = k_i (u - u^2 / (2 u_peak)) for u < u_peak and "
      "k_i u_peak / 2 beyond, fitted by Levenberg-Marquardt (residuals relative to the measured "
      "stress) to the rows up to the peak and on while tau stays within 5 % of it; then "
      "k_s,initial = A sigma_n^B (eq 7) and u_peak = C sigma_n^D (eq 6) by least squares in "
      "logarithms; friction_deg: the smallest Mohr-Coulomb cap at or above the law's peak "
      "A C sigma_n^(B+D) / 2 at every tested normal stress";
  nlohmann::ordered_json curves = nlohmann::ordered_json::array();
  for (const PeakCurveFit& fit : cal.curves) {
    nlohmann::ordered_json c;
    c["normal_stress_Pa"] = fit.normal_stress;
    c["initial_stiffness_Pa_per_m"] = fit.initial_stiffness;
    c["peak_displacement_m"] = fit.peak_displacement;
    c["initial_stiffness_interval95_Pa_per_m"] = {fit.initial_stiffness_lower95,
                                                  fit.initial_stiffness_upper95};
    c["peak_displacement_interval95_m"] = {fit.peak_displacement_lower95,
                                           fit.peak_displacement_upper95};
    c["peak_shear_stress_Pa"] = fit.peak_shear_stress;
    c["rows_used"] = fit.points_used;
    c["peak_within_data"] = fit.peak_within_data;
    c["eq5_fit"] = quality_json(fit.quality, "Pa");
    c["calibrated_law"] = quality_json(fit.law_quality, "Pa");
    c["calibrated_law"]["residuals_Pa"] = fit.law_quality.residuals;
    c["iterations"] = fit.iterations;
    curves.push_back(c);
  }
  out["curves"] = curves;
  out["initial_stiffness_eq7"] = power_law_json(cal.stiffness, "Pa_per_m");
  out["peak_displacement_eq6"] = power_law_json(cal.peak, "m");
  out[std::string(kStrengthParams[0].key)] = cal.law.strength.friction_deg();
  out["joint_law"] = block_json(joint_law_block(cal.law));
  out["next_step"] = "blockdem calibrate cy --data " + data.source + " --stiffness-coefficient " +
                     law_number(cal.stiffness.coefficient) + " --stiffness-exponent " +
                     law_number(cal.stiffness.exponent);
  out["citation"] = std::string(kCitation) + " Eqs 5-7 and Figs 2-3.";
  return out;
}

nlohmann::ordered_json cy_report(const DirectShearData& data, const CyCalibration& cal) {
  nlohmann::ordered_json out;
  std::size_t rows = 0;
  for (const auto& curve : data.curves) rows += curve.displacement.size();
  out["command"] = "calibrate cy";
  out["data"] = data_json(data.source, data.comments, rows);
  out["inputs"]["stiffness_coefficient"] = cal.stiffness.stiffness_coefficient;
  out["inputs"]["stiffness_exponent"] = cal.stiffness.stiffness_exponent;
  out["method"] =
      "model curves from the engine's continuously-yielding kernel (update_shear), monotonic "
      "shear at constant normal stress on unit area; mu0 = tan(phi) and u_peak = C sigma_n^D "
      "(eqs 6, 8) fitted by Levenberg-Marquardt to all curves at once (residuals relative to "
      "the measured stress), started from single-curve fits; k_s,initial = A sigma_n^B held "
      "at the inputs";
  out[std::string(kStrengthParams[0].key)] = cal.law.strength.friction_deg();
  out["friction_coefficient"] = cal.friction_coefficient;
  out["peak_coefficient"] = cal.law.power_laws.peak_coefficient;
  out["peak_exponent"] = cal.law.power_laws.peak_exponent;
  out["reference_stress_Pa"] = cal.reference_stress;
  out["peak_displacement_at_reference_stress_m"] = cal.reference_peak;
  out["fit"] = quality_json(cal.quality, "mobilised_friction");
  out["iterations"] = cal.iterations;
  out["termination"] = cal.termination;
  nlohmann::ordered_json curves = nlohmann::ordered_json::array();
  for (const CyCurveFit& fit : cal.curves) {
    nlohmann::ordered_json c;
    c["normal_stress_Pa"] = fit.normal_stress;
    c["single_curve_friction_coefficient"] = fit.friction_coefficient;
    c["single_curve_peak_displacement_m"] = fit.peak_displacement;
    c["single_curve_fit_converged"] = fit.converged;
    c["calibrated_law"] = quality_json(fit.quality, "Pa");
    c["calibrated_law"]["residuals_Pa"] = fit.quality.residuals;
    curves.push_back(c);
  }
  out["curves"] = curves;
  out["single_curve_peak_displacement_eq6"] = power_law_json(cal.curve_peak_fit, "m");
  out["joint_law"] = block_json(joint_law_block(cal.law));
  out["citation"] = std::string(kCitation) + " Eqs 6-16 and Fig 4.";
  return out;
}

std::vector<std::string> write_normal_csv(const std::filesystem::path& dir,
                                          const ColumnCompressionData& data,
                                          const NormalCalibration& cal) {
  {
    CsvWriter points(dir / "normal_fit_points.csv",
                     {"line", "stress_Pa", "displacement_m", "intact_displacement_m",
                      "joint_closure_m", "exponential_closure_m", "exponential_residual_m",
                      "linear_closure_m", "linear_residual_m"});
    for (std::size_t i = 0; i < cal.stress.size(); ++i) {
      points.cell(data.lines[i]).cell(cal.stress[i]).cell(cal.displacement[i]);
      points.cell(cal.intact_displacement[i]).cell(cal.closure[i]);
      points.cell(cal.exponential_closure[i]).cell(cal.exponential_quality.residuals[i]);
      points.cell(cal.linear_closure[i]).cell(cal.linear_quality.residuals[i]);
      points.end_row();
    }
  }
  {
    // The laws evaluated by the engine's normal kernels.
    CsvWriter curve(dir / "normal_fit_curve.csv",
                    {"joint_closure_m", "exponential_stress_Pa", "linear_stress_Pa",
                     "exponential_tangent_stiffness_Pa_per_m"});
    const NormalLaw exponential = cal.exponential;
    const NormalLaw linear = cal.linear;
    for (double u : grid(1.05 * largest(cal.closure))) {
      curve.cell(u).cell(normal_stress(exponential, u)).cell(normal_stress(linear, u));
      curve.cell(normal_tangent_stiffness(exponential, u)).end_row();
    }
  }
  return {"normal_fit_points.csv", "normal_fit_curve.csv"};
}

std::vector<std::string> write_shear_csv(const std::filesystem::path& dir,
                                         const DirectShearData& data, const ShearCalibration& cal) {
  {
    CsvWriter points(dir / "shear_fit_points.csv",
                     {"line", "normal_stress_Pa", "shear_displacement_m", "shear_stress_Pa",
                      "used_in_eq5_fit", "eq5_fit_stress_Pa", "law_stress_Pa", "law_residual_Pa"});
    for (std::size_t c = 0; c < data.curves.size(); ++c) {
      const DirectShearCurve& curve = data.curves[c];
      const PeakCurveFit& fit = cal.curves[c];
      for (std::size_t i = 0; i < curve.displacement.size(); ++i) {
        points.cell(curve.lines[i]).cell(curve.normal_stress).cell(curve.displacement[i]);
        points.cell(curve.shear_stress[i]).cell(i < fit.points_used ? 1 : 0);
        points.cell(fit.model_stress[i]).cell(fit.law_stress[i]);
        points.cell(fit.law_quality.residuals[i]).end_row();
      }
    }
  }
  {
    CsvWriter curves(dir / "shear_fit_curves.csv",
                     {"normal_stress_Pa", "shear_displacement_m", "eq5_fit_stress_Pa",
                      "eq5_fit_stiffness_Pa_per_m", "law_stress_Pa"});
    for (std::size_t c = 0; c < data.curves.size(); ++c) {
      const DirectShearCurve& curve = data.curves[c];
      const PeakCurveFit& fit = cal.curves[c];
      const std::vector<double> u = grid(1.1 * largest(curve.displacement));
      const std::vector<double> law = simulate_monotonic_shear(cal.law, curve.normal_stress, u);
      for (std::size_t i = 0; i < u.size(); ++i) {
        // Eq 5: the instantaneous stiffness of the per-curve fit (the paper's Fig 2).
        const double ks = std::max(0.0, 1.0 - u[i] / fit.peak_displacement) * fit.initial_stiffness;
        curves.cell(curve.normal_stress).cell(u[i]);
        curves.cell(degrading_shear_stress(fit.initial_stiffness, fit.peak_displacement, u[i]));
        curves.cell(ks).cell(law[i]).end_row();
      }
    }
  }
  {
    CsvWriter laws(
        dir / "shear_power_laws.csv",
        {"normal_stress_Pa", "initial_stiffness_Pa_per_m", "peak_displacement_m",
         "eq7_initial_stiffness_Pa_per_m", "eq6_peak_displacement_m", "peak_shear_stress_Pa"});
    for (const PeakCurveFit& fit : cal.curves) {
      laws.cell(fit.normal_stress).cell(fit.initial_stiffness).cell(fit.peak_displacement);
      laws.cell(cal.stiffness.evaluate(fit.normal_stress));
      laws.cell(cal.peak.evaluate(fit.normal_stress)).cell(fit.peak_shear_stress).end_row();
    }
  }
  return {"shear_fit_points.csv", "shear_fit_curves.csv", "shear_power_laws.csv"};
}

std::vector<std::string> write_cy_csv(const std::filesystem::path& dir, const DirectShearData& data,
                                      const CyCalibration& cal) {
  {
    CsvWriter points(dir / "cy_fit_points.csv",
                     {"line", "normal_stress_Pa", "shear_displacement_m", "shear_stress_Pa",
                      "law_stress_Pa", "law_residual_Pa"});
    for (std::size_t c = 0; c < data.curves.size(); ++c) {
      const DirectShearCurve& curve = data.curves[c];
      const CyCurveFit& fit = cal.curves[c];
      for (std::size_t i = 0; i < curve.displacement.size(); ++i) {
        points.cell(curve.lines[i]).cell(curve.normal_stress).cell(curve.displacement[i]);
        points.cell(curve.shear_stress[i]).cell(fit.law_stress[i]);
        points.cell(fit.quality.residuals[i]).end_row();
      }
    }
  }
  {
    CsvWriter curves(dir / "cy_fit_curves.csv", {"normal_stress_Pa", "shear_displacement_m",
                                                 "law_stress_Pa", "mobilised_friction"});
    for (const DirectShearCurve& curve : data.curves) {
      const std::vector<double> u = grid(1.1 * largest(curve.displacement));
      const std::vector<double> law = simulate_monotonic_shear(cal.law, curve.normal_stress, u);
      for (std::size_t i = 0; i < u.size(); ++i) {
        curves.cell(curve.normal_stress).cell(u[i]).cell(law[i]);
        curves.cell(law[i] / curve.normal_stress).end_row();
      }
    }
  }
  {
    CsvWriter fits(dir / "cy_curve_fits.csv",
                   {"normal_stress_Pa", "single_curve_friction_coefficient",
                    "single_curve_peak_displacement_m", "law_friction_coefficient",
                    "law_peak_displacement_m"});
    for (const CyCurveFit& fit : cal.curves) {
      fits.cell(fit.normal_stress).cell(fit.friction_coefficient).cell(fit.peak_displacement);
      fits.cell(cal.friction_coefficient);
      fits.cell(cal.law.power_laws.peak_displacement(fit.normal_stress)).end_row();
    }
  }
  return {"cy_fit_points.csv", "cy_fit_curves.csv", "cy_curve_fits.csv"};
}

}  // namespace blockdem
