// Byte streams for a run's saved state: numbers as their exact bytes (doubles bit for bit), so
// that a state read back continues a run bit-identically. Used by World and the run checkpoint.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace blockdem {

/// Thrown when saved state is truncated or does not fit the world it is read into.
class StateError : public std::runtime_error {
 public:
  explicit StateError(const std::string& what) : std::runtime_error(what) {}
};

/// Appends values to a byte buffer in the machine's byte order (the file header records it).
/// Made with a sink, it hands its bytes on in pieces of about `chunk` bytes as they are written
/// (a restart checkpoint of a large world goes to its file without being held whole in memory)
/// and flush() hands on the rest; without one, bytes() holds everything written.
class StateWriter {
 public:
  using Sink = std::function<void(std::string_view)>;
  StateWriter() = default;
  explicit StateWriter(Sink sink, std::size_t chunk = std::size_t{1} << 20)
      : sink_(std::move(sink)), chunk_(chunk) {
    bytes_.reserve(chunk_ + 4096);
  }

  template <class T>
  requires std::is_trivially_copyable_v<T>
  void pod(const T& value) {
    const std::size_t at = bytes_.size();
    bytes_.resize(at + sizeof(T));
    std::memcpy(bytes_.data() + at, &value, sizeof(T));
    if (sink_ && bytes_.size() >= chunk_) flush();
  }
  void vec(const Eigen::Vector3d& v) {
    for (int i = 0; i < 3; ++i) pod(v[i]);
  }
  void quat(const Eigen::Quaterniond& q) {
    for (int i = 0; i < 4; ++i) pod(q.coeffs()[i]);
  }
  void str(const std::string& s) {
    pod(static_cast<std::uint64_t>(s.size()));
    bytes_.insert(bytes_.end(), s.begin(), s.end());
    if (sink_ && bytes_.size() >= chunk_) flush();
  }
  void size(std::size_t n) { pod(static_cast<std::uint64_t>(n)); }
  /// Appends bytes another StateWriter wrote (a section kept apart), as they are.
  void raw(std::string_view b) {
    bytes_.insert(bytes_.end(), b.begin(), b.end());
    if (sink_ && bytes_.size() >= chunk_) flush();
  }

  /// With a sink: hands the bytes held on to it (none are held after). Without: nothing.
  void flush() {
    if (!sink_ || bytes_.empty()) return;
    sink_(std::string_view(reinterpret_cast<const char*>(bytes_.data()), bytes_.size()));
    bytes_.clear();
  }

  /// The bytes written (with a sink: since its last piece).
  const std::vector<std::uint8_t>& bytes() const { return bytes_; }
  std::vector<std::uint8_t>& bytes() { return bytes_; }

 private:
  std::vector<std::uint8_t> bytes_;
  Sink sink_;
  std::size_t chunk_ = 0;
};

/// Reads what a StateWriter wrote; throws StateError past the end.
class StateReader {
 public:
  StateReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  template <class T>
  requires std::is_trivially_copyable_v<T> T pod() {
    need(sizeof(T));
    T value;
    std::memcpy(&value, data_ + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  template <class T>
  void pod(T& value) {
    value = pod<T>();
  }
  Eigen::Vector3d vec() {
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) v[i] = pod<double>();
    return v;
  }
  Eigen::Quaterniond quat() {
    Eigen::Quaterniond q;
    for (int i = 0; i < 4; ++i) q.coeffs()[i] = pod<double>();
    return q;
  }
  std::string str() {
    const std::size_t n = size();
    need(n);
    std::string s(reinterpret_cast<const char*>(data_ + at_), n);
    at_ += n;
    return s;
  }
  /// A count; refused when larger than the bytes left (a corrupt count cannot allocate much).
  std::size_t size() {
    const auto n = pod<std::uint64_t>();
    if (n > size_ - at_) throw StateError("saved state is corrupt (a count exceeds the data)");
    return static_cast<std::size_t>(n);
  }
  bool done() const { return at_ == size_; }
  /// Bytes read so far.
  std::size_t position() const { return at_; }
  /// Passes over `n` bytes (throws past the end).
  void skip(std::size_t n) {
    need(n);
    at_ += n;
  }
  /// Calls `passed(position())` whenever the reader has gone at least `every` bytes on since the
  /// last call (a reader of a mapped file gives back the pages behind it).
  void on_progress(std::size_t every, std::function<void(std::size_t)> passed) {
    every_ = every;
    passed_ = std::move(passed);
    next_ = at_ + every_;
  }

 private:
  void need(std::size_t n) {
    if (n > size_ - at_) throw StateError("saved state is truncated");
    if (at_ >= next_) {
      next_ = at_ + every_;
      passed_(at_);
    }
  }
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
  std::size_t every_ = 0;
  std::size_t next_ = std::numeric_limits<std::size_t>::max();  ///< no calls until on_progress
  std::function<void(std::size_t)> passed_;
};

}  // namespace blockdem
