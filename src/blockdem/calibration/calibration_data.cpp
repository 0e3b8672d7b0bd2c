// Strict CSV reading and checking of calibration data: column compression and direct shear
// tables (see the header for the rules and the messages).
#include "blockdem/calibration/calibration_data.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "blockdem/contact/law_params.hpp"

namespace blockdem {
namespace {

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  const auto last = text.find_last_not_of(" \t\r\n");
  return text.substr(first, last - first + 1);
}

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) fields.push_back(trim(field));
  // A trailing comma ends with an empty field that getline does not return.
  if (!line.empty() && trim(line).back() == ',') fields.emplace_back();
  return fields;
}

std::string quoted_list(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& name : names) out += (out.empty() ? "'" : ", '") + name + "'";
  return out;
}

// Parses a whole field as a decimal number (an optional leading '+' is allowed).
bool parse_number(const std::string& field, double& value) {
  const char* first = field.data();
  const char* last = field.data() + field.size();
  if (first != last && *first == '+') ++first;
  if (first == last) return false;
  const auto [end, error] = std::from_chars(first, last, value);
  return error == std::errc() && end == last;
}

}  // namespace

std::string CalibrationTable::where(std::size_t row) const {
  return source + ":" + std::to_string(lines.at(row));
}

CalibrationTable parse_calibration_csv(std::istream& in, const std::string& source,
                                       const std::vector<std::string>& columns) {
  CalibrationTable table;
  table.source = source;
  table.columns = columns;
  std::vector<int> column_of_field;  // field index -> index into `columns`
  bool have_header = false;
  std::string raw;
  int line_number = 0;
  while (std::getline(in, raw)) {
    ++line_number;
    const std::string line = trim(raw);
    const std::string at = source + ":" + std::to_string(line_number) + ": ";
    if (line.empty()) continue;
    if (line.front() == '#') {
      table.comments.push_back(trim(line.substr(1)));
      continue;
    }
    const std::vector<std::string> fields = split_fields(line);
    if (!have_header) {
      // The header: every requested column once, nothing else.
      std::map<std::string, int> seen;
      for (const auto& name : fields) {
        const auto it = std::find(columns.begin(), columns.end(), name);
        if (it == columns.end()) {
          throw CalibrationError(at + "unexpected column '" + name + "' in the header; expected " +
                                 quoted_list(columns));
        }
        if (seen.count(name) > 0) {
          throw CalibrationError(at + "column '" + name + "' appears twice in the header");
        }
        seen[name] = static_cast<int>(it - columns.begin());
        column_of_field.push_back(seen[name]);
      }
      std::vector<std::string> missing;
      for (const auto& name : columns) {
        if (seen.count(name) == 0) missing.push_back(name);
      }
      if (!missing.empty()) {
        throw CalibrationError(at + "missing column" + (missing.size() > 1 ? "s " : " ") +
                               quoted_list(missing) + " in the header '" + line + "'; expected " +
                               quoted_list(columns));
      }
      have_header = true;
      continue;
    }
    if (fields.size() != columns.size()) {
      throw CalibrationError(at + "expected " + std::to_string(columns.size()) + " values (" +
                             quoted_list(columns) + "), found " + std::to_string(fields.size()));
    }
    std::vector<double> row(columns.size());
    for (std::size_t f = 0; f < fields.size(); ++f) {
      const std::string& name = columns[static_cast<std::size_t>(column_of_field[f])];
      double value = 0.0;
      if (fields[f].empty()) throw CalibrationError(at + "column '" + name + "' is empty");
      if (!parse_number(fields[f], value)) {
        throw CalibrationError(at + "column '" + name + "': '" + fields[f] + "' is not a number");
      }
      if (!std::isfinite(value)) {
        throw CalibrationError(at + "column '" + name + "' is " + format_value(value) +
                               "; every value must be finite");
      }
      row[static_cast<std::size_t>(column_of_field[f])] = value;
    }
    table.rows.push_back(std::move(row));
    table.lines.push_back(line_number);
  }
  if (in.bad()) throw CalibrationError(source + ": read error");
  if (!have_header) {
    throw CalibrationError(source + ": no header line (expected the columns " +
                           quoted_list(columns) + ")");
  }
  if (table.rows.empty()) throw CalibrationError(source + ": no data rows after the header");
  return table;
}

CalibrationTable read_calibration_csv(const std::filesystem::path& path,
                                      const std::vector<std::string>& columns) {
  std::ifstream in(path);
  if (!in) throw CalibrationError(path.string() + ": cannot open the file for reading");
  return parse_calibration_csv(in, path.string(), columns);
}

