// Half-spaces stored column by column (normal components and offsets in separate arrays): the
// layout in which the narrow phase's loops over planes vectorise.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "blockdem/geometry/halfspace.hpp"

namespace blockdem {

/// The planes of one or two lists, in order (those of `first`, then those of `second`), as the
/// columns n_x, n_y, n_z and d of n·x <= d. Up to kStackPlanes planes live inside the object
/// (no heap allocation); longer lists use the heap. Not copyable (the columns point into it).
class PlaneColumns {
 public:
  static constexpr std::size_t kStackPlanes = 64;

  explicit PlaneColumns(std::span<const Halfspace> first, std::span<const Halfspace> second = {});
  PlaneColumns(const PlaneColumns&) = delete;
  PlaneColumns& operator=(const PlaneColumns&) = delete;

  std::size_t size() const { return size_; }
  const double* nx() const { return data_; }
  const double* ny() const { return data_ + size_; }
  const double* nz() const { return data_ + 2 * size_; }
  const double* d() const { return data_ + 3 * size_; }  ///< offsets (m)

 private:
  std::array<double, 4 * kStackPlanes> stack_;  // uninitialised until filled
  std::vector<double> heap_;
  double* data_ = nullptr;
  std::size_t size_ = 0;
};

inline PlaneColumns::PlaneColumns(std::span<const Halfspace> first,
                                  std::span<const Halfspace> second)
    : size_(first.size() + second.size()) {
  data_ = stack_.data();
  if (size_ > kStackPlanes) {
    heap_.resize(4 * size_);
    data_ = heap_.data();
  }
  std::size_t j = 0;
  for (const auto list : {first, second}) {
    for (const Halfspace& h : list) {
      data_[j] = h.normal.x();
      data_[size_ + j] = h.normal.y();
      data_[2 * size_ + j] = h.normal.z();
      data_[3 * size_ + j] = h.offset;
      ++j;
    }
  }
}

}  // namespace blockdem
