// CSV writer.
#include "blockdem/io/csv.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "blockdem/io/output_error.hpp"

namespace blockdem {

char* write_general12(char* out, double value) {
  constexpr int kPrecision = 12;
  if (value == 0.0) {
    if (std::signbit(value)) *out++ = '-';
    *out++ = '0';
    return out;
  }
  // The shortest digits that read back as `value` (std::to_chars without a precision), rounded
  // to 12 digits. This is the rounding of the exact binary value to 12 digits, as printf's, except
  // when the shortest digits end on a tie at the 13th: a normal number's interval of reals that
  // read back to it is at most 2^-52 of it wide, so it holds at most one 13-digit decimal (they lie
  // 1e-13 to 1e-12 apart), and the shortest digits are that decimal if it holds one; no rounding
  // boundary of 12 digits (a 12-digit decimal, or a tie ending in 5 at the 13th) then lies between
  // the value and its shortest digits, unless the shortest digits are that tie. Ties are written
  // by std::to_chars at precision 12 (the exact value decides, the slow way), and so are
  // subnormal numbers, whose intervals are wider.
  if (std::fabs(value) < std::numeric_limits<double>::min())
    return std::to_chars(out, out + 32, value, std::chars_format::general, kPrecision).ptr;
  char sci[40];
  const char* const sci_end =
      std::to_chars(sci, sci + sizeof sci, value, std::chars_format::scientific).ptr;
  const char* p = sci;
  const bool negative = *p == '-';
  if (negative) ++p;
  char d[24];
  int n = 0;
  for (; p < sci_end && *p != 'e'; ++p) {
    if (*p != '.') d[n++] = *p;
  }
  ++p;  // 'e'
  const bool exponent_negative = *p == '-';
  ++p;
  int exponent = 0;
  for (; p < sci_end; ++p) exponent = 10 * exponent + (*p - '0');
  if (exponent_negative) exponent = -exponent;
  if (n > kPrecision) {
    if (n == kPrecision + 1 && d[kPrecision] == '5')
      return std::to_chars(out, out + 32, value, std::chars_format::general, kPrecision).ptr;
    const bool up = d[kPrecision] >= '5';
    n = kPrecision;
    if (up) {
      int i = n - 1;
      while (i >= 0 && d[i] == '9') --i;
      if (i < 0) {
        d[0] = '1';
        n = 1;
        ++exponent;
      } else {
        ++d[i];
        n = i + 1;
      }
    }
    while (n > 1 && d[n - 1] == '0') --n;
  }
  // "%g": exponent notation below 1e-4 and from 1e12 on, else fixed; no trailing zeros.
  if (negative) *out++ = '-';
  if (exponent < -4 || exponent >= kPrecision) {
    *out++ = d[0];
    if (n > 1) {
      *out++ = '.';
      std::memcpy(out, d + 1, static_cast<std::size_t>(n - 1));
      out += n - 1;
    }
    *out++ = 'e';
    *out++ = exponent < 0 ? '-' : '+';
    const int e = exponent < 0 ? -exponent : exponent;
    if (e >= 100) *out++ = static_cast<char>('0' + e / 100);
    *out++ = static_cast<char>('0' + e / 10 % 10);
    *out++ = static_cast<char>('0' + e % 10);
  } else if (exponent >= 0) {
    const int whole = exponent + 1;  // digits before the point
    for (int i = 0; i < whole; ++i) *out++ = i < n ? d[i] : '0';
    if (n > whole) {
      *out++ = '.';
      std::memcpy(out, d + whole, static_cast<std::size_t>(n - whole));
      out += n - whole;
    }
  } else {
    *out++ = '0';
    *out++ = '.';
    for (int i = 0; i < -exponent - 1; ++i) *out++ = '0';
    std::memcpy(out, d, static_cast<std::size_t>(n));
    out += n;
  }
  return out;
}

CsvWriter::CsvWriter(const std::filesystem::path& path, std::vector<std::string> columns,
                     bool append)
    : path_(path),
      out_(path, append ? std::ios::app : std::ios::trunc),
      buffer_(new char[kBuffer]),
      columns_(columns.size()) {
  if (!out_) throw OutputError("cannot write " + path.string() + ": " + std::strerror(errno));
  if (append) return;
  for (std::size_t i = 0; i < columns.size(); ++i) out_ << (i ? "," : "") << columns[i];
  // In the file at once: a restart file taken before the first rows are flushed (a checkpoint
  // in the first stage) carries the file as it is on disk, and its run appends to it.
  out_ << "\n" << std::flush;
}

CsvWriter::CsvWriter(std::size_t columns)
    : memory_(true), buffer_(new char[kBuffer]), columns_(columns) {}

std::string CsvWriter::take() {
  text_.append(buffer_.get(), used_);
  used_ = 0;
  std::string out;
  out.swap(text_);
  return out;
}

void CsvWriter::raw(std::string_view rows) {
  if (in_row_ != 0) throw std::logic_error(path_.string() + ": rows added inside a row");
  append(rows.data(), rows.size());
}

CsvWriter::~CsvWriter() {
  // Rows not yet flushed go to the file (as the stream's own buffer would at its close).
  if (!memory_ && used_ > 0 && out_) out_.write(buffer_.get(), static_cast<std::streamsize>(used_));
}

void CsvWriter::write_buffer() {
  if (memory_) {
    text_.append(buffer_.get(), used_);
    used_ = 0;
    return;
  }
  out_.write(buffer_.get(), static_cast<std::streamsize>(used_));
  used_ = 0;
  if (!out_)
    throw OutputError("cannot write " + path_.string() + ": the write failed (a full disk?)");
}

void CsvWriter::flush() {
  write_buffer();
  if (memory_) return;
  out_.flush();
  if (!out_)
    throw OutputError("cannot write " + path_.string() + ": the write failed (a full disk?)");
}

void CsvWriter::append(const char* text, std::size_t size) {
  if (size > kBuffer / 2) {
    write_buffer();
    if (memory_) {
      text_.append(text, size);
      return;
    }
    out_.write(text, static_cast<std::streamsize>(size));
    return;
  }
  std::memcpy(room(size), text, size);
  used_ += size;
}

CsvWriter& CsvWriter::cell(double value) {
  separator();
  if (std::isfinite(value)) {
    // The text of the stream at precision 12 (printf's "%.12g"), byte for byte, without the
    // stream's locale and format machinery (the hot part of writing large tables).
    used_ = static_cast<std::size_t>(write_general12(room(kCell), value) - buffer_.get());
  } else {
    const char* text = std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf");
    append(text, std::strlen(text));
  }
  return *this;
}

CsvWriter& CsvWriter::cell(long long value) {
  separator();
  char* at = room(kCell);
  used_ = static_cast<std::size_t>(std::to_chars(at, at + kCell, value).ptr - buffer_.get());
  return *this;
}

CsvWriter& CsvWriter::cell(const std::string& value) {
  separator();
  if (value.find_first_of(",\"\n") == std::string::npos) {
    append(value.data(), value.size());
  } else {
    std::string quoted = "\"";
    for (char c : value) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    quoted += '"';
    append(quoted.data(), quoted.size());
  }
  return *this;
}

void CsvWriter::end_row() {
  if (in_row_ != columns_) {
    throw std::logic_error(path_.string() + ": row has " + std::to_string(in_row_) +
                           " cells, header has " + std::to_string(columns_));
  }
  *room(1) = '\n';
  ++used_;
  in_row_ = 0;
}

}  // namespace blockdem
