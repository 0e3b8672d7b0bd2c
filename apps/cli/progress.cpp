// Terminal progress line.
#include "progress.hpp"

#include <unistd.h>

#include <cstdio>
#include <iostream>

namespace blockdem::cli {

Progress::Progress(bool enabled) : interactive_(enabled && isatty(STDERR_FILENO) != 0) {}

Progress::~Progress() {
  if (dirty_) std::cerr << "\n";
}

void Progress::update(const std::string& line) {
  if (!interactive_) return;
  std::cerr << "\r\033[K" << line << std::flush;
  dirty_ = true;
}

void Progress::message(const std::string& line) {
  if (dirty_) std::cerr << "\r\033[K";
  dirty_ = false;
  std::cerr << line << "\n" << std::flush;
}

}  // namespace blockdem::cli
