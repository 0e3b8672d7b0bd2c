// The restart file's envelope: a versioned binary container with a magic, the byte order, the
// scenario's hash and a trailing checksum around the run's saved state (docs/restart.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace blockdem {

/// Thrown for a checkpoint file that cannot be used; the message starts with the file's name.
class CheckpointError : public std::runtime_error {
 public:
  CheckpointError(const std::filesystem::path& file, const std::string& reason)
      : std::runtime_error(file.string() + ": " + reason), reason_(reason) {}
  /// The reason alone, without the file.
  const std::string& reason() const { return reason_; }

 private:
  std::string reason_;
};

/// A checkpoint written for another scenario (its hash is not one this scenario accepts).
class CheckpointScenarioError : public CheckpointError {
 public:
  using CheckpointError::CheckpointError;
};

/// The format version this program writes and reads.
inline constexpr std::uint32_t kCheckpointVersion = 6;

/// Writes `payload` as a checkpoint file, atomically (temporary name, fsync, rename). A previous
/// file of that name is first renamed to NAME.prev, so the last two checkpoints are kept.
void write_checkpoint_file(const std::filesystem::path& file, std::uint64_t scenario_hash,
                           std::string_view payload);

/// A checkpoint file written in pieces, for a payload that is never held whole (a distributed
/// run's state, merged to process 0 as it comes): the same bytes, the same temporary name, fsync,
/// `.prev` and rename as write_checkpoint_file. The pieces go to the temporary file (buffered);
/// finish() writes the header, reads the file back in chunks for its checksum and renames it.
/// Destroyed unfinished (an exception), it removes its temporary file.
class CheckpointFileWriter {
 public:
  CheckpointFileWriter(const std::filesystem::path& file, std::uint64_t scenario_hash);
  ~CheckpointFileWriter();
  CheckpointFileWriter(const CheckpointFileWriter&) = delete;
  CheckpointFileWriter& operator=(const CheckpointFileWriter&) = delete;
  void append(std::string_view bytes);
  /// Payload bytes appended so far.
  std::uint64_t size() const { return size_; }
  /// Overwrites payload bytes appended earlier, at payload offset `at` (a length known later).
  void patch(std::uint64_t at, std::string_view bytes);
  void finish();

 private:
  void write_at(std::uint64_t at, std::string_view bytes);
  void flush();
  std::filesystem::path file_, tmp_;
  std::uint64_t scenario_hash_ = 0;
  int fd_ = -1;
  std::uint64_t size_ = 0;     ///< payload bytes appended
  std::uint64_t written_ = 0;  ///< payload bytes in the file (the rest in buffer_)
  std::string buffer_;
};

/// Reads a checkpoint file and returns its payload after checking, in order: the magic, the
/// byte order, the format version, the size, the checksum and the scenario hash. Throws
/// CheckpointError with the reason.
std::string read_checkpoint_file(const std::filesystem::path& file, std::uint64_t scenario_hash);
/// The same for a checkpoint that may carry any of the hashes `accepted`.
std::string read_checkpoint_file(const std::filesystem::path& file,
                                 const std::vector<std::uint64_t>& accepted);

/// A checkpoint file mapped into memory (read only) and checked as read_checkpoint_file checks
/// it, with the same errors. Its payload is read in place, and the pages a reader has passed can
/// be given back (release_before): a restart of a large world then never holds the file's bytes
/// and the world's state in memory at once (read_checkpoint_file's string held both). The
/// checksum's pass gives back its pages as it goes. The file must not change in place while it is
/// mapped (blockdem replaces a checkpoint by a rename: the mapping keeps the old file).
class MappedCheckpoint {
 public:
  MappedCheckpoint(const std::filesystem::path& file, std::uint64_t scenario_hash);
  /// The same for a checkpoint that may carry any of the hashes `accepted` (a run that branches
  /// from it, docs/restart.md).
  MappedCheckpoint(const std::filesystem::path& file, const std::vector<std::uint64_t>& accepted);
  ~MappedCheckpoint();
  MappedCheckpoint(const MappedCheckpoint&) = delete;
  MappedCheckpoint& operator=(const MappedCheckpoint&) = delete;
  std::string_view payload() const;
  /// The file's checksum (its last 8 bytes): two mappings with the same checksum hold the same
  /// checkpoint.
  std::uint64_t checksum() const { return checksum_; }
  /// The scenario hash the file carries (one of those accepted).
  std::uint64_t scenario_hash() const { return scenario_hash_; }
  /// Gives back the whole pages of the payload before payload offset `offset` (bytes read there
  /// again are read from the file again).
  void release_before(std::size_t offset);
  /// Unmaps the file now (the payload is empty after): a checkpoint file that the run replaces
  /// later is then not kept on disk by the mapping.
  void close();

 private:
  void release_file_before(std::size_t at);
  const char* base_ = nullptr;
  std::size_t size_ = 0;          ///< the file's bytes
  std::size_t payload_size_ = 0;  ///< the payload's bytes
  std::size_t released_ = 0;      ///< file bytes given back so far (whole pages)
  std::uint64_t checksum_ = 0;
  std::uint64_t scenario_hash_ = 0;
};

}  // namespace blockdem
