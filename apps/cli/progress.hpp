// Progress display: on a terminal one line, rewritten in place; otherwise (a log file, a pipe) the
// latest status as a line of its own every few seconds.
#pragma once

#include <chrono>
#include <string>

namespace blockdem::cli {

class Progress {
 public:
  /// `enabled`: false for --quiet. `log_interval`: seconds between status lines when stderr is
  /// not a terminal.
  explicit Progress(bool enabled, double log_interval = 5.0);
  ~Progress();
  /// Rewrites the status line (no newline); not on a terminal, prints it when log_interval has
  /// passed since the last printed line.
  void update(const std::string& line);
  /// Ends the status line and prints `line` on its own.
  void message(const std::string& line);
  bool interactive() const { return interactive_; }

 private:
  bool enabled_ = false;
  bool interactive_ = false;
  bool dirty_ = false;
  double log_interval_ = 5.0;  ///< (s)
  std::chrono::steady_clock::time_point last_line_;
};

}  // namespace blockdem::cli
