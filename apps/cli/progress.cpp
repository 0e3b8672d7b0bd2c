// Terminal progress line.
#include "progress.hpp"

#include <unistd.h>

#include <cstdio>
#include <iostream>

namespace blockdem::cli {

Progress::Progress(bool enabled, double log_interval)
    : enabled_(enabled),
      interactive_(enabled && isatty(STDERR_FILENO) != 0),
      log_interval_(log_interval),
      last_line_(std::chrono::steady_clock::now()) {}

Progress::~Progress() {
  if (dirty_) std::cerr << "\n";
}

void Progress::update(const std::string& line) {
  if (!enabled_) return;
  if (!interactive_) {
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last_line_).count() < log_interval_) return;
    last_line_ = now;
    std::cerr << line << "\n" << std::flush;
    return;
  }
  std::cerr << "\r\033[K" << line << std::flush;
  dirty_ = true;
}

void Progress::message(const std::string& line) {
  if (dirty_) std::cerr << "\r\033[K";
  dirty_ = false;
  std::cerr << line << "\n" << std::flush;
}

}  // namespace blockdem::cli
