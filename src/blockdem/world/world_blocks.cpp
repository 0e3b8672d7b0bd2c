// World block bookkeeping beyond the step: the water's total force, per-face joint laws and block
// removal (excavation).
#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

#include "blockdem/world/world.hpp"

namespace blockdem {

Eigen::Vector3d World::total_water_force() const {
  // Exact sums over the free blocks this process counts, reduced over the processes.
  std::array<ExactSum, 3> sums;
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    const Block& b = blocks_[i];
    if (!b.is_dynamic() || !counts_block(i)) continue;
    for (int k = 0; k < 3; ++k) sums[static_cast<std::size_t>(k)].add(b.water_force()[k]);
  }
  reduce_partials(sums, {}, {});
  return {sums[0].value(), sums[1].value(), sums[2].value()};
}

void World::set_face_laws(int block, std::span<const int> law_per_plane) {
  if (block < 0 || block >= static_cast<int>(blocks_.size()))
    throw std::invalid_argument("set_face_laws: no block " + std::to_string(block));
  if (law_per_plane.size() != blocks_[block].shape.planes().size())
    throw std::invalid_argument("set_face_laws: block '" + blocks_[block].name + "' has " +
                                std::to_string(blocks_[block].shape.planes().size()) +
                                " planes, got " + std::to_string(law_per_plane.size()) + " laws");
  for (int law : law_per_plane) {
    if (law < -1 || law >= static_cast<int>(laws_.size()))
      throw std::invalid_argument("set_face_laws: unknown joint law " + std::to_string(law));
  }
  face_laws_.set(static_cast<std::size_t>(block), law_per_plane);
}

void World::remove_blocks(const std::vector<int>& indices) {
  decomposition_.require_replica("remove_blocks");
  drop_primed();  // kept by block indices
  std::vector<int> new_index(blocks_.size(), 0);
  for (int i : indices) {
    if (i < 0 || i >= static_cast<int>(blocks_.size()))
      throw std::invalid_argument("remove_blocks: no block " + std::to_string(i));
    new_index[i] = -1;
  }
  std::vector<Block> kept;
  std::vector<APrioriShape> kept_a_priori;
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    if (new_index[i] < 0) continue;
    new_index[i] = static_cast<int>(kept.size());
    kept.push_back(std::move(blocks_[i]));
    kept.back().index = new_index[i];
    kept_a_priori.push_back(a_priori_shape_[i]);
  }
  blocks_ = std::move(kept);
  preloads_.renumber(new_index);
  renumber_bolts(new_index);
  std::size_t kept_relaxing = 0;
  for (Relaxation& r : relaxation_) {
    r.block = new_index[static_cast<std::size_t>(r.block)];
    if (r.block >= 0) relaxation_[kept_relaxing++] = r;
  }
  relaxation_.resize(kept_relaxing);
  energy_.restart();  // the removed blocks' energy leaves the budget
  face_laws_.keep(new_index);
  face_sets_.keep(new_index);
  a_priori_shape_ = std::move(kept_a_priori);
  // Pairs with a removed block go; the others keep their history under the new indices. The
  // renumbering keeps the order of the blocks, so the slots stay sorted by (a, b).
  std::size_t kept_slots = 0;
  for (auto& slot : slots_) {
    if (new_index[slot.a] < 0 || new_index[slot.b] < 0) continue;
    slot.a = new_index[slot.a];
    slot.b = new_index[slot.b];
    if (slot.contact >= 0) {
      Contact& c = contact_of(slot);
      c.a = slot.a;
      c.b = slot.b;
    }
    slots_[kept_slots++] = slot;
  }
  slots_.resize(kept_slots);
  compact_contacts();
  std::vector<std::pair<int, int>>().swap(pairs_);  // the next broad phase refills it
  active_count_ = 0;
  for (const auto& slot : slots_) active_count_ += slot.active ? 1 : 0;
  overlap_violation_ = -1;
  update_geometry(thread_count());
  save_checkpoint();
}

}  // namespace blockdem
