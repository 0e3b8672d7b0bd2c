// Test support for the calibration tests: synthetic data sets written by
// tools/make_synthetic_calibration_data.py (the independent, closed-form generator), a scratch
// directory per test process, and helpers to catch error messages.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "blockdem/calibration/calibration_data.hpp"
#include "blockdem/calibration/calibration_report.hpp"
#include "support/temp_path.hpp"

namespace blockdem::test {

/// A directory of this test process, created on first use and removed at exit (temp_path).
inline std::filesystem::path scratch_directory() {
  static const std::filesystem::path path = [] {
    const std::filesystem::path p = temp_path("calibration_test");
    std::filesystem::create_directories(p);
    return p;
  }();
  return path;
}

/// Debian's /usr/bin/python3 when it exists (the script needs only the standard library).
inline std::string test_python() {
  return std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
}

/// Runs the synthetic-data script with `arguments` (e.g. "normal --noise 0.02") into
/// scratch_directory()/name and returns the path; a file already made under that name is reused
/// (each name stands for one set of arguments). Fails the test if the script fails.
inline std::filesystem::path synthetic_data(const std::string& arguments, const std::string& name) {
  const std::filesystem::path out = scratch_directory() / name;
  if (std::filesystem::exists(out)) return out;
  const std::string command =
      test_python() + " '" BLOCKDEM_SOURCE_DIR "/tools/make_synthetic_calibration_data.py' " +
      arguments + " --out '" + out.string() + "'";
  const int status = std::system(command.c_str());
  EXPECT_EQ(status, 0) << command;
  return out;
}

/// Writes `text` to scratch_directory()/name and returns the path.
inline std::filesystem::path write_file(const std::string& name, const std::string& text) {
  const std::filesystem::path path = scratch_directory() / name;
  std::ofstream(path) << text;
  return path;
}

/// The message of the CalibrationError thrown by f, or "" if none is thrown.
template <class Function>
std::string calibration_error(Function&& f) {
  try {
    f();
  } catch (const CalibrationError& e) {
    return e.what();
  }
  return "";
}

/// |a - b| / |b|.
inline double relative_error(double a, double b) {
  return std::abs(a - b) / std::abs(b);
}

}  // namespace blockdem::test
