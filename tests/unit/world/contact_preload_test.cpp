// The prestressed joints' list (world/contact_preload.hpp): a pair's prestress is found through
// the index of where each block's joints start. Oracle: a scan of the whole list.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "blockdem/world/contact_preload.hpp"

namespace blockdem {
namespace {

const ContactPreload* scan(const ContactPreloads& list, int a, int b) {
  for (const ContactPreload& p : list.all()) {
    if (p.a == a && p.b == b) return &p;
  }
  return nullptr;
}

// Every pair (and pairs of indices outside the blocks) found as the scan finds it: the same
// record, or none.
void expect_as_scan(const ContactPreloads& list, int blocks) {
  for (int a = -1; a <= blocks; ++a) {
    for (int b = -1; b <= blocks; ++b) {
      EXPECT_EQ(list.find(a, b), scan(list, a, b)) << "pair " << a << ", " << b;
    }
  }
}

TEST(ContactPreloads, FindsEachPairAsAScanDoesBeforeAndAfterARemoval) {
  std::mt19937 rng(7);
  const int blocks = 60;
  std::vector<ContactPreload> given;
  for (int a = 0; a < blocks; ++a) {
    for (int b = a + 1; b < blocks; ++b) {
      if (rng() % 7 != 0) continue;
      ContactPreload p;
      p.a = a;
      p.b = b;
      p.closure = 1000.0 * a + b;  // the pair it was given as
      given.push_back(p);
    }
  }
  std::shuffle(given.begin(), given.end(), rng);
  ContactPreloads list;
  list.assign(given);
  ASSERT_EQ(list.size(), given.size());
  expect_as_scan(list, blocks);
  for (const ContactPreload& p : given) {
    const ContactPreload* found = list.find(p.a, p.b);
    ASSERT_NE(found, nullptr);
    EXPECT_EQ(found->closure, p.closure);
  }

  // The first block, one in the middle and the last removed; the others keep their order.
  std::vector<int> new_index(blocks);
  int kept = 0;
  for (int i = 0; i < blocks; ++i)
    new_index[i] = (i == 0 || i == 17 || i == blocks - 1) ? -1 : kept++;
  list.renumber(new_index);
  const auto survives = [&](const ContactPreload& p) {
    return new_index[static_cast<std::size_t>(p.a)] >= 0 &&
           new_index[static_cast<std::size_t>(p.b)] >= 0;
  };
  EXPECT_EQ(list.size(),
            static_cast<std::size_t>(std::count_if(given.begin(), given.end(), survives)));
  expect_as_scan(list, kept);
  for (const ContactPreload& p : given) {
    const ContactPreload* found = list.find(new_index[static_cast<std::size_t>(p.a)],
                                            new_index[static_cast<std::size_t>(p.b)]);
    if (!survives(p)) continue;
    ASSERT_NE(found, nullptr);
    EXPECT_EQ(found->closure, p.closure);
  }

  ContactPreloads none;
  EXPECT_EQ(none.find(0, 1), nullptr);
  none.assign({});
  EXPECT_EQ(none.find(0, 1), nullptr);
}

}  // namespace
}  // namespace blockdem
