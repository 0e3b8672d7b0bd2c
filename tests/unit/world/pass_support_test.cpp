// A store's spare room given back to the system (world/pass_support.hpp, release_spare_room):
// the elements stay where they are, with their values, and the pages of the room are no longer
// resident (Linux: the process's resident size falls by about the room's size, where a copy to
// a smaller allocation would have moved the elements).
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "blockdem/io/process_memory.hpp"
#include "blockdem/world/pass_support.hpp"

namespace blockdem {
namespace {

TEST(PassSupport, LargeSpareRoomReleasedInPlaceKeepsTheElements) {
  // 192 MiB written, then 8 MiB of it kept: 184 MiB of spare room whose pages were touched.
  constexpr std::size_t room = std::size_t{24} << 20, kept = std::size_t{1} << 20;
  std::vector<std::uint64_t> store(room);
  for (std::size_t k = 0; k < room; ++k) store[k] = k * 2654435761u;
  store.resize(kept);
  const std::uint64_t* before = store.data();
  const ResidentMemory held = resident_memory();
  pass_support::release_spare_room(store);
  const ResidentMemory after = resident_memory();
  EXPECT_EQ(store.data(), before);
  EXPECT_EQ(store.size(), kept);
  for (std::size_t k = 0; k < kept; ++k) ASSERT_EQ(store[k], k * 2654435761u) << k;
#if defined(__linux__)
  EXPECT_EQ(store.capacity(), room);
  ASSERT_GE(held.current, 0);
  ASSERT_GE(after.current, 0);
  // The whole pages of the 184 MiB returned (less any the test's own allocations took).
  EXPECT_GT(held.current - after.current, std::int64_t{160} << 20)
      << "resident " << held.current << " B before, " << after.current << " B after";
#endif
  // The room is the store's again: grown into it, the new elements are value-initialised and
  // the old ones kept.
  store.resize(2 * kept);
  EXPECT_EQ(store.data(), before);
  for (std::size_t k = 0; k < kept; ++k) ASSERT_EQ(store[k], k * 2654435761u) << k;
  for (std::size_t k = kept; k < 2 * kept; ++k) ASSERT_EQ(store[k], 0u) << k;
}

TEST(PassSupport, SmallSpareRoomIsShrunkToFit) {
  // 1 MiB of room: below the 64 MiB where pages are returned, the store is shrunk.
  std::vector<std::uint64_t> store(std::size_t{1} << 17, 7);
  store.resize(100);
  pass_support::release_spare_room(store);
  EXPECT_EQ(store.capacity(), 100u);
  for (const std::uint64_t v : store) EXPECT_EQ(v, 7u);
}

}  // namespace
}  // namespace blockdem
