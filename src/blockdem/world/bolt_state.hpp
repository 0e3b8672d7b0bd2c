// A world's bolts as bytes, for restart files (world_state.cpp).
#pragma once

#include <cstddef>
#include <vector>

#include "blockdem/world/bolt.hpp"
#include "blockdem/world/state_stream.hpp"

namespace blockdem {

/// Every field of each bolt, in order.
void save_bolts(StateWriter& w, const std::vector<Bolt>& bolts);
/// What save_bolts wrote, for a world of `blocks` blocks (a bolt tied to a block index beyond
/// them is refused: StateError, as for truncated or corrupt bytes).
std::vector<Bolt> load_bolts(StateReader& r, std::size_t blocks);

}  // namespace blockdem
