// CSV writer.
#include "blockdem/io/csv.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace blockdem {

CsvWriter::CsvWriter(const std::filesystem::path& path, std::vector<std::string> columns,
                     bool append)
    : path_(path), out_(path, append ? std::ios::app : std::ios::trunc), columns_(columns.size()) {
  if (!out_) throw std::runtime_error("cannot write " + path.string());
  out_.precision(12);
  if (append) return;
  for (std::size_t i = 0; i < columns.size(); ++i) out_ << (i ? "," : "") << columns[i];
  // In the file at once: a restart file taken before the first rows are flushed (a checkpoint
  // in the first stage) carries the file as it is on disk, and its run appends to it.
  out_ << "\n" << std::flush;
}

void CsvWriter::separator() {
  if (in_row_++ > 0) out_.put(',');
}

CsvWriter& CsvWriter::cell(double value) {
  separator();
  if (std::isfinite(value)) {
    // The text of the stream at precision 12 (printf's "%.12g"), byte for byte: std::to_chars
    // with the same precision is specified as that printf conversion, without the stream's
    // locale and format machinery (the hot part of writing large tables).
    char text[32];
    const auto end = std::to_chars(text, text + sizeof text, value, std::chars_format::general, 12);
    out_.write(text, end.ptr - text);
  } else {
    out_ << (std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf"));
  }
  return *this;
}

CsvWriter& CsvWriter::cell(long long value) {
  separator();
  char text[24];
  const auto end = std::to_chars(text, text + sizeof text, value);
  out_.write(text, end.ptr - text);
  return *this;
}

CsvWriter& CsvWriter::cell(const std::string& value) {
  separator();
  if (value.find_first_of(",\"\n") == std::string::npos) {
    out_ << value;
  } else {
    out_ << '"';
    for (char c : value) out_ << (c == '"' ? std::string("\"\"") : std::string(1, c));
    out_ << '"';
  }
  return *this;
}

void CsvWriter::end_row() {
  if (in_row_ != columns_) {
    throw std::logic_error(path_.string() + ": row has " + std::to_string(in_row_) +
                           " cells, header has " + std::to_string(columns_));
  }
  out_.put('\n');
  in_row_ = 0;
  if (!out_) throw std::runtime_error("write failed: " + path_.string());
}

}  // namespace blockdem
