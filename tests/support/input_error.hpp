// What the command-line program does with bad input: exit code 2, one message that starts with
// "blockdem:" and names the file (where there is one), the key and the reason, nothing written.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "temp_path.hpp"

namespace blockdem::test {

/// A fresh, empty folder `name` under this process's temporary folder `suite`.
inline std::filesystem::path fresh_case_dir(const std::string& suite, const std::string& name) {
  const std::filesystem::path dir = temp_path(suite) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// Exit code 2, a message starting with "blockdem:" that holds every fragment, and `out` not
/// written.
inline void expect_input_error(const CommandOutput& r, const std::filesystem::path& out,
                               const std::vector<std::string>& fragments) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err.rfind("blockdem:", 0), 0u) << r.err;
  for (const auto& f : fragments) EXPECT_NE(r.err.find(f), std::string::npos) << f << "\n" << r.err;
  EXPECT_FALSE(std::filesystem::exists(out)) << "an input error wrote " << out;
}

}  // namespace blockdem::test
