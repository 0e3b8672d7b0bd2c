// A small CSV writer: a header of column names (units in the names) and rows of values.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace blockdem {

class CsvWriter {
 public:
  /// Creates (truncates) the file and writes the header; with `append`, adds rows to the end of
  /// an existing file that has the header (a restarted run). Throws std::runtime_error on failure.
  CsvWriter(const std::filesystem::path& path, std::vector<std::string> columns,
            bool append = false);

  /// One row: values in column order. Numbers print with 12 significant digits.
  CsvWriter& cell(double value);
  CsvWriter& cell(long long value);
  CsvWriter& cell(int value) { return cell(static_cast<long long>(value)); }
  CsvWriter& cell(const std::string& value);
  /// Ends the row; throws if the number of cells differs from the header.
  void end_row();
  void flush() { out_.flush(); }

 private:
  void separator();
  std::filesystem::path path_;
  std::ofstream out_;
  std::size_t columns_ = 0;
  std::size_t in_row_ = 0;
};

}  // namespace blockdem
