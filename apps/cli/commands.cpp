// Shared state of the command-line program: version, exit code, option checks.
#include "commands.hpp"

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "blockdem/world/world.hpp"

namespace blockdem::cli {
namespace {
int g_exit_code = 0;
}

const char* version() {
  return BLOCKDEM_VERSION;
}
int exit_code() {
  return g_exit_code;
}
void set_exit_code(int code) {
  g_exit_code = code;
}

void check_thread_count(int threads) {
  if (threads > thread_limit())
    throw std::invalid_argument("--threads: at most " + std::to_string(thread_limit()) +
                                " on this machine (64 per core, at most 1024), got " +
                                std::to_string(threads));
}

CLI::Validator positive_number(const std::string& what) {
  return CLI::Validator(
      [what](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !std::isfinite(v) || !(v > 0.0))
          return "must be a finite positive number of " + what + ", got " + text;
        return {};
      },
      "> 0");
}

}  // namespace blockdem::cli
