// What the calibration commands hand to the user: the joint-law block to paste into a scenario
// (JSON object and TOML line), the JSON report of a fit, and the CSV files the plots are drawn
// from (docs/calibration.md lists every file and column).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "blockdem/calibration/cy_calibration.hpp"
#include "blockdem/calibration/normal_calibration.hpp"
#include "blockdem/calibration/shear_calibration.hpp"

namespace blockdem {

/// A number for a joint-law block: 7 significant digits, always written as a float literal
/// (TOML reads "54050" as an integer): 54050 is written "54050.0", 2e-06 "2e-06".
std::string law_number(double value);

/// A joint law as a scenario's joint-law table holds it, in both notations.
struct JointLawBlock {
  nlohmann::ordered_json json;  ///< e.g. {"normal": {"law": "exponential", "a": ..., "b": ...}}
  std::string toml;             ///< e.g. normal = { law = "exponential", a = ..., b = ... }
};

/// normal = { law = "exponential", a = ..., b = ... }: the keys of the law's table (law_table.hpp).
JointLawBlock joint_law_block(const ExponentialNormal& law);
/// shear = { law = "degrading", ... }: the law's keys, then its strength keys (optional ones
/// only when they differ from their defaults).
JointLawBlock joint_law_block(const DegradingShear& law);
/// shear = { law = "continuously_yielding", ... }, as for the degrading law.
JointLawBlock joint_law_block(const ContinuouslyYieldingShear& law);

/// The JSON reports (calibration.json): the data file and its comments, the inputs, the method,
/// the fitted parameters at full precision with goodness of fit and residuals, the joint-law
/// block, and the paper's citation.
nlohmann::ordered_json normal_report(const ColumnCompressionData& data,
                                     const NormalCalibration& cal);
nlohmann::ordered_json shear_report(const DirectShearData& data, const ShearCalibration& cal);
nlohmann::ordered_json cy_report(const DirectShearData& data, const CyCalibration& cal);

/// Writes the fit CSVs of a calibration into `dir` (which must exist) and returns their file
/// names. Throws std::runtime_error if a file cannot be written.
std::vector<std::string> write_normal_csv(const std::filesystem::path& dir,
                                          const ColumnCompressionData& data,
                                          const NormalCalibration& cal);
std::vector<std::string> write_shear_csv(const std::filesystem::path& dir,
                                         const DirectShearData& data, const ShearCalibration& cal);
std::vector<std::string> write_cy_csv(const std::filesystem::path& dir, const DirectShearData& data,
                                      const CyCalibration& cal);

/// The outcome of running tools/calibration_plot.py.
}  // namespace blockdem
