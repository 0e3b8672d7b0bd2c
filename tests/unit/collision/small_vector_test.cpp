// SmallVector: elements kept in order across the move to the heap, copies and moves that carry
// exactly the elements in use (inline or on the heap), and emplace_back's fresh element.
#include "blockdem/collision/small_vector.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <utility>

#include "blockdem/collision/face_contact.hpp"

namespace blockdem {
namespace {

template <class V>
std::vector<int> values_of(const V& v) {
  return std::vector<int>(v.begin(), v.end());
}

TEST(SmallVector, PushBackPastTheInlineCapacityKeepsTheOrder) {
  SmallVector<int, 4> v;
  for (int i = 0; i < 11; ++i) v.push_back(10 * i);
  ASSERT_EQ(v.size(), 11u);
  for (int i = 0; i < 11; ++i) EXPECT_EQ(v[static_cast<std::size_t>(i)], 10 * i);
  EXPECT_EQ(v.back(), 100);
  EXPECT_EQ(v.end() - v.begin(), 11);
}

// Copies and moves of a vector inline (3 of 8 used) and of one on the heap (10 of 4), onto
// empty vectors and onto vectors that held other elements, inline or on the heap.
TEST(SmallVector, CopiesAndMovesCarryTheElementsInUse) {
  SmallVector<int, 4> small{1, 2, 3}, large;
  for (int i = 0; i < 10; ++i) large.push_back(i);
  const std::vector<int> small_values{1, 2, 3}, large_values = values_of(large);
  for (const auto* source : {&small, &large}) {
    const std::vector<int> expected = values_of(*source);
    SmallVector<int, 4> copied(*source);
    EXPECT_EQ(values_of(copied), expected);
    SmallVector<int, 4> onto_inline{7, 8};
    onto_inline = *source;
    EXPECT_EQ(values_of(onto_inline), expected);
    SmallVector<int, 4> onto_heap{9, 9, 9, 9, 9, 9};
    onto_heap = *source;
    EXPECT_EQ(values_of(onto_heap), expected);
    SmallVector<int, 4> moved(std::move(copied));
    EXPECT_EQ(values_of(moved), expected);
    EXPECT_TRUE(copied.empty());  // NOLINT(bugprone-use-after-move): the moved-from state
    SmallVector<int, 4> move_onto{5, 5, 5, 5, 5};
    move_onto = std::move(moved);
    EXPECT_EQ(values_of(move_onto), expected);
    EXPECT_TRUE(moved.empty());  // NOLINT(bugprone-use-after-move)
    // A moved-from vector takes new elements from its start.
    moved.push_back(42);
    EXPECT_EQ(values_of(moved), std::vector<int>{42});
  }
  EXPECT_EQ(values_of(small), small_values);
  EXPECT_EQ(values_of(large), large_values);
}

// clear() empties a vector on the heap too, and the next elements go inline again (a
// narrow-phase buffer reused from pair to pair).
TEST(SmallVector, ClearedOnTheHeapStartsInlineAgain) {
  SmallVector<double, 8> v;
  for (int i = 0; i < 12; ++i) v.push_back(0.5 * i);
  ASSERT_EQ(v.size(), 12u);
  EXPECT_EQ(v[11], 5.5);
  v.clear();
  EXPECT_TRUE(v.empty());
  EXPECT_EQ(v.begin(), v.end());
  for (int i = 0; i < 3; ++i) v.push_back(-1.0 * i);
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[0], 0.0);
  EXPECT_EQ(v[2], -2.0);
  EXPECT_EQ(v.back(), -2.0);
}

// The face contact's cells: Eigen vectors inline, copied with a cell of the sequence of cells.
TEST(SmallVector, CellsCopyTheirVerticesAndClosures) {
  SmallVector<ClosureCell, 2> cells;
  for (int c = 0; c < 3; ++c) {  // the third cell moves the cells to the heap
    ClosureCell& cell = cells.emplace_back();
    for (int k = 0; k < 3 + c; ++k) {
      cell.vertices.push_back(Eigen::Vector3d(c, k, 0.5 * k));
      cell.closures.push_back(1e-6 * (c + k));
    }
  }
  const SmallVector<ClosureCell, 2> copy = cells;
  ASSERT_EQ(copy.size(), 3u);
  for (std::size_t c = 0; c < 3; ++c) {
    ASSERT_EQ(copy[c].vertices.size(), 3 + c);
    ASSERT_EQ(copy[c].closures.size(), 3 + c);
    for (std::size_t k = 0; k < 3 + c; ++k) {
      EXPECT_EQ(copy[c].vertices[k], cells[c].vertices[k]);
      EXPECT_EQ(copy[c].closures[k], cells[c].closures[k]);
    }
  }
}

// emplace_back gives a value-initialised element, also in a slot a cleared vector reuses.
TEST(SmallVector, EmplaceBackGivesAFreshElement) {
  SmallVector<ClosureCell, 2> cells;
  cells.emplace_back().closures.push_back(3.0);
  cells.clear();
  ClosureCell& reused = cells.emplace_back();
  EXPECT_TRUE(reused.closures.empty());
  EXPECT_TRUE(reused.vertices.empty());
  SmallVector<double, 1> values;
  values.push_back(2.0);
  EXPECT_EQ(values.emplace_back(), 0.0);  // on the heap
  EXPECT_EQ(values.size(), 2u);
  EXPECT_EQ(values[0], 2.0);
}

}  // namespace
}  // namespace blockdem
