// CsvWriter: numbers print as a stream at precision 12 prints them (printf's "%.12g").
#include "blockdem/io/csv.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "blockdem/io/output_error.hpp"
#include "support/temp_path.hpp"

namespace blockdem {
namespace {

std::string read_all(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Reference: an output stream at precision 12, the writer's text before it formatted numbers
// itself; checked against printf's "%.12g" too.
std::string stream_text(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  char c[64];
  std::snprintf(c, sizeof c, "%.12g", v);
  EXPECT_EQ(s.str(), std::string(c)) << "stream and printf disagree on " << v;
  return s.str();
}

TEST(CsvWriter, NumbersAreTheTextOfAStreamAtPrecision12) {
  std::vector<double> values = {0.0,
                                -0.0,
                                1.0,
                                -1.5,
                                0.1,
                                1.0 / 3.0,
                                2.0 / 3.0,
                                123456789012.0,
                                1234567890123.0,
                                999999999999.5,
                                9.999999999995e-5,
                                1e-5,
                                1e21,
                                1e-300,
                                2.42165035894e-42,
                                std::numeric_limits<double>::denorm_min(),
                                std::numeric_limits<double>::max(),
                                -std::numeric_limits<double>::min(),
                                0.023,
                                -2.50000000007e-08};
  // Random values over the whole exponent range, and values near rounding ties.
  std::mt19937_64 rng(20261125);
  std::uniform_real_distribution<double> mantissa(-10.0, 10.0);
  std::uniform_int_distribution<int> exponent(-320, 300);
  for (int i = 0; i < 2000; ++i) values.push_back(std::ldexp(mantissa(rng), exponent(rng)));
  for (int i = 1; i < 200; ++i) values.push_back(static_cast<double>(i) * 0.5e-12 + 1.0);
  const std::vector<long long> integers = {0,
                                           1,
                                           -1,
                                           42,
                                           1000000007,
                                           std::numeric_limits<long long>::max(),
                                           std::numeric_limits<long long>::min()};

  const auto path = test::temp_path("csv_test.csv");
  std::string expected = "x,n\n";
  {
    CsvWriter csv(path, {"x", "n"});
    for (std::size_t i = 0; i < values.size(); ++i) {
      const long long n = integers[i % integers.size()];
      csv.cell(values[i]).cell(n);
      csv.end_row();
      expected += stream_text(values[i]) + "," + std::to_string(n) + "\n";
    }
    csv.cell(std::numeric_limits<double>::quiet_NaN())
        .cell(std::numeric_limits<double>::infinity());
    csv.end_row();
    expected += "nan,inf\n";
  }
  EXPECT_EQ(read_all(path), expected);
  std::filesystem::remove(path);
}

// The writer's own "%.12g" against printf's, on values that end on a tie at the 13th digit in
// their shortest digits (the exact value decides), values whose rounding carries into a new
// digit, random bit patterns of every exponent, and values where fixed and exponent notation
// meet.
TEST(CsvWriter, General12IsPrintfsText) {
  std::vector<double> values;
  std::mt19937_64 rng(20261126);
  // 13-digit decimals ending in 5 (ties in their shortest digits) at many scales, and their
  // neighbouring doubles.
  std::uniform_int_distribution<long long> mantissa13(100000000000LL, 999999999999LL);
  std::uniform_int_distribution<int> scale(-40, 40);
  for (int i = 0; i < 20000; ++i) {
    const std::string text = std::to_string(mantissa13(rng)) + "5e" + std::to_string(scale(rng));
    const double v = std::strtod(text.c_str(), nullptr);
    values.push_back(v);
    values.push_back(std::nextafter(v, 0.0));
    values.push_back(std::nextafter(v, 1e300));
    values.push_back(-v);
  }
  // Carries: 12 nines and more, at the notation's boundaries 1e-5, 1e-4, 1e11, 1e12.
  for (int e = -330; e <= 308; ++e) {
    for (const char* m : {"9.999999999995", "9.9999999999949", "9.99999999999951",
                          "9.99999999999999", "1", "1.00000000000049", "5", "4.99999999999950"}) {
      const double v = std::strtod((std::string(m) + "e" + std::to_string(e)).c_str(), nullptr);
      if (!std::isfinite(v)) continue;
      values.push_back(v);
      values.push_back(std::nextafter(v, 0.0));
      values.push_back(std::nextafter(v, 1e300));
    }
  }
  // Random bit patterns (every exponent, subnormals included) and random short decimals.
  std::uniform_int_distribution<std::uint64_t> bits;
  for (int i = 0; i < 200000; ++i) {
    double v;
    const std::uint64_t b = bits(rng);
    std::memcpy(&v, &b, sizeof v);
    if (std::isfinite(v)) values.push_back(v);
  }
  std::uniform_int_distribution<long long> short_mantissa(1, 99999999);
  for (int i = 0; i < 50000; ++i) {
    values.push_back(static_cast<double>(short_mantissa(rng)) * std::pow(10.0, scale(rng)));
  }
  values.push_back(std::numeric_limits<double>::denorm_min());
  values.push_back(std::numeric_limits<double>::max());
  values.push_back(-0.0);
  values.push_back(0.0);
  int differ = 0;
  for (double v : values) {
    char ours[40], theirs[64];
    const std::string got(ours, write_general12(ours, v));
    std::snprintf(theirs, sizeof theirs, "%.12g", v);
    if (got != theirs && ++differ <= 10) ADD_FAILURE() << "ours " << got << ", printf " << theirs;
  }
  EXPECT_EQ(differ, 0) << "of " << values.size() << " values";
}

// /dev/full refuses every write as a full disk does: the writer says so with an OutputError
// naming the file (the command-line program's exit code 4, not an internal error).
TEST(CsvWriter, AFullDiskIsAnOutputErrorNamingTheFile) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full on this system";
  try {
    CsvWriter w("/dev/full", {"a"});
    w.cell(1.0);
    w.end_row();
    w.flush();
    ADD_FAILURE() << "a write to /dev/full did not fail";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("/dev/full"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace blockdem
