// The contacts' loads scattered onto their blocks in (a, b) order, as a serial pass over the slots
// would form them, for any number of threads; with them the contact count, the broken bonds, the
// first too-deep overlap, the contacts' energy terms and the automatic time step's minimum.
#include <algorithm>
#include <cmath>
#include <exception>
#include <iterator>
#include <limits>
#include <optional>
#include <stdexcept>

#include "blockdem/contact/twist.hpp"
#include "blockdem/response/contact_twist.hpp"
#include "blockdem/world/pass_support.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

using namespace pass_support;

namespace {

// A contact's loads on one of its blocks: on b its force at the force point and its twisting
// couple about the normal (M n), on a the opposite of both (the same bits as subtracting them);
// with them the block's stiffness sums, k A for translation and for rotation k A (|r|² + A/12),
// the second term the rocking stiffness of a spread face, plus the twist spring's.
template <bool kOnB>
void add_contact_load(const Contact& ct, Block& block, double& stiffness, double& rotational) {
  const Eigen::Vector3d& xf = ct.force_point();
  const Eigen::Vector3d f = kOnB ? ct.force_on_b() : Eigen::Vector3d(-ct.force_on_b());
  block.force += f;
  block.contact_force += f;
  block.torque += (xf - block.position).cross(f);
  if (ct.couple_about_normal() != 0.0) {
    const double couple = kOnB ? ct.couple_about_normal() : -ct.couple_about_normal();
    const Eigen::Vector3d moment = couple * ct.geometry.normal;
    block.torque += moment;
  }
  const double k = ct.stiffness;
  const double spread = ct.compressed_area() / 12.0;
  stiffness += k;
  rotational += k * ((xf - block.position).squaredNorm() + spread);
  rotational += ct.twist_stiffness;
}

// The slots (sorted by a) cut into `runs` runs of about equal slot counts, each cut at a
// block's first slot: run t holds the blocks [first[t], first[t+1]) and the slots
// [begin[t], begin[t+1]).
void split_into_runs(const std::vector<PairSlot>& slots, std::size_t n_blocks, std::size_t runs,
                     std::vector<std::size_t>& first, std::vector<std::size_t>& begin) {
  const std::size_t m = slots.size();
  first.assign(runs + 1, n_blocks);
  begin.assign(runs + 1, m);
  first[0] = 0;
  begin[0] = 0;
  for (std::size_t t = 1; t < runs; ++t) {
    const std::size_t at = t * m / runs;
    first[t] = at < m ? std::max(first[t - 1], static_cast<std::size_t>(slots[at].a)) : n_blocks;
    begin[t] = static_cast<std::size_t>(
        std::lower_bound(
            slots.begin() + static_cast<std::ptrdiff_t>(begin[t - 1]), slots.end(), first[t],
            [](const PairSlot& s, std::size_t a) { return static_cast<std::size_t>(s.a) < a; }) -
        slots.begin());
  }
}

// The automatic time step's bound over the blocks [first, last): sqrt(m / k) and sqrt(I / k_r)
// of each dynamic block with a contact (a minimum: exact in any order).
double blocks_step_bound(const std::vector<Block>& blocks, const std::vector<double>& stiffness,
                         const std::vector<double>& rotational, std::size_t first,
                         std::size_t last) {
  double dt_min = std::numeric_limits<double>::infinity();
  for (std::size_t i = first; i < last; ++i) {
    // The stiffness first: a block with no contact here (one that another process holds)
    // needs no visit to its record.
    if (stiffness[i] <= 0.0) continue;
    const Block& bl = blocks[i];
    if (!bl.is_dynamic()) continue;
    dt_min = std::min(dt_min, std::sqrt(bl.inertial_mass() / stiffness[i]));
    dt_min = std::min(dt_min, std::sqrt(bl.inertial_moments().minCoeff() / rotational[i]));
  }
  return dt_min;
}

// The stiffness sums cleared for a step: every block's, or (`kept` set: a distributed step)
// those of the blocks whose loads this process sums, the others left as they are.
void clear_stiffness_sums(std::vector<double>& sums, std::size_t n_blocks,
                          const std::vector<int>* kept) {
  if (kept == nullptr) {
    sums.assign(n_blocks, 0.0);
    return;
  }
  sums.resize(n_blocks, 0.0);
  for (const int i : *kept) sums[static_cast<std::size_t>(i)] = 0.0;
}

}  // namespace

