// Per-plane values in one array (world/plane_values.hpp) against the list per block they
// replace: after every one of a few thousand random sets, edits and removals, each block's values
// are the reference's, and the array holds no more values than the blocks that have some.
#include "blockdem/world/plane_values.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

// A namespace of this file's own: the unity build compiles it with other test files.
namespace blockdem::test::plane_values_test {
namespace {

using Lists = std::vector<std::vector<int>>;

void expect_same(const PlaneValues& v, const Lists& ref, int step) {
  for (std::size_t i = 0; i < ref.size() + 3; ++i) {
    const std::vector<int> none;
    const std::vector<int>& want = i < ref.size() ? ref[i] : none;
    const auto got = v.of(i);
    ASSERT_EQ(std::vector<int>(got.begin(), got.end()), want) << "block " << i << ", step " << step;
    EXPECT_EQ(v.has(i), !want.empty());
  }
  int most = -1;
  for (const auto& l : ref)
    for (const int x : l) most = std::max(most, x);
  EXPECT_EQ(v.max_value(-1), most) << "step " << step;
}

TEST(PlaneValues, AgreeWithAListPerBlockThroughSetsEditsAndRemovals) {
  std::mt19937 rng(20261204);
  // Each block's plane count is fixed, as a block's shape is.
  std::vector<std::size_t> planes(40);
  for (auto& p : planes) p = std::uniform_int_distribution<std::size_t>(4, 12)(rng);
  PlaneValues v;
  Lists ref;
  const auto random_values = [&](std::size_t count) {
    std::vector<int> values(count);
    for (auto& x : values) x = std::uniform_int_distribution<int>(-1, 9)(rng);
    return values;
  };
  for (int step = 0; step < 3000; ++step) {
    if (planes.empty()) break;
    const std::size_t i = std::uniform_int_distribution<std::size_t>(0, planes.size() - 1)(rng);
    const int op = std::uniform_int_distribution<int>(0, 9)(rng);
    if (ref.size() < planes.size()) ref.resize(planes.size());
    if (op < 4) {
      // Values for every plane, or none (a restored state may clear a block's laws).
      const std::vector<int> values = op == 0 ? std::vector<int>{} : random_values(planes[i]);
      v.set(i, values);
      ref[i] = values;
    } else if (op < 9) {
      const int fill = std::uniform_int_distribution<int>(-1, 3)(rng);
      const std::span<int> edit = v.edit(i, planes[i], fill);
      if (ref[i].empty()) ref[i].assign(planes[i], fill);
      ASSERT_EQ(edit.size(), ref[i].size());
      const std::size_t j = std::uniform_int_distribution<std::size_t>(0, planes[i] - 1)(rng);
      edit[j] = ref[i][j] = std::uniform_int_distribution<int>(0, 20)(rng);
    } else {
      // Remove a few blocks, the others keep their order; then a new block at the end.
      std::vector<int> new_index(planes.size());
      Lists kept_ref;
      std::vector<std::size_t> kept_planes;
      for (std::size_t k = 0; k < planes.size(); ++k) {
        if (std::uniform_int_distribution<int>(0, 4)(rng) == 0) {
          new_index[k] = -1;
          continue;
        }
        new_index[k] = static_cast<int>(kept_planes.size());
        kept_planes.push_back(planes[k]);
        kept_ref.push_back(ref[k]);
      }
      v.keep(new_index);
      ref = kept_ref;
      planes = kept_planes;
      planes.push_back(std::uniform_int_distribution<std::size_t>(4, 12)(rng));
      // Every run is a kept block's: nothing of the removed ones' stays.
      std::size_t values = 0;
      for (const auto& l : ref) values += l.size();
      EXPECT_EQ(v.stored(), values);
    }
    expect_same(v, ref, step);
    if (::testing::Test::HasFailure()) return;
  }
}

TEST(PlaneValues, ACopyIsIndependentOfItsOriginal) {
  PlaneValues a;
  a.set(2, std::vector<int>{1, 2, 3});
  PlaneValues b = a;
  b.edit(2, 3, -1)[0] = 7;
  b.set(5, std::vector<int>{4});
  EXPECT_EQ(a.of(2)[0], 1);
  EXPECT_FALSE(a.has(5));
  EXPECT_EQ(b.of(2)[0], 7);
  EXPECT_EQ(b.of(5)[0], 4);
  EXPECT_FALSE(b.has(0));
  EXPECT_TRUE(b.of(0).empty());
}

TEST(PlaneValues, ABlockGivenAnotherBlocksValuesGetsThemWhenTheArrayGrows) {
  PlaneValues v;
  v.reserve(2, 4);
  v.set(0, std::vector<int>{1, 2, 3, 4});
  // Block 1's new run makes the array grow past its room: the values read from block 0 move.
  v.set(1, v.of(0));
  v.set(1, v.of(0).subspan(1));
  ASSERT_EQ(v.of(1).size(), 3U);
  EXPECT_EQ(v.of(1)[0], 2);
  EXPECT_EQ(v.of(1)[2], 4);
  EXPECT_EQ(v.of(0)[3], 4);
}

}  // namespace
}  // namespace blockdem::test::plane_values_test
