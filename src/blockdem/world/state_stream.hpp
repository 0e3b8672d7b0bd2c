// Byte streams for a run's saved state: numbers as their exact bytes (doubles bit for bit), so
// that a state read back continues a run bit-identically. Used by World and the run checkpoint.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace blockdem {

/// Thrown when saved state is truncated or does not fit the world it is read into.
class StateError : public std::runtime_error {
 public:
  explicit StateError(const std::string& what) : std::runtime_error(what) {}
};

/// Appends values to a byte buffer in the machine's byte order (the file header records it).
class StateWriter {
 public:
  template <class T>
  requires std::is_trivially_copyable_v<T>
  void pod(const T& value) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(&value);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
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
  }
  void size(std::size_t n) { pod(static_cast<std::uint64_t>(n)); }

  const std::vector<std::uint8_t>& bytes() const { return bytes_; }
  std::vector<std::uint8_t>& bytes() { return bytes_; }

 private:
  std::vector<std::uint8_t> bytes_;
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

 private:
  void need(std::size_t n) const {
    if (n > size_ - at_) throw StateError("saved state is truncated");
  }
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
};

}  // namespace blockdem