ColumnCompressionData column_compression_data(const CalibrationTable& table) {
  if (table.columns != std::vector<std::string>{"stress_Pa", "displacement_m"}) {
    throw std::invalid_argument(
        "column_compression_data: the table must be read with the columns stress_Pa, "
        "displacement_m");
  }
  ColumnCompressionData data;
  data.source = table.source;
  data.comments = table.comments;
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    const double stress = table.rows[i][0];
    const double displacement = table.rows[i][1];
    if (stress < 0.0) {
      throw CalibrationError(table.where(i) + ": stress_Pa = " + format_value(stress) +
                             " is negative; give compression as positive stress");
    }
    if (displacement < 0.0) {
      throw CalibrationError(table.where(i) + ": displacement_m = " + format_value(displacement) +
                             " is negative; give the shortening of the column as positive");
    }
    if (i > 0 && !(stress > data.stress.back())) {
      throw CalibrationError(table.where(i) + ": stress_Pa = " + format_value(stress) +
                             " is not greater than the previous row's " +
                             format_value(data.stress.back()) +
                             "; give the loading branch only, in order of increasing stress");
    }
    data.stress.push_back(stress);
    data.displacement.push_back(displacement);
    data.lines.push_back(table.lines[i]);
  }
  if (data.stress.size() < kMinimumColumnRows) {
    throw CalibrationError(table.source + ": " + std::to_string(data.stress.size()) +
                           " data rows; a column test needs at least " +
                           std::to_string(kMinimumColumnRows));
  }
  return data;
}

ColumnCompressionData read_column_compression(const std::filesystem::path& path) {
  return column_compression_data(read_calibration_csv(path, {"stress_Pa", "displacement_m"}));
}

DirectShearData direct_shear_data(const CalibrationTable& table) {
  if (table.columns !=
      std::vector<std::string>{"normal_stress_Pa", "shear_displacement_m", "shear_stress_Pa"}) {
    throw std::invalid_argument(
        "direct_shear_data: the table must be read with the columns normal_stress_Pa, "
        "shear_displacement_m, shear_stress_Pa");
  }
  DirectShearData data;
  data.source = table.source;
  data.comments = table.comments;
  std::set<double> finished;  // normal stresses of curves already closed
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    const double sigma = table.rows[i][0];
    const double u = table.rows[i][1];
    const double tau = table.rows[i][2];
    if (!(sigma > 0.0)) {
      throw CalibrationError(table.where(i) + ": normal_stress_Pa = " + format_value(sigma) +
                             " must be positive (compression)");
    }
    if (u < 0.0) {
      throw CalibrationError(table.where(i) + ": shear_displacement_m = " + format_value(u) +
                             " is negative; give monotonic shear from zero as positive");
    }
    if (tau < 0.0) {
      throw CalibrationError(table.where(i) + ": shear_stress_Pa = " + format_value(tau) +
                             " is negative; give monotonic shear as positive stress");
    }
    if (data.curves.empty() || data.curves.back().normal_stress != sigma) {
      if (!data.curves.empty()) finished.insert(data.curves.back().normal_stress);
      if (finished.count(sigma) > 0) {
        throw CalibrationError(table.where(i) + ": normal_stress_Pa = " + format_value(sigma) +
                               " was already given in an earlier block of rows; the rows of "
                               "each normal stress must be contiguous");
      }
      data.curves.emplace_back();
      data.curves.back().normal_stress = sigma;
    }
    DirectShearCurve& curve = data.curves.back();
    if (!curve.displacement.empty() && !(u > curve.displacement.back())) {
      throw CalibrationError(table.where(i) + ": shear_displacement_m = " + format_value(u) +
                             " is not greater than the previous row's " +
                             format_value(curve.displacement.back()) + " at normal stress " +
                             format_value(sigma) +
                             " Pa; give monotonic loading, in order of increasing displacement");
    }
    curve.displacement.push_back(u);
    curve.shear_stress.push_back(tau);
    curve.lines.push_back(table.lines[i]);
  }
  for (const DirectShearCurve& curve : data.curves) {
    if (curve.displacement.size() < kMinimumCurveRows) {
      throw CalibrationError(table.source + ":" + std::to_string(curve.lines.front()) +
                             ": the curve at normal stress " + format_value(curve.normal_stress) +
                             " Pa has " + std::to_string(curve.displacement.size()) +
                             " rows; each curve needs at least " +
                             std::to_string(kMinimumCurveRows));
    }
  }
  if (data.curves.size() < kMinimumShearCurves) {
    throw CalibrationError(table.source + ": " + std::to_string(data.curves.size()) +
                           " normal stress(es); fitting eqs 6-7 needs curves at at least " +
                           std::to_string(kMinimumShearCurves) + " different normal stresses");
  }
  return data;
}

DirectShearData read_direct_shear(const std::filesystem::path& path) {
  return direct_shear_data(
      read_calibration_csv(path, {"normal_stress_Pa", "shear_displacement_m", "shear_stress_Pa"}));
}

}  // namespace blockdem
