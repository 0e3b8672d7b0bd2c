// Per block, one integer per plane of its shape (a face's own joint law, the joint set that made a
// face), or none: every block's values in one array, each block's a run in it. A list per block
// cost a 24-byte header and a heap block of its own (56 bytes for a block of six planes, 32 here);
// a rock mass of a million blocks has two such lists per block.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <vector>

namespace blockdem {

class PlaneValues {
 public:
  /// Block i's values, one per plane (empty: none).
  std::span<const int> of(std::size_t i) const {
    if (i >= runs_.size()) return {};
    const Run r = runs_[i];
    return {values_.data() + r.at, r.count};
  }
  bool has(std::size_t i) const { return i < runs_.size() && runs_[i].count > 0; }
  /// The values held: every block's, and those of blocks cleared since the last keep().
  std::size_t stored() const { return values_.size(); }
  /// Room for `blocks` blocks and `values` values in all (a world's set-up knows them before
  /// it sets them).
  void reserve(std::size_t blocks, std::size_t values) {
    runs_.reserve(blocks);
    values_.reserve(values);
  }

  /// Gives block i these values (empty: none). A block's values replace its earlier ones in
  /// place when they are as many (a block's planes do not change); the blocks before it that
  /// had none keep none.
  void set(std::size_t i, std::span<const int> values) {
    // Values read from this object (another block's) would move when the array grows.
    const bool own = !values.empty() && values.data() >= values_.data() &&
                     values.data() < values_.data() + values_.size();
    if (own) {
      const std::vector<int> copy(values.begin(), values.end());
      set(i, copy);
      return;
    }
    if (runs_.size() <= i) runs_.resize(i + 1);
    Run& r = runs_[i];
    if (values.size() != r.count) r = append(values.size());
    std::copy(values.begin(), values.end(), values_.begin() + static_cast<std::ptrdiff_t>(r.at));
  }
  /// Block i's values to change in place; a block without any is first given `count` values
  /// `fill`.
  std::span<int> edit(std::size_t i, std::size_t count, int fill) {
    if (runs_.size() <= i) runs_.resize(i + 1);
    Run& r = runs_[i];
    if (r.count == 0) {
      r = append(count);
      std::fill_n(values_.begin() + static_cast<std::ptrdiff_t>(r.at), count, fill);
    }
    return {values_.data() + r.at, r.count};
  }
  /// Keeps the blocks whose new_index is not negative, under their new indices (which keep
  /// the blocks' order), and gives back the room of the others' values.
  void keep(const std::vector<int>& new_index) {
    PlaneValues kept;
    for (std::size_t i = 0; i < runs_.size() && i < new_index.size(); ++i) {
      if (new_index[i] >= 0 && runs_[i].count > 0)
        kept.set(static_cast<std::size_t>(new_index[i]), of(i));
    }
    *this = std::move(kept);
  }
  /// Asks the cache for block i's run, and (once the run is there) for its values: the step
  /// reads them a few pairs ahead.
  void prefetch_run(std::size_t i) const {
    if (i < runs_.size()) __builtin_prefetch(&runs_[i]);
  }
  void prefetch_values(std::size_t i) const {
    if (i < runs_.size()) __builtin_prefetch(values_.data() + runs_[i].at);
  }
  /// The largest value of any block (`none` when no block has values).
  int max_value(int none) const {
    int most = none;
    for (std::size_t i = 0; i < runs_.size(); ++i)
      for (const int v : of(i)) most = std::max(most, v);
    return most;
  }

 private:
  struct Run {
    std::uint32_t at = 0;     ///< the first value's place in values_
    std::uint32_t count = 0;  ///< values (the block's planes); 0: none
  };
  Run append(std::size_t count) {
    if (count > std::numeric_limits<std::uint32_t>::max() ||
        values_.size() + count > std::numeric_limits<std::uint32_t>::max())
      throw std::length_error("PlaneValues: more than 2^32 values of planes");
    Run r{static_cast<std::uint32_t>(values_.size()), static_cast<std::uint32_t>(count)};
    values_.resize(values_.size() + count);
    return r;
  }
  std::vector<Run> runs_;
  std::vector<int> values_;
};

}  // namespace blockdem
