// A contiguous sequence that keeps its first N elements inside the object and moves to the heap
// only beyond N, so that contact geometry of the usual size allocates nothing per time step.
#pragma once

#include <algorithm>
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
  // Copies and moves take the size_ elements in use only: the inline slots beyond them were
  // never written (for Eigen vectors or doubles, uninitialised memory that must not be read).
  SmallVector(const SmallVector& other)
      : heap_(other.heap_), size_(other.size_), on_heap_(other.on_heap_) {
    if (!on_heap_) std::copy(other.inline_.begin(), other.inline_.begin() + size_, inline_.begin());
  }
  SmallVector(SmallVector&& other) noexcept
      : heap_(std::move(other.heap_)), size_(other.size_), on_heap_(other.on_heap_) {
    if (!on_heap_) std::move(other.inline_.begin(), other.inline_.begin() + size_, inline_.begin());
    other.size_ = 0;
    other.on_heap_ = false;
  }
  SmallVector& operator=(const SmallVector& other) {
    if (this == &other) return *this;
    heap_ = other.heap_;
    size_ = other.size_;
    on_heap_ = other.on_heap_;
    if (!on_heap_) std::copy(other.inline_.begin(), other.inline_.begin() + size_, inline_.begin());
    return *this;
  }
  SmallVector& operator=(SmallVector&& other) noexcept {
    if (this == &other) return *this;
    heap_ = std::move(other.heap_);
    size_ = other.size_;
    on_heap_ = other.on_heap_;
    if (!on_heap_) std::move(other.inline_.begin(), other.inline_.begin() + size_, inline_.begin());
    other.heap_.clear();
    other.size_ = 0;
    other.on_heap_ = false;
    return *this;
  }
  ~SmallVector() = default;

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

  // The inline case is a store and an increment, inlined at every call; growth to the heap is a
  // call (spill), taken once per sequence that outgrows N.
  void push_back(T value) {
    if (!on_heap_ && size_ < N) {
      inline_[size_++] = std::move(value);
      return;
    }
    heap_push(std::move(value));
  }

  /// Appends a value-initialised element (T()) and returns it, to be filled in place.
  T& emplace_back() {
    if (!on_heap_ && size_ < N) {
      T& slot = inline_[size_++];
      slot = T();
      return slot;
    }
    heap_push(T());
    return heap_.back();
  }

  /// Removes every element (heap storage, if any, is kept for reuse).
  void clear() {
    if (on_heap_) heap_.clear();
    size_ = 0;
    on_heap_ = false;
  }

 private:
  // The heap path of push_back: moves the N inline elements to the heap on the first call.
  [[gnu::noinline]] void heap_push(T value) {
    if (!on_heap_) {
      heap_.reserve(2 * N);
      heap_.assign(std::make_move_iterator(inline_.begin()),
                   std::make_move_iterator(inline_.end()));
      on_heap_ = true;
    }
    heap_.push_back(std::move(value));
    ++size_;
  }

  std::array<T, N> inline_;  // default-initialised: unused slots cost nothing
  std::vector<T> heap_;
  std::size_t size_ = 0;
  bool on_heap_ = false;
};

}  // namespace blockdem
