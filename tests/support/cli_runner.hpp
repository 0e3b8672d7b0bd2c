// Runs the blockdem program from a test: exit code, stdout and stderr of one command line.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "temp_path.hpp"

namespace blockdem::test {

struct CommandOutput {
  int exit_code = -1;  ///< -1 when the program did not exit normally (e.g. a signal)
  std::string out;
  std::string err;
};

/// Runs `BLOCKDEM_CLI_PATH arguments` through the shell, capturing stdout through a pipe and
/// stderr through a temporary file. `environment` (e.g. "NAME=value ") goes before the program.
inline CommandOutput run_cli(const std::string& arguments, const std::string& environment = "") {
  static std::atomic<int> counter{0};
  const std::filesystem::path err_path =
      temp_path("cli_test_" + std::to_string(counter++) + ".err");
  const std::string command =
      environment + BLOCKDEM_CLI_PATH + " " + arguments + " 2>'" + err_path.string() + "'";
  CommandOutput result;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer{};
  std::size_t count = 0;
  while ((count = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) {
    result.out.append(buffer.data(), count);
  }
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream err(err_path);
  result.err.assign(std::istreambuf_iterator<char>(err), std::istreambuf_iterator<char>());
  err.close();
  std::filesystem::remove(err_path);
  return result;
}

}  // namespace blockdem::test
