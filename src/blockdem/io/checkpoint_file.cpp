// Checkpoint envelope. Layout (byte offsets): 0 magic (8 bytes, "\x89BDCK\r\n\x1a": the CR-LF
// and the high byte catch text-mode and 7-bit transfers), 8 byte-order mark 0x01020304 (u32),
// 12 format version (u32), 16 scenario hash (u64), 24 payload size n (u64), 32 payload,
// 32 + n FNV-1a 64 of bytes [0, 32 + n) (u64). Integers in the writer's byte order.
#include "blockdem/io/checkpoint_file.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "blockdem/io/atomic_file.hpp"
#include "blockdem/io/output_error.hpp"

namespace blockdem {
namespace {

constexpr char kMagic[8] = {'\x89', 'B', 'D', 'C', 'K', '\r', '\n', '\x1a'};
constexpr std::uint32_t kByteOrder = 0x01020304u;
constexpr std::size_t kHeader = 32;

template <class T>
void put(std::string& s, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  s.append(b, sizeof(T));
}

std::string header(std::uint64_t scenario_hash, std::uint64_t payload_size) {
  std::string bytes(kMagic, sizeof kMagic);
  put(bytes, kByteOrder);
  put(bytes, kCheckpointVersion);
  put(bytes, scenario_hash);
  put(bytes, payload_size);
  return bytes;
}

// The last checkpoint becomes NAME.prev by a second name (a hard link; a copy where the file
// system has none), then the new one replaces NAME by a rename: at every moment NAME is a whole
// checkpoint, also when the process is killed in between.
void keep_previous(const std::filesystem::path& file) {
  std::error_code ec;
  if (std::filesystem::exists(file, ec)) {
    std::filesystem::path prev = file;
    prev += ".prev";
    std::filesystem::remove(prev, ec);
    std::filesystem::create_hard_link(file, prev, ec);
    if (ec)
      std::filesystem::copy_file(file, prev, std::filesystem::copy_options::overwrite_existing, ec);
  }
}

[[noreturn]] void fail_checkpoint(const std::filesystem::path& file, const char* what) {
  throw OutputError("cannot write " + file.string() + ": " + what + " (" + std::strerror(errno) +
                    ")");
}

constexpr std::size_t kBufferBytes = std::size_t{1} << 20;
/// A reader's checksum goes over the file in chunks of this size (a mapped file's pages are
/// given back after each).
constexpr std::size_t kHashChunkBytes = std::size_t{16} << 20;

}  // namespace

CheckpointFileWriter::CheckpointFileWriter(const std::filesystem::path& file,
                                           std::uint64_t scenario_hash)
    : file_(file), scenario_hash_(scenario_hash) {
  // The temporary name of write_file_atomically (a run's folder clean-up knows it).
  const std::filesystem::path dir = file.has_parent_path() ? file.parent_path() : ".";
  std::string name(1, '.');
  name.append(file.filename().string()).append(".tmp");
  tmp_ = dir / name;
  fd_ = ::open(tmp_.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) fail_checkpoint(file_, "cannot create the temporary file");
}

CheckpointFileWriter::~CheckpointFileWriter() {
  if (fd_ < 0) return;
  ::close(fd_);
  ::unlink(tmp_.c_str());
}

void CheckpointFileWriter::write_at(std::uint64_t at, std::string_view bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n =
        ::pwrite(fd_, bytes.data() + done, bytes.size() - done, static_cast<off_t>(at + done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail_checkpoint(file_, "write failed");
    done += static_cast<std::size_t>(n);
  }
}

void CheckpointFileWriter::flush() {
  write_at(kHeader + written_, buffer_);
  written_ += buffer_.size();
  buffer_.clear();
}

void CheckpointFileWriter::append(std::string_view bytes) {
  size_ += bytes.size();
  if (buffer_.size() + bytes.size() < kBufferBytes) {
    buffer_.append(bytes);
    return;
  }
  // A large piece goes to the file as it is, not through the buffer (no copy of it is held).
  flush();
  write_at(kHeader + written_, bytes);
  written_ += bytes.size();
}

void CheckpointFileWriter::patch(std::uint64_t at, std::string_view bytes) {
  if (at + bytes.size() > size_) throw std::logic_error("checkpoint patch past the end");
  // The part still buffered is patched there, the rest in the file.
  for (std::size_t k = 0; k < bytes.size(); ++k) {
    const std::uint64_t p = at + k;
    if (p >= written_)
      buffer_[static_cast<std::size_t>(p - written_)] = bytes[k];
    else
      write_at(kHeader + p, bytes.substr(k, 1));
  }
}

void CheckpointFileWriter::finish() {
  flush();
  write_at(0, header(scenario_hash_, size_));
  // The checksum of header and payload, read back in chunks (never the whole file in memory).
  std::uint64_t hash = 14695981039346656037ull;
  std::vector<char> chunk(kBufferBytes);
  for (std::uint64_t at = 0, end = kHeader + size_; at < end;) {
    const auto want = static_cast<std::size_t>(std::min<std::uint64_t>(chunk.size(), end - at));
    const ssize_t n = ::pread(fd_, chunk.data(), want, static_cast<off_t>(at));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail_checkpoint(file_, "read back failed");
    hash = fnv1a64(std::string_view(chunk.data(), static_cast<std::size_t>(n)), hash);
    at += static_cast<std::uint64_t>(n);
  }
  std::string tail;
  put(tail, hash);
  write_at(kHeader + size_, tail);
  if (::fsync(fd_) != 0) fail_checkpoint(file_, "fsync failed");
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) {
    ::unlink(tmp_.c_str());
    fail_checkpoint(file_, "close failed");
  }
  keep_previous(file_);
  if (::rename(tmp_.c_str(), file_.c_str()) != 0) {
    ::unlink(tmp_.c_str());
    fail_checkpoint(file_, "rename failed");
  }
  const std::filesystem::path dir = file_.has_parent_path() ? file_.parent_path() : ".";
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

void write_checkpoint_file(const std::filesystem::path& file, std::uint64_t scenario_hash,
                           std::string_view payload) {
  std::string bytes = header(scenario_hash, payload.size());
  bytes.append(payload);
  put(bytes, fnv1a64(bytes));
  keep_previous(file);
  write_file_atomically(file, bytes);
}

namespace {

// The envelope's checks in read_checkpoint_file's order, on the file's bytes; returns the
// payload's size. `hashed` is told after each chunk of the checksum (the bytes before that file
// offset are not read again).
std::size_t check_envelope(const std::filesystem::path& file, std::string_view bytes,
                           const std::vector<std::uint64_t>& accepted,
                           const std::function<void(std::size_t)>& hashed) {
  const auto get_at = [&bytes]<class T>(T, std::size_t at) {
    T v;
    std::memcpy(&v, bytes.data() + at, sizeof(T));
    return v;
  };
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    throw CheckpointError(file, "not a blockdem checkpoint (wrong magic number)");
  if (bytes.size() < kHeader + 8) throw CheckpointError(file, "truncated (shorter than a header)");
  if (get_at(std::uint32_t{}, 8) != kByteOrder)
    throw CheckpointError(file, "written on a machine of the other byte order");
  const auto version = get_at(std::uint32_t{}, 12);
  if (version != kCheckpointVersion)
    throw CheckpointError(file, "format version " + std::to_string(version) +
                                    "; this blockdem reads version " +
                                    std::to_string(kCheckpointVersion));
  const auto size = get_at(std::uint64_t{}, 24);
  if (size != bytes.size() - kHeader - 8)
    throw CheckpointError(file, "truncated or padded: the header announces " +
                                    std::to_string(size) + " bytes of state, the file holds " +
                                    std::to_string(bytes.size() - kHeader - 8));
  const std::size_t body = kHeader + static_cast<std::size_t>(size);
  std::uint64_t hash = fnv1a64({});
  for (std::size_t at = 0; at < body;) {
    const std::size_t n = std::min(kHashChunkBytes, body - at);
    hash = fnv1a64(bytes.substr(at, n), hash);
    at += n;
    if (hashed) hashed(at);
  }
  if (get_at(std::uint64_t{}, body) != hash)
    throw CheckpointError(file, "corrupt (checksum mismatch)");
  if (std::find(accepted.begin(), accepted.end(), get_at(std::uint64_t{}, 16)) == accepted.end())
    throw CheckpointScenarioError(
        file,
        "written for another scenario or other run options (--max-steps): the "
        "settings, blocks, laws and outputs, and the stages up to the "
        "checkpoint's, must be those of the run that wrote it (later stages "
        "may differ)");
  return static_cast<std::size_t>(size);
}

}  // namespace

std::string read_checkpoint_file(const std::filesystem::path& file, std::uint64_t scenario_hash) {
  return read_checkpoint_file(file, std::vector<std::uint64_t>{scenario_hash});
}

std::string read_checkpoint_file(const std::filesystem::path& file,
                                 const std::vector<std::uint64_t>& accepted) {
  std::string bytes;
  try {
    bytes = read_file_bytes(file);
  } catch (const std::runtime_error&) {
    throw CheckpointError(file, "cannot be read");
  }
  const std::size_t size = check_envelope(file, bytes, accepted, {});
  // The payload in place (no second copy of a file that can hold a large world).
  bytes.resize(kHeader + size);
  bytes.erase(0, kHeader);
  return bytes;
}

MappedCheckpoint::MappedCheckpoint(const std::filesystem::path& file, std::uint64_t scenario_hash)
    : MappedCheckpoint(file, std::vector<std::uint64_t>{scenario_hash}) {}

MappedCheckpoint::MappedCheckpoint(const std::filesystem::path& file,
                                   const std::vector<std::uint64_t>& accepted) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  struct stat st {};
  if (fd < 0 || ::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    if (fd >= 0) ::close(fd);
    throw CheckpointError(file, "cannot be read");
  }
  size_ = static_cast<std::size_t>(st.st_size);
  if (size_ > 0) {
    void* p = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
    if (p == MAP_FAILED) {
      ::close(fd);
      throw CheckpointError(file, "cannot be read");
    }
    base_ = static_cast<const char*>(p);
    ::madvise(p, size_, MADV_SEQUENTIAL);
  }
  ::close(fd);  // the mapping keeps the file
  try {
    payload_size_ = check_envelope(file, std::string_view(base_, size_), accepted,
                                   [this](std::size_t at) { release_file_before(at); });
  } catch (...) {
    if (base_) ::munmap(const_cast<char*>(base_), size_);
    throw;
  }
  std::memcpy(&checksum_, base_ + kHeader + payload_size_, sizeof checksum_);
  std::memcpy(&scenario_hash_, base_ + 16, sizeof scenario_hash_);
  released_ = 0;  // the checksum's pass gave back every page: a reader's pass starts again
}

MappedCheckpoint::~MappedCheckpoint() {
  close();
}

void MappedCheckpoint::close() {
  if (base_) ::munmap(const_cast<char*>(base_), size_);
  base_ = nullptr;
  size_ = payload_size_ = released_ = 0;
}

std::string_view MappedCheckpoint::payload() const {
  return std::string_view(base_ ? base_ + kHeader : base_, payload_size_);
}

void MappedCheckpoint::release_before(std::size_t offset) {
  release_file_before(kHeader + std::min(offset, payload_size_));
}

void MappedCheckpoint::release_file_before(std::size_t at) {
  // Whole pages only; a page the reader is still in stays. Given back, a page is read from the
  // file again if it is touched again (the mapping is private and never written).
  const auto page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
  const std::size_t end = std::min(at, size_) / page * page;
  if (end <= released_) return;
  ::madvise(const_cast<char*>(base_) + released_, end - released_, MADV_DONTNEED);
  released_ = end;
}

}  // namespace blockdem
