// Whole-file outputs written so that no reader ever sees half a file: a temporary name in the
// same folder, flushed to disk, then renamed over the target; and the checksum the run record uses.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace blockdem {

/// Writes `content` to `path` atomically: `.NAME.tmp` in the same folder, fsync, rename over
/// `path`, fsync of the folder. Throws std::runtime_error naming the file on failure (the
/// temporary file is removed).
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

/// 64-bit FNV-1a hash of bytes (Fowler, Noll & Vo; offset basis 14695981039346656037, prime
/// 1099511628211). Detects corruption and truncation; not a cryptographic hash.
std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t hash = 14695981039346656037ull);

/// The hash as 16 lower-case hex digits.
std::string hex64(std::uint64_t value);

/// The whole content of a file; throws std::runtime_error naming it when it cannot be read.
std::string read_file_bytes(const std::filesystem::path& path);

/// A file's size and FNV-1a hash, read in chunks (the file is never held in memory whole): the
/// same as read_file_bytes(path).size() and fnv1a64(read_file_bytes(path)).
struct FileDigest {
  std::uint64_t bytes = 0;
  std::uint64_t fnv1a64 = 0;
};
FileDigest file_digest(const std::filesystem::path& path);

}  // namespace blockdem
