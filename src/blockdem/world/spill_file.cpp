// SpillFile: an unlinked scratch file, written through a StateWriter and read back mapped.
#include "blockdem/world/spill_file.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <string_view>
#include <system_error>
#include <vector>

namespace blockdem {
namespace {

// $TMPDIR, else /var/tmp, else /tmp: /var/tmp is on disk where /tmp may be a tmpfs (Debian 13's
// default), whose files take memory, which the file is there to save.
std::string scratch_folder() {
  const char* dir = std::getenv("TMPDIR");
  if (dir && *dir) return dir;
  if (::access("/var/tmp", W_OK | X_OK) == 0) return "/var/tmp";
  return "/tmp";
}

// A filesystem_error: the system's refusal (a full disk, a folder that is not there), which the
// program reports as such (exit code 4), not as a defect.
[[noreturn]] void fail(const std::string& folder, const std::string& what, int err) {
  throw std::filesystem::filesystem_error(
      "cannot " + what + " the divergence checkpoint's scratch file in " + folder +
          " (set TMPDIR to a folder with room, or raise checkpoint_memory_mib to keep the "
          "checkpoint in memory)",
      std::filesystem::path(folder), std::error_code(err, std::generic_category()));
}

}  // namespace

std::shared_ptr<const SpillFile> SpillFile::write(const std::function<void(StateWriter&)>& fill) {
  const std::string folder = scratch_folder();
  std::string name = folder + "/blockdem-checkpoint-XXXXXX";
  std::vector<char> path(name.begin(), name.end());
  path.push_back('\0');
  // Closed on exec: a program the run starts (the figures' scripts) does not keep it.
  const int fd = ::mkostemp(path.data(), O_CLOEXEC);
  if (fd < 0) fail(folder, "make", errno);
  // Unlinked at once: the open descriptor keeps the file until it is closed.
  ::unlink(path.data());
  std::shared_ptr<SpillFile> file(new SpillFile(fd, folder));
  StateWriter w(
      [&](std::string_view bytes) {
        while (!bytes.empty()) {
          const ssize_t n = ::write(file->fd_, bytes.data(), bytes.size());
          if (n < 0 && errno == EINTR) continue;
          if (n <= 0) fail(folder, "write", n < 0 ? errno : ENOSPC);
          bytes.remove_prefix(static_cast<std::size_t>(n));
          file->size_ += static_cast<std::size_t>(n);
        }
      },
      std::size_t{4} << 20);
  fill(w);
  w.flush();
  return file;
}

SpillFile::~SpillFile() {
  if (fd_ >= 0) ::close(fd_);
}

void SpillFile::read(const std::function<void(StateReader&)>& read) const {
  if (size_ == 0) {
    StateReader r(nullptr, 0);
    read(r);
    return;
  }
  void* map = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd_, 0);
  if (map == MAP_FAILED) fail(folder_, "map", errno);
  const auto* data = static_cast<const std::uint8_t*>(map);
  StateReader r(data, size_);
  // Give back the pages behind the reader every 64 MiB (they are the file's: nothing is lost).
  const std::size_t page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
  std::size_t released = 0;
  r.on_progress(std::size_t{64} << 20, [&](std::size_t at) {
    const std::size_t end = at / page * page;
    if (end <= released) return;
    ::madvise(const_cast<std::uint8_t*>(data) + released, end - released, MADV_DONTNEED);
    released = end;
  });
  try {
    read(r);
  } catch (...) {
    ::munmap(map, size_);
    throw;
  }
  ::munmap(map, size_);
}

void SpillFile::copy_to(StateWriter& w) const {
  std::vector<char> buffer(std::size_t{4} << 20);
  std::size_t at = 0;
  while (at < size_) {
    const ssize_t n =
        ::pread(fd_, buffer.data(), std::min(buffer.size(), size_ - at), static_cast<off_t>(at));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail(folder_, "read", n < 0 ? errno : EIO);
    w.raw(std::string_view(buffer.data(), static_cast<std::size_t>(n)));
    at += static_cast<std::size_t>(n);
  }
}

}  // namespace blockdem
