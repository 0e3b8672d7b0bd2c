// The error of a file or folder the operating system would not let the program write: a folder
// without write permission or that cannot exist (/proc/x), a full disk. Not a defect of the
// program nor of its input: the command-line program ends it with its own exit code.
#pragma once

#include <stdexcept>
#include <string>

namespace blockdem {

class OutputError : public std::runtime_error {
 public:
  explicit OutputError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace blockdem
