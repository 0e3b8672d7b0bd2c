// Laboratory data for joint-law calibration: a strict CSV reader (named
// columns, '#' comment lines, every value finite) and the two test types the paper calibrates
// from, column compression (its Fig 1) and direct shear at several normal stresses (Figs 2-4).
#pragma once

#include <filesystem>
#include <istream>
#include <stdexcept>
#include <string>
#include <vector>

namespace blockdem {

/// Unusable calibration input: unreadable file, missing column, bad value, too few points, or a
/// parameter that makes the data meaningless. The message names the file and row (FILE:LINE) or
/// the parameter.
class CalibrationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A CSV table with named columns, as read by read_calibration_csv.
struct CalibrationTable {
  std::string source;                     ///< file name, used in every message
  std::vector<std::string> comments;      ///< text of the '#' lines, '#' and blanks trimmed
  std::vector<std::string> columns;       ///< the requested column names, in the requested order
  std::vector<std::vector<double>> rows;  ///< rows[i][j]: value of columns[j] in data row i
  std::vector<int> lines;                 ///< 1-based file line of each data row

  /// "SOURCE:LINE" of data row i, the prefix of messages about that row.
  std::string where(std::size_t row) const;
};

/// Reads a CSV table. Lines that are empty or start with '#' (after leading blanks) are skipped
/// and their text kept in `comments`; the first other line is the header. The header must hold
/// every name in `columns` exactly once and nothing else (order free). Every data row must have
/// one field per header column, each a finite decimal number. Throws CalibrationError naming
/// `source` and the line for a missing or unknown column, a short or long row, a non-numeric,
/// NaN or infinite value, or a table without data rows.
CalibrationTable parse_calibration_csv(std::istream& in, const std::string& source,
                                       const std::vector<std::string>& columns);
/// parse_calibration_csv on a file; throws CalibrationError if it cannot be opened.
CalibrationTable read_calibration_csv(const std::filesystem::path& path,
                                      const std::vector<std::string>& columns);

/// A column compression test (the paper's Fig 1): loading branch, stress increasing.
struct ColumnCompressionData {
  std::string source;                 ///< file name
  std::vector<std::string> comments;  ///< the file's '#' lines
  std::vector<double> stress;         ///< applied axial stress sigma, >= 0, increasing (Pa)
  std::vector<double> displacement;   ///< measured total shortening of the column, >= 0 (m)
  std::vector<int> lines;             ///< file line of each row
};

/// Minimum rows of a column test: the exponential fit has two parameters, and goodness of fit
/// needs a few more points than that.
inline constexpr std::size_t kMinimumColumnRows = 5;

/// Checks a table with columns stress_Pa, displacement_m and returns it as a column test. Throws
/// CalibrationError naming the row for a negative stress or displacement, a stress not greater
/// than the previous row's (give the loading branch only, in loading order), or fewer than
/// kMinimumColumnRows rows.
ColumnCompressionData column_compression_data(const CalibrationTable& table);
/// read_calibration_csv + column_compression_data.
ColumnCompressionData read_column_compression(const std::filesystem::path& path);

/// One direct-shear curve: monotonic shear at a constant normal stress.
struct DirectShearCurve {
  double normal_stress = 0.0;        ///< sigma_n, > 0 (Pa)
  std::vector<double> displacement;  ///< shear displacement u, >= 0, increasing (m)
  std::vector<double> shear_stress;  ///< shear stress tau, >= 0 (Pa)
  std::vector<int> lines;            ///< file line of each row
};

/// Direct shear tests at several normal stresses (the paper's Figs 2-4).
struct DirectShearData {
  std::string source;                    ///< file name
  std::vector<std::string> comments;     ///< the file's '#' lines
  std::vector<DirectShearCurve> curves;  ///< one per normal stress, in file order
};

/// Minimum rows per shear curve and minimum number of curves (eqs 6-7 have two parameters each;
/// a third normal stress leaves a residual to judge the fit by).
inline constexpr std::size_t kMinimumCurveRows = 5;
inline constexpr std::size_t kMinimumShearCurves = 3;

/// Checks a table with columns normal_stress_Pa, shear_displacement_m, shear_stress_Pa and
/// groups it into curves: consecutive rows with the same normal stress form one curve. Throws
/// CalibrationError naming the row for a non-positive normal stress, a negative displacement or
/// shear stress, a displacement not greater than the previous row's in the same curve, a normal
/// stress whose rows are not contiguous, a curve with fewer than kMinimumCurveRows rows, and
/// naming the file for fewer than kMinimumShearCurves curves.
DirectShearData direct_shear_data(const CalibrationTable& table);
/// read_calibration_csv + direct_shear_data.
DirectShearData read_direct_shear(const std::filesystem::path& path);

}  // namespace blockdem
