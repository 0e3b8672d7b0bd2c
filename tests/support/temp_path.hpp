#pragma once
// Paths in the system's temporary folder that are this test process's own: suites that run side
// by side (ctest -j, two checkouts, sanitizer builds) never share a file or a folder. Every such
// path is registered and removed, with whatever was written under it, when the process ends
// (after the last test, passed or failed), unless the environment variable
// BLOCKDEM_KEEP_TEST_FILES is set: then the process prints once which of them it left, for a
// failing test's files to be inspected. A process that is killed or crashes cannot remove them.

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <set>
#include <string>
#include <system_error>

namespace blockdem::test {

/// The registry of the temporary paths of this process: a static object, destroyed (and the
/// paths removed) when the process exits normally.
class TempFiles {
 public:
  static TempFiles& instance() {
    static TempFiles files;
    return files;
  }

  /// Removes `path` (a file or a folder, made yet or not) at exit.
  void add(const std::filesystem::path& path) {
    const std::lock_guard<std::mutex> lock(mutex_);
    paths_.insert(path);
  }

  TempFiles(const TempFiles&) = delete;
  TempFiles& operator=(const TempFiles&) = delete;

  ~TempFiles() {
    // A forked child that exits through exit() leaves the files of the process that made them.
    if (::getpid() != owner_) return;
    if (std::getenv("BLOCKDEM_KEEP_TEST_FILES") != nullptr) {
      std::string kept;
      for (const auto& p : paths_) {
        std::error_code ec;
        if (std::filesystem::exists(p, ec)) kept += "  " + p.string() + "\n";
      }
      if (!kept.empty())
        std::fprintf(stderr, "BLOCKDEM_KEEP_TEST_FILES is set: this test process kept\n%s",
                     kept.c_str());
      return;
    }
    for (const auto& p : paths_) {
      std::error_code ignored;
      std::filesystem::remove_all(p, ignored);
    }
  }

 private:
  TempFiles() = default;

  std::mutex mutex_;
  std::set<std::filesystem::path> paths_;
  pid_t owner_ = ::getpid();
};

/// Registers `path` for removal when the process ends (see TempFiles) and returns it.
inline std::filesystem::path remove_at_exit(const std::filesystem::path& path) {
  TempFiles::instance().add(path);
  return path;
}

/// temp/blockdem_<pid>_<name>, removed at exit; name may end in an extension (".csv").
inline std::filesystem::path temp_path(const std::string& name) {
  return remove_at_exit(std::filesystem::temp_directory_path() /
                        ("blockdem_" + std::to_string(::getpid()) + "_" + name));
}

}  // namespace blockdem::test
