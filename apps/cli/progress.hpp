// Progress display on a terminal: one line, rewritten in place; silent when stderr is not a
// terminal (logs get one line per stage instead, from the caller).
#pragma once

#include <string>

namespace blockdem::cli {

class Progress {
 public:
  explicit Progress(bool enabled);
  ~Progress();
  /// Rewrites the status line (no newline).
  void update(const std::string& line);
  /// Ends the status line and prints `line` on its own.
  void message(const std::string& line);
  bool interactive() const { return interactive_; }

 private:
  bool interactive_ = false;
  bool dirty_ = false;
};

}  // namespace blockdem::cli
