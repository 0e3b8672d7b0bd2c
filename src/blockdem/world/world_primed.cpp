// The set-up's narrow phase, kept for the first step: the check of the initial overlaps solves
// every candidate pair cold at the blocks' starting poses, which is exactly what the first step
// does again (its pairs are new, so their warm starts are empty). The step takes the kept results
// (warm starts and geometry, the same bits) for the pairs whose blocks have not moved.
#include <algorithm>
#include <bit>
#include <cstdint>

#include "blockdem/world/world.hpp"

namespace blockdem {
namespace {

bool same_bits(double x, double y) {
  return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y);
}

bool same_bits(const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
  return same_bits(x.x(), y.x()) && same_bits(x.y(), y.y()) && same_bits(x.z(), y.z());
}

}  // namespace

void World::prime_narrow_phase(
    const std::vector<std::pair<int, int>>& pairs,
    const std::function<void(std::int64_t, const ContactGeometry&)>& visit) {
  drop_primed();
  // The slots the next step opens (merge_pairs' fresh slots), at their places in `pairs`.
  std::vector<std::int32_t> slot_of(pairs.size(), -1);
  std::size_t count = 0;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (steps_pair(pairs[k].first, pairs[k].second))
      slot_of[k] = static_cast<std::int32_t>(count++);
  }
  // With merge_pairs' slack of an eighth, which the next steps' new pairs fill.
  primed_slots_.reserve(count + count / 8);
  primed_slots_.resize(count);
  primed_area_.assign(count, kNotPrimed);
  // A contact's result is kept only without twist, which reads the slice polygon as well.
  const bool keep_contacts = !settings_.twist_enabled();
  const std::int64_t n = static_cast<std::int64_t>(pairs.size());
  const int threads = thread_count();
#pragma omp parallel for num_threads(threads) schedule(dynamic, 64) if (threads > 1 && n > 64)
  for (std::int64_t k = 0; k < n; ++k) {
    const auto [i, j] = pairs[static_cast<std::size_t>(k)];
    const Block& a = blocks_[static_cast<std::size_t>(i)];
    const Block& b = blocks_[static_cast<std::size_t>(j)];
    const double extent = 2.0 * (a.shape.bounding_radius() + b.shape.bounding_radius());
    Boon2012Cache cache;
    const ContactGeometry g =
        boon2012_contact(a.world_planes, b.world_planes, extent, settings_.boon2012, &cache);
    visit(k, g);
    const std::int32_t s = slot_of[static_cast<std::size_t>(k)];
    if (s < 0) continue;
    PairSlot& slot = primed_slots_[static_cast<std::size_t>(s)];
    slot.a = i;
    slot.b = j;
    slot.group_law = law_for(i, j);
    if (step_count_ > 0) slot.bond = BondState::unbonded;  // as merge_pairs opens it
    // What the step reads of the geometry: a contact has a positive area and overlap.
    const bool contact = g.touching && g.area > 0.0 && g.overlap > 0.0;
    if (contact && !keep_contacts) continue;  // solved again, from an empty warm start
    slot.narrow_cache = pack_warm_start(cache);
    primed_area_[static_cast<std::size_t>(s)] = contact ? g.area : 0.0;
  }
  primed_poses_.reserve(blocks_.size());
  for (const Block& b : blocks_) primed_poses_.push_back({b.position, b.orientation, b.shape});
  primed_settings_ = settings_.boon2012;
  primed_step_ = step_count_;
}

void World::drop_primed() {
  std::vector<PairSlot>().swap(primed_slots_);
  std::vector<double>().swap(primed_area_);
  std::vector<PrimedPose>().swap(primed_poses_);
}

void World::take_primed_slots() {
  if (primed_area_.empty()) return;
  // Taken only as a whole: into a step without slots whose pairs are the primed ones, with the
  // same narrow-phase settings and blocks (a changed block's pairs are solved again).
  bool take = slots_.empty() && step_count_ == primed_step_ &&
              pairs_.size() == primed_slots_.size() && primed_poses_.size() == blocks_.size() &&
              same_bits(primed_settings_.rounding_distance, settings_.boon2012.rounding_distance) &&
              same_bits(primed_settings_.overlap_tolerance, settings_.boon2012.overlap_tolerance);
  for (std::size_t k = 0; take && k < pairs_.size(); ++k) {
    take = primed_slots_[k].a == pairs_[k].first && primed_slots_[k].b == pairs_[k].second;
  }
  if (!take) {
    drop_primed();
    return;
  }
  std::vector<std::uint8_t> unchanged(blocks_.size());
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    const Block& b = blocks_[i];
    const PrimedPose& p = primed_poses_[i];
    unchanged[i] = same_bits(b.position, p.position) &&
                   same_bits(b.orientation.coeffs().x(), p.orientation.coeffs().x()) &&
                   same_bits(b.orientation.coeffs().y(), p.orientation.coeffs().y()) &&
                   same_bits(b.orientation.coeffs().z(), p.orientation.coeffs().z()) &&
                   same_bits(b.orientation.coeffs().w(), p.orientation.coeffs().w()) &&
                   b.shape.shares_data_with(p.shape);
  }
  std::vector<PrimedPose>().swap(primed_poses_);
  for (std::size_t k = 0; k < primed_slots_.size(); ++k) {
    PairSlot& s = primed_slots_[k];
    if (unchanged[static_cast<std::size_t>(s.a)] && unchanged[static_cast<std::size_t>(s.b)])
      continue;
    s.narrow_cache = NarrowWarmStart{};
    primed_area_[k] = kNotPrimed;
  }
  slots_ = std::move(primed_slots_);
  primed_slots_.clear();
}

ContactGeometry World::narrow_phase(PairSlot& slot, const Block& a, const Block& b,
                                    double extent) const {
  const std::size_t k = static_cast<std::size_t>(&slot - slots_.data());
  if (k < primed_area_.size() && primed_area_[k] != kNotPrimed) {
    // The cold solve of the set-up at these very poses: its warm start is the slot's already,
    // the contact point its last point, from which steps 3 and 4 give the same normal and
    // overlap again; the area (step 5, whose warm start of the cold solve is gone) was kept.
    ContactGeometry g;
    const NarrowWarmStart& w = slot.narrow_cache;
    g.inscribed_radius = w.radius;
    g.inscribed_centre = w.center;
    if (primed_area_[k] > 0.0) {
      g.touching = true;
      g.point = w.last_point;
      boon2012_normal_and_overlap(a.world_planes, b.world_planes, g.point, settings_.boon2012,
                                  g.normal, g.overlap);
      g.area = primed_area_[k];
    }
    return g;
  }
  Boon2012Cache cache = unpack_warm_start(slot.narrow_cache);
  const ContactGeometry g =
      boon2012_contact(a.world_planes, b.world_planes, extent, settings_.boon2012, &cache);
  slot.narrow_cache = pack_warm_start(cache);
  return g;
}

}  // namespace blockdem
