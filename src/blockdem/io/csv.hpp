// A small CSV writer: a header of column names (units in the names) and rows of values.
#pragma once

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace blockdem {

/// Writes `value` as printf's "%.12g" writes it (the text of a stream at precision 12), at
/// `out`, which has room for 32 characters; returns the end of the text.
char* write_general12(char* out, double value);

class CsvWriter {
 public:
  /// Creates (truncates) the file and writes the header; with `append`, adds rows to the end of
  /// an existing file that has the header (a restarted run). Throws OutputError (a
  /// std::runtime_error) when the file cannot be written, here or when rows are flushed.
  CsvWriter(const std::filesystem::path& path, std::vector<std::string> columns,
            bool append = false);
  /// A writer into memory (no file, no header): take() returns the rows so far, formatted as
  /// a file's writer formats them, for rows written elsewhere (raw()).
  explicit CsvWriter(std::size_t columns);
  ~CsvWriter();
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;

  /// One row: values in column order. Numbers print with 12 significant digits.
  CsvWriter& cell(double value);
  CsvWriter& cell(long long value);
  CsvWriter& cell(int value) { return cell(static_cast<long long>(value)); }
  CsvWriter& cell(const std::string& value);
  /// Ends the row; throws if the number of cells differs from the header.
  void end_row();
  /// Puts every row so far in the file.
  void flush();
  /// A writer into memory: the rows so far, which it forgets.
  std::string take();
  /// Whole rows formatted by a writer into memory with the same columns, added as they are.
  void raw(std::string_view rows);

 private:
  // Rows gather in a buffer of this size, passed to the file when it is nearly full.
  static constexpr std::size_t kBuffer = 1 << 16;
  // The longest cell that is written into the buffer directly (a number).
  static constexpr std::size_t kCell = 40;
  // Room for `bytes` more characters: the buffer goes to the file first if they do not fit.
  char* room(std::size_t bytes) {
    if (used_ + bytes > kBuffer) write_buffer();
    return buffer_.get() + used_;
  }
  void separator() {
    if (in_row_++ > 0) *room(1) = ',', ++used_;
  }
  void append(const char* text, std::size_t size);
  void write_buffer();
  std::filesystem::path path_;
  std::ofstream out_;
  bool memory_ = false;  ///< rows gather in text_, not in a file
  std::string text_;
  std::unique_ptr<char[]> buffer_;
  std::size_t used_ = 0;
  std::size_t columns_ = 0;
  std::size_t in_row_ = 0;
};

}  // namespace blockdem
