// The rule that gives each candidate pair of blocks of a distributed world one owner process (the
// one that evaluates its contact), shared by the step (world/decomposition_step.cpp) and the
// outputs written per process (io/vtu.hpp).
#pragma once

#include <vector>

namespace blockdem {

/// The owner process of the pair (a, b), from each block's owner process (`owners`, indexed by
/// block) and whether each block can move: the owner of the block that can move when only one
/// can; otherwise of a when a + b is odd, of b when even (so that pairs across a subdomain
/// boundary split about evenly between the two sides). 0 when `owners` is empty (no partition
/// yet).
inline int pair_owner_process(const std::vector<int>& owners, int a, bool a_moves, int b,
                              bool b_moves) {
  if (owners.empty()) return 0;
  if (a_moves != b_moves) return owners[static_cast<std::size_t>(a_moves ? a : b)];
  return owners[static_cast<std::size_t>(((a + b) & 1) != 0 ? a : b)];
}

}  // namespace blockdem
