// CsvWriter: numbers print as a stream at precision 12 prints them (printf's "%.12g").
#include "blockdem/io/csv.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

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

  const auto path = std::filesystem::temp_directory_path() / "blockdem_csv_test.csv";
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

}  // namespace
}  // namespace blockdem
