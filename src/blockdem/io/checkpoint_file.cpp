// Checkpoint envelope. Layout (byte offsets): 0 magic (8 bytes, "\x89BDCK\r\n\x1a": the CR-LF
// and the high byte catch text-mode and 7-bit transfers), 8 byte-order mark 0x01020304 (u32),
// 12 format version (u32), 16 scenario hash (u64), 24 payload size n (u64), 32 payload,
// 32 + n FNV-1a 64 of bytes [0, 32 + n) (u64). Integers in the writer's byte order.
#include "blockdem/io/checkpoint_file.hpp"

#include <cstring>
#include <system_error>

#include "blockdem/io/atomic_file.hpp"

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

template <class T>
T get(const std::string& s, std::size_t at) {
  T v;
  std::memcpy(&v, s.data() + at, sizeof(T));
  return v;
}

}  // namespace

void write_checkpoint_file(const std::filesystem::path& file, std::uint64_t scenario_hash,
                           std::string_view payload) {
  std::string bytes(kMagic, sizeof kMagic);
  put(bytes, kByteOrder);
  put(bytes, kCheckpointVersion);
  put(bytes, scenario_hash);
  put(bytes, static_cast<std::uint64_t>(payload.size()));
  bytes.append(payload);
  put(bytes, fnv1a64(bytes));
  // The last checkpoint becomes NAME.prev by a second name (a hard link; a copy where the file
  // system has none), then the new one replaces NAME by a rename: at every moment NAME is a
  // whole checkpoint, also when the process is killed in between.
  std::error_code ec;
  if (std::filesystem::exists(file, ec)) {
    std::filesystem::path prev = file;
    prev += ".prev";
    std::filesystem::remove(prev, ec);
    std::filesystem::create_hard_link(file, prev, ec);
    if (ec)
      std::filesystem::copy_file(file, prev, std::filesystem::copy_options::overwrite_existing, ec);
  }
  write_file_atomically(file, bytes);
}

std::string read_checkpoint_file(const std::filesystem::path& file, std::uint64_t scenario_hash) {
  std::string bytes;
  try {
    bytes = read_file_bytes(file);
  } catch (const std::runtime_error&) {
    throw CheckpointError(file, "cannot be read");
  }
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    throw CheckpointError(file, "not a blockdem checkpoint (wrong magic number)");
  if (bytes.size() < kHeader + 8) throw CheckpointError(file, "truncated (shorter than a header)");
  const auto order = get<std::uint32_t>(bytes, 8);
  if (order != kByteOrder)
    throw CheckpointError(file, "written on a machine of the other byte order");
  const auto version = get<std::uint32_t>(bytes, 12);
  if (version != kCheckpointVersion)
    throw CheckpointError(file, "format version " + std::to_string(version) +
                                    "; this blockdem reads version " +
                                    std::to_string(kCheckpointVersion));
  const auto size = get<std::uint64_t>(bytes, 24);
  if (size != bytes.size() - kHeader - 8)
    throw CheckpointError(file, "truncated or padded: the header announces " +
                                    std::to_string(size) + " bytes of state, the file holds " +
                                    std::to_string(bytes.size() - kHeader - 8));
  const std::size_t body = kHeader + static_cast<std::size_t>(size);
  if (get<std::uint64_t>(bytes, body) != fnv1a64(std::string_view(bytes.data(), body)))
    throw CheckpointError(file, "corrupt (checksum mismatch)");
  if (get<std::uint64_t>(bytes, 16) != scenario_hash)
    throw CheckpointError(file,
                          "written for another scenario file or other run options (--max-steps); "
                          "restart with the scenario and options of the run that wrote it");
  return bytes.substr(kHeader, static_cast<std::size_t>(size));
}

}  // namespace blockdem
