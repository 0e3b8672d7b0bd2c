// A contiguous sequence that keeps its first N elements inside the object and moves to the heap
// only beyond N, so that contact geometry of the usual size allocates nothing per time step.
#pragma once

#include <array>
#include <cstddef>
#include <initializer_list>
#include <iterator>
#include <utility>
#include <vector>

namespace blockdem {

/// Push-back-only sequence of default-constructible values: elements live in an inline array
/// while size() <= N, and all of them move to a std::vector once one more is added. data(),
/// begin() and end() address whichever storage is in use, so it converts to std::span.
template <class T, std::size_t N>
class SmallVector {
 public:
  using value_type = T;
  using size_type = std::size_t;
  using iterator = T*;
  using const_iterator = const T*;

  SmallVector() = default;
  SmallVector(std::initializer_list<T> values) {
    for (const T& v : values) push_back(v);
  }

  T* data() { return on_heap_ ? heap_.data() : inline_.data(); }
  const T* data() const { return on_heap_ ? heap_.data() : inline_.data(); }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  T* begin() { return data(); }
  T* end() { return data() + size_; }
  const T* begin() const { return data(); }
  const T* end() const { return data() + size_; }
  T& operator[](std::size_t i) { return data()[i]; }
  const T& operator[](std::size_t i) const { return data()[i]; }
  T& back() { return data()[size_ - 1]; }
  const T& back() const { return data()[size_ - 1]; }

  void push_back(T value) {
    if (!on_heap_ && size_ == N) {
      heap_.reserve(2 * N);
      heap_.assign(std::make_move_iterator(inline_.begin()),
                   std::make_move_iterator(inline_.end()));
      on_heap_ = true;
    }
    if (on_heap_) {
      heap_.push_back(std::move(value));
    } else {
      inline_[size_] = std::move(value);
    }
    ++size_;
  }

  /// Removes every element (heap storage, if any, is kept for reuse).
  void clear() {
    if (on_heap_) heap_.clear();
    size_ = 0;
    on_heap_ = false;
  }

 private:
  std::array<T, N> inline_;  // default-initialised: unused slots cost nothing
  std::vector<T> heap_;
  std::size_t size_ = 0;
  bool on_heap_ = false;
};

}  // namespace blockdem
