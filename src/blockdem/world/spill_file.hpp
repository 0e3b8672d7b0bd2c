// A scratch file for state a run may need back but seldom does (the divergence checkpoint of a
// large world): written once, then read or copied whole, never changed.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>

#include "blockdem/world/state_stream.hpp"

namespace blockdem {

/// An unnamed file in $TMPDIR (else /var/tmp, else /tmp): made and unlinked at once, so that its
/// space is given back when the last owner lets it go, or when the process ends however it ends.
/// Shared between copies of a world (a stability search's trials): it never changes once written.
class SpillFile {
 public:
  /// A new file holding what `fill` writes to the StateWriter it is given. Throws
  /// std::filesystem::filesystem_error naming the folder and the reason if the file cannot be
  /// made or written (nothing is left behind).
  static std::shared_ptr<const SpillFile> write(const std::function<void(StateWriter&)>& fill);

  SpillFile(const SpillFile&) = delete;
  SpillFile& operator=(const SpillFile&) = delete;
  ~SpillFile();

  std::size_t size() const { return size_; }
  /// Calls `read` with a reader over the file's bytes, mapped read-only; the pages it has passed
  /// are given back as it goes, so that reading does not hold the whole file in memory.
  void read(const std::function<void(StateReader&)>& read) const;
  /// Appends the file's bytes to `w`, a piece at a time.
  void copy_to(StateWriter& w) const;

 private:
  SpillFile(int fd, std::string folder) : fd_(fd), folder_(std::move(folder)) {}
  int fd_ = -1;
  std::string folder_;  ///< where the file was made, for error messages
  std::size_t size_ = 0;
};

}  // namespace blockdem