void World::scatter_loads(const std::vector<char>* counted) {
  // Every block's sums are formed in (a, b) order, as a serial pass over the slots would form
  // them, for any number of threads. The slots are split into T runs of whole blocks (run t:
  // the slots whose a is in [first_[t], first_[t+1])). A block's terms in slot order are those
  // where it is b (from slots with a smaller a) and then those where it is a, so run t's blocks
  // take first the terms of earlier runs' slots whose b falls in run t (listed by those runs,
  // in slot order), then run t's own slots in order. The pass also counts contacts and broken
  // bonds, finds the first too-deep overlap, sums the contacts' energies (exact sums) and the
  // automatic time step's minimum over blocks (a minimum is exact).
  //
  // A distributed step (`counted` set) sums the loads and stiffnesses of the blocks of
  // keeps_loads_ alone (its own and the resting ones): a ghost's are not read (its owner sums
  // its own), nor are any of a block this process does not hold. Each kept block's terms are
  // the same, in the same order. Its counts, energy terms and overlap check cover the counted
  // slots, and it takes its time-step minimum over its own blocks.
  const std::size_t n_blocks = blocks_.size();
  const std::size_t m = slots_.size();
  const char* keeps = counted != nullptr ? decomposition_.keeps_loads().data() : nullptr;
  clear_stiffness_sums(stiffness_, n_blocks,
                       keeps != nullptr ? &decomposition_.kept_list() : nullptr);
  clear_stiffness_sums(rotational_stiffness_, n_blocks,
                       keeps != nullptr ? &decomposition_.kept_list() : nullptr);
  const int threads = thread_count();

  const auto load_b = [&](const PairSlot& s) {
    const Contact& ct = contact_of(s);
    add_contact_load<true>(ct, blocks_[ct.b], stiffness_[ct.b], rotational_stiffness_[ct.b]);
  };
  const auto load_a = [&](const PairSlot& s) {
    const Contact& ct = contact_of(s);
    add_contact_load<false>(ct, blocks_[ct.a], stiffness_[ct.a], rotational_stiffness_[ct.a]);
  };

  struct RunTotals {
    std::int64_t broken = 0;
    std::size_t active = 0;
    std::int64_t violation = -1;
    double dt_min = std::numeric_limits<double>::infinity();
    EnergyStepSums energy;
  };
  std::vector<RunTotals> totals;
  const std::int64_t big_enough = 256;
  // The body of the pass, run by each thread of a team, or alone outside any parallel region
  // (its single and barrier constructs then bind to no team and cost nothing: a team of one
  // would still wake the runtime's futex at each barrier, a fixed cost per step that small
  // scenes of many steps feel).
  const auto pass = [&] {
#pragma omp single
    {
      const std::size_t runs = static_cast<std::size_t>(team_size());
      totals.resize(runs);
      split_into_runs(slots_, n_blocks, runs, scatter_first_, scatter_begin_);
      scatter_cross_.resize(runs);
    }
    const auto t = static_cast<std::size_t>(team_rank());
    const std::size_t runs = totals.size();
    const std::size_t begin = scatter_begin_[t], end = scatter_begin_[t + 1];
    const std::size_t last = scatter_first_[t + 1];  // past this run's blocks
    // 1. This run's slots whose b lies in a later run.
    std::vector<std::size_t>& cross = scatter_cross_[t];
    cross.clear();
    if (runs > 1) {
      for (std::size_t k = begin; k < end; ++k) {
        const PairSlot& s = slots_[k];
        if (s.active && static_cast<std::size_t>(s.b) >= last) cross.push_back(k);
      }
    }
#pragma omp barrier
    // 2. The earlier runs' terms on this run's blocks, in slot order; then this run's slots.
    const std::size_t first = scatter_first_[t];
    for (std::size_t r = 0; r < t; ++r) {
      for (const std::size_t k : scatter_cross_[r]) {
        const PairSlot& s = slots_[k];
        const auto b = static_cast<std::size_t>(s.b);
        if (b >= first && b < last && (keeps == nullptr || keeps[b] != 0)) load_b(s);
      }
    }
    RunTotals mine;  // local: no cache line shared with another run's totals
    for (std::size_t k = begin; k < end; ++k) {
      if (k + kPrefetchRecord < end) {
        const PairSlot& ahead = slots_[k + kPrefetchRecord];
        if (ahead.active) {
          prefetch_loads(blocks_[static_cast<std::size_t>(ahead.b)]);
          if (ahead.a != slots_[k + kPrefetchRecord - 1].a)
            prefetch_loads(blocks_[static_cast<std::size_t>(ahead.a)]);
        }
      }
      const PairSlot& s = slots_[k];
      const bool counts = counted == nullptr || (*counted)[k] != 0;
      // A bond that broke in tension leaves its slot inactive.
      if (s.broke && counts) ++mine.broken;
      if (!s.active) continue;
      if (keeps == nullptr || keeps[s.a] != 0) load_a(s);
      if (static_cast<std::size_t>(s.b) < last && (keeps == nullptr || keeps[s.b] != 0)) load_b(s);
      if (!counts) continue;
      ++mine.active;
      const Contact& ct = contact_of(s);
      mine.energy.add_contact(ct, ct.twist_stiffness, ct.slip_work);
      if (mine.violation < 0) {
        const double size = std::min(blocks_[ct.a].bounding_radius, blocks_[ct.b].bounding_radius);
        if (ct.geometry.overlap > settings_.max_overlap_fraction * size)
          mine.violation = static_cast<std::int64_t>(k);
      }
    }
    // 3. This run's blocks are complete: their time-step bound.
    if (keeps == nullptr)
      mine.dt_min = blocks_step_bound(blocks_, stiffness_, rotational_stiffness_, first, last);
    totals[t] = std::move(mine);
  };
  if (threads > 1 && static_cast<std::int64_t>(m) > big_enough) {
#pragma omp parallel num_threads(threads)
    pass();
  } else {
    pass();
  }
  active_count_ = 0;
  overlap_violation_ = -1;
  double dt_min = std::numeric_limits<double>::infinity();
  std::int64_t broke = 0;
  for (const RunTotals& r : totals) {
    broke += r.broken;
    broken_bonds_ += r.broken;
    active_count_ += r.active;
    if (overlap_violation_ < 0) overlap_violation_ = r.violation;
    dt_min = std::min(dt_min, r.dt_min);
  }
  // Broken bonds per joint set and cause (rare: only in a step where one broke). A distributed
  // step sums the processes' tables first (Decomposition::reduce_step_checks).
  step_breaks_.clear();
  if (broke > 0) {
    tally_step_breaks(counted);
    if (counted == nullptr) add_step_breaks(step_breaks_);
  }
  // One run (one thread, or a small scene): its sums are taken as they are, without the
  // normalisations of +=, a fixed cost per step that small scenes of many steps feel. The sums
  // are exact, so their values are the same bits either way.
  if (totals.size() == 1) {
    contact_energy_ = std::move(totals.front().energy);
  } else {
    contact_energy_ = EnergyStepSums{};
    for (const RunTotals& r : totals) contact_energy_ += r.energy;
  }
  contact_energy_.contact_damping += dashpot_carried_;
  contact_dt_ = 0.0;
  if (std::isfinite(dt_min)) contact_dt_ = settings_.safety_factor * dt_min;
}

}  // namespace blockdem
