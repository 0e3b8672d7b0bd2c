// The restart file's envelope: a versioned binary container with a magic, the byte order, the
// scenario's hash and a trailing checksum around the run's saved state (docs/restart.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace blockdem {

/// Thrown for a checkpoint file that cannot be used; the message starts with the file's name.
class CheckpointError : public std::runtime_error {
 public:
  CheckpointError(const std::filesystem::path& file, const std::string& reason)
      : std::runtime_error(file.string() + ": " + reason) {}
};

/// The format version this program writes and reads.
inline constexpr std::uint32_t kCheckpointVersion = 2;

/// Writes `payload` as a checkpoint file, atomically (temporary name, fsync, rename). A previous
/// file of that name is first renamed to NAME.prev, so the last two checkpoints are kept.
void write_checkpoint_file(const std::filesystem::path& file, std::uint64_t scenario_hash,
                           std::string_view payload);

/// Reads a checkpoint file and returns its payload after checking, in order: the magic, the
/// byte order, the format version, the size, the checksum and the scenario hash. Throws
/// CheckpointError with the reason.
std::string read_checkpoint_file(const std::filesystem::path& file, std::uint64_t scenario_hash);

}  // namespace blockdem
