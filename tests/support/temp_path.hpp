#pragma once
// A path in the system's temporary folder that is this test process's own: suites that run side
// by side (ctest -j, two checkouts, sanitizer builds) never share a file or a folder.

#include <unistd.h>

#include <filesystem>
#include <string>

namespace blockdem::test {

/// temp/blockdem_<pid>_<name>; name may end in an extension (".csv").
inline std::filesystem::path temp_path(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("blockdem_" + std::to_string(::getpid()) + "_" + name);
}

}  // namespace blockdem::test
