// The set-up's narrow phase, kept for the first step: the check of the initial overlaps solves
// every candidate pair cold at the blocks' starting poses, which is exactly what the first step
// does again (its pairs are new, so their warm starts are empty). The step takes the kept results
// (warm starts and geometry, the same bits) for the pairs whose blocks have not moved.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>

#include "blockdem/world/pass_support.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {
namespace {

bool same_bits(double x, double y) {
  return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y);
}

bool same_bits(const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
  return same_bits(x.x(), y.x()) && same_bits(x.y(), y.y()) && same_bits(x.z(), y.z());
}

// Whether every vertex of B lies beyond the plane of A's face of the joint they share (A inside
// n·x <= d), to the tolerance of shared_face: A and B then overlap within a slab of that
// thickness at most, no initial overlap.
bool beyond_shared_plane(const Block& a, const Block& b, const ContactPreload& p) {
  const Halfspace& h = a.world_planes[static_cast<std::size_t>(p.plane_a)];
  const double tolerance = 1e-9 * (a.shape.bounding_radius() + b.shape.bounding_radius());
  for (const Eigen::Vector3d& v : b.shape.vertices()) {
    if (h.signed_distance(b.to_world(v)) < -tolerance) return false;
  }
  return true;
}

}  // namespace

// The cache's layout, field for field: a field added to Boon2012Cache, InscribedBall or
// SliceWarmStart must be added to NarrowWarmStart and the two functions below. They sit in the
// file of narrow_phase, which calls them for every pair and step: inlined there, the fields of
// the cache that the other writes over are not cleared first.
static_assert(sizeof(Boon2012Cache) == 184 && sizeof(InscribedBall) == 64 &&
                  sizeof(SliceWarmStart) == 72,
              "the narrow-phase cache changed: update World::NarrowWarmStart");

World::NarrowWarmStart World::pack_warm_start(const Boon2012Cache& cache) {
  // Every index in [-1, kMax]: tested over whole arrays without a branch per index (signed
  // comparisons or-ed together, which the compiler makes vector operations).
  constexpr int kMax = std::numeric_limits<std::int16_t>::max();
  const auto outside = [](int i) { return static_cast<int>(i < -1) | static_cast<int>(i > kMax); };
  int out = outside(cache.planes_a) | outside(cache.planes_b);
  for (int i : cache.ball.active) out |= outside(i);
  for (int i : cache.slice.edge_planes) out |= outside(i);
  const bool bad = out != 0 || cache.ball.num_active < 0 || cache.ball.num_active > 4 ||
                   cache.slice.count > cache.slice.edge_planes.size();
  NarrowWarmStart w;
  if (bad) return w;
  w.radius = cache.ball.radius;
  w.center = cache.ball.center;
  w.last_point = cache.last_point;
  for (std::size_t k = 0; k < 4; ++k) w.active[k] = static_cast<std::int16_t>(cache.ball.active[k]);
  for (std::size_t k = 0; k < w.edge_planes.size(); ++k)
    w.edge_planes[k] = static_cast<std::int16_t>(cache.slice.edge_planes[k]);
  w.planes_a = static_cast<std::int16_t>(cache.planes_a);
  w.planes_b = static_cast<std::int16_t>(cache.planes_b);
  w.num_active = static_cast<std::uint8_t>(cache.ball.num_active);
  w.slice_count = static_cast<std::uint8_t>(cache.slice.count);
  w.flags = static_cast<std::uint8_t>((cache.has_ball ? NarrowWarmStart::kHasBall : 0) |
                                      (cache.ball.bounded ? NarrowWarmStart::kBounded : 0) |
                                      (cache.has_point ? NarrowWarmStart::kHasPoint : 0));
  return w;
}

Boon2012Cache World::unpack_warm_start(const NarrowWarmStart& w) {
  Boon2012Cache c;
  c.planes_a = w.planes_a;
  c.planes_b = w.planes_b;
  c.ball.radius = w.radius;
  c.ball.center = w.center;
  c.ball.bounded = (w.flags & NarrowWarmStart::kBounded) != 0;
  for (std::size_t k = 0; k < 4; ++k) c.ball.active[k] = w.active[k];
  c.ball.num_active = w.num_active;
  c.has_ball = (w.flags & NarrowWarmStart::kHasBall) != 0;
  c.last_point = w.last_point;
  c.has_point = (w.flags & NarrowWarmStart::kHasPoint) != 0;
  for (std::size_t k = 0; k < w.edge_planes.size(); ++k) c.slice.edge_planes[k] = w.edge_planes[k];
  c.slice.count = w.slice_count;
  return c;
}

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
  pass_support::populate_pages(primed_slots_.data(), count * sizeof(PairSlot), thread_count());
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
    // A prestressed pair is solved by the step with its face plane moved out, so its result
    // here would not be kept; when B lies beyond A's face of the shared face, it is not solved.
    const ContactPreload* preload = preloads_.find(i, j);
    const bool apart = preload != nullptr && beyond_shared_plane(a, b, *preload);
    Boon2012Cache cache;
    ContactGeometry g;
    if (!apart) {
      const double extent = 2.0 * (a.shape.bounding_radius() + b.shape.bounding_radius());
      g = boon2012_contact(a.world_planes, b.world_planes, extent, settings_.boon2012, &cache);
      visit(k, g);
    }
    const std::int32_t s = slot_of[static_cast<std::size_t>(k)];
    if (s < 0) continue;
    PairSlot& slot = primed_slots_[static_cast<std::size_t>(s)];
    slot.a = i;
    slot.b = j;
    slot.group_law = law_for(i, j);
    if (step_count_ > 0) slot.bond = BondState::unbonded;  // as merge_pairs opens it
    if (preload != nullptr) continue;                      // solved with its face plane moved out
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

ContactGeometry World::narrow_phase(PairSlot& slot, std::span<const Halfspace> planes_a,
                                    const Block& a, const Block& b, double extent) const {
  const std::size_t k = static_cast<std::size_t>(&slot - slots_.data());
  // Each path builds its result in the caller's object: the geometry holds the slice polygon's
  // vertices inline (~300 bytes), which a copy per pair and step would move again.
  const auto primed = [&] {
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
  };
  const auto solve = [&] {
    Boon2012Cache cache = unpack_warm_start(slot.narrow_cache);
    ContactGeometry g =
        boon2012_contact(planes_a, b.world_planes, extent, settings_.boon2012, &cache);
    slot.narrow_cache = pack_warm_start(cache);
    return g;
  };
  if (k < primed_area_.size() && primed_area_[k] != kNotPrimed) return primed();
  return solve();
}

}  // namespace blockdem
