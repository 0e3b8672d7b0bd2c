// A world spread over processes: block ownership and the pairs each process owns, the measures
// counted without the whole world (exact reductions, merges to process 0), the resting blocks,
// and the partition (recursive coordinate bisection over the processes).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "blockdem/world/decomposition.hpp"
#include "blockdem/world/decomposition_wire.hpp"
#include "blockdem/world/pair_owner.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

using namespace decomposition_wire;

void Decomposition::require_replica(const char* what) const {
  if (!replica_complete_)
    throw std::logic_error(std::string(what) +
                           ": the distributed world is not whole here; call synchronize() first");
}

int Decomposition::pair_owner(const World& world, int a, int b) const {
  // One owner per pair, by a rule on the blocks' global indices (world/pair_owner.hpp).
  return pair_owner_process(owner_, a, world.blocks_[a].is_dynamic(), b,
                            world.blocks_[b].is_dynamic());
}

std::vector<const Contact*> Decomposition::counted_contacts(const World& world) const {
  const auto counted = [&](const World::PairSlot& s) {
    return s.active && (replica_complete_ ||
                        pair_owner(world, s.a, s.b) == world.settings_.distribution->rank());
  };
  // Sized exactly: grown by doubling, the list (an output's, at the run's peak of memory) would
  // hold up to twice its pointers, and three times while it moves.
  std::vector<const Contact*> out;
  out.reserve(
      static_cast<std::size_t>(std::count_if(world.slots_.begin(), world.slots_.end(), counted)));
  for (const auto& s : world.slots_) {
    if (counted(s)) out.push_back(&world.contact_of(s));
  }
  return out;
}

bool Decomposition::counts_contact(const World& world, const Contact& c) const {
  return replica_complete_ || pair_owner(world, c.a, c.b) == world.settings_.distribution->rank();
}

void Decomposition::reduce_partials(const World& world, std::span<ExactSum> sums,
                                    std::span<double> maxima,
                                    std::span<std::int64_t> counts) const {
  if (replica_complete_) return;
  PairDistribution& dist = *world.settings_.distribution;
  // One integer-sum reduction for the accumulators' limbs and the counts (exact in any order),
  // one minimum of the negated maxima (exact).
  std::vector<std::int64_t> ints;
  ints.reserve(sums.size() * ExactSum::kLimbs + counts.size());
  for (const ExactSum& s : sums) {
    const auto l = s.limbs();
    ints.insert(ints.end(), l.begin(), l.end());
  }
  ints.insert(ints.end(), counts.begin(), counts.end());
  const std::vector<std::int64_t> total = dist.sum(ints);
  const std::span<const std::int64_t> all(total);
  for (std::size_t k = 0; k < sums.size(); ++k)
    sums[k] = ExactSum::from_limbs(all.subspan(k * ExactSum::kLimbs, ExactSum::kLimbs));
  for (std::size_t k = 0; k < counts.size(); ++k)
    counts[k] = total[sums.size() * ExactSum::kLimbs + k];
  std::int64_t bytes = static_cast<std::int64_t>(ints.size() * sizeof(std::int64_t));
  if (!maxima.empty()) {
    std::vector<double> negated(maxima.begin(), maxima.end());
    for (double& x : negated) x = -x;
    const std::vector<double> least = dist.min(negated);
    for (std::size_t k = 0; k < maxima.size(); ++k) maxima[k] = -least[k];
    bytes += static_cast<std::int64_t>(maxima.size() * sizeof(double));
  }
  dist_stats_.bytes_sent += bytes;
  dist_stats_.bytes_received += bytes;
}

std::vector<int> Decomposition::gather_indices(const World& world,
                                               const std::vector<int>& mine) const {
  if (replica_complete_) return mine;
  std::vector<char> bytes(mine.size() * sizeof(std::int32_t));
  for (std::size_t k = 0; k < mine.size(); ++k) {
    const auto v = static_cast<std::int32_t>(mine[k]);
    std::memcpy(bytes.data() + k * sizeof v, &v, sizeof v);
  }
  std::vector<std::size_t> counts;
  const std::vector<char> all = world.settings_.distribution->all_gather(bytes, counts);
  std::vector<int> out(all.size() / sizeof(std::int32_t));
  for (std::size_t k = 0; k < out.size(); ++k) {
    std::int32_t v = 0;
    std::memcpy(&v, all.data() + k * sizeof v, sizeof v);
    out[k] = v;
  }
  std::sort(out.begin(), out.end());
  dist_stats_.bytes_sent += static_cast<std::int64_t>(bytes.size());
  dist_stats_.bytes_received += static_cast<std::int64_t>(all.size() - bytes.size());
  return out;
}

void Decomposition::merge_to_root(const World& world, std::size_t count,
                                  const std::function<std::uint64_t(std::size_t)>& key,
                                  const std::function<void(std::size_t, std::string&)>& record,
                                  const std::function<void(std::string_view)>& emit) const {
  std::string text;
  if (replica_complete_ || !world.settings_.distribution) {
    for (std::size_t k = 0; k < count; ++k) {
      text.clear();
      record(k, text);
      emit(text);
    }
    return;
  }
  // Rounds of one broadcast (which processes send their next chunk, and whether to go on) and
  // one gather to process 0. Process 0 asks only the processes whose records it has used up, so
  // it holds at most one chunk per process; it emits a record once no process that still has
  // records can send a smaller key. A chunk: a flag (1: this process's last), then records as
  // key, length, bytes.
  PairDistribution& dist = *world.settings_.distribution;
  const int rank = dist.rank();
  const auto procs = static_cast<std::size_t>(dist.size());
  struct Queue {
    std::vector<char> bytes;
    std::size_t at = 0;
    bool done = false;
  };
  std::vector<Queue> queues(rank == 0 ? procs : 0);
  std::vector<char> ask(procs + 1, 1);  // [r]: process r sends a chunk; [procs]: another round
  std::size_t next = 0;
  dist_stats_.output_merges += 1;
  for (;;) {
    dist.broadcast(ask);
    if (ask.size() != procs + 1) throw std::logic_error("merge_to_root: a malformed request");
    if (ask[procs] == 0) break;
    std::vector<char> chunk;
    if (ask[static_cast<std::size_t>(rank)] != 0) {
      chunk.push_back(0);
      while (next < count && chunk.size() < World::kMergeChunkBytes) {
        text.clear();
        record(next, text);
        put(chunk, key(next));
        put(chunk, static_cast<std::uint64_t>(text.size()));
        put_bytes(chunk, text.data(), text.size());
        ++next;
      }
      chunk[0] = next == count ? 1 : 0;
    }
    std::vector<std::size_t> counts;
    std::vector<char> all = dist.gather(chunk, counts);
    if (rank != 0) {
      dist_stats_.output_bytes_sent += static_cast<std::int64_t>(chunk.size());
      continue;
    }
    dist_stats_.output_bytes_received += static_cast<std::int64_t>(all.size() - chunk.size());
    std::size_t begin = 0;
    for (std::size_t r = 0; r < procs; begin += counts[r], ++r) {
      if (counts[r] == 0) continue;
      Queue& q = queues[r];
      q.bytes.assign(all.begin() + static_cast<std::ptrdiff_t>(begin + 1),
                     all.begin() + static_cast<std::ptrdiff_t>(begin + counts[r]));
      q.at = 0;
      q.done = all[begin] != 0;
    }
    std::vector<char>().swap(all);
    for (;;) {
      std::size_t best = procs;
      std::uint64_t best_key = 0;
      bool stalled = false;
      for (std::size_t r = 0; r < procs && !stalled; ++r) {
        const Queue& q = queues[r];
        if (q.at == q.bytes.size()) {
          stalled = !q.done;
          continue;
        }
        const auto k = get<std::uint64_t>(q.bytes, q.at);
        if (best == procs || k < best_key) best = r, best_key = k;
      }
      if (stalled || best == procs) break;
      Queue& q = queues[best];
      const auto size = get<std::uint64_t>(q.bytes, q.at + 8);
      if (q.at + 16 + size > q.bytes.size())
        throw std::logic_error("merge_to_root: a process sent a malformed chunk");
      emit(std::string_view(q.bytes.data() + q.at + 16, size));
      q.at += 16 + size;
    }
    bool more = false;
    for (std::size_t r = 0; r < procs; ++r) {
      const Queue& q = queues[r];
      ask[r] = q.at == q.bytes.size() && !q.done ? 1 : 0;
      more = more || ask[r] != 0 || q.at != q.bytes.size();
    }
    ask[procs] = more ? 1 : 0;
  }
}

std::vector<std::pair<int, Eigen::Vector3d>> Decomposition::resting_contact_forces(
    const World& world) const {
  std::vector<std::pair<int, Eigen::Vector3d>> out;
  if (replica_complete_ || !world.settings_.distribution || resting_.size() != world.blocks_.size())
    return out;
  // Every process marks the same resting blocks (on a whole world), so all take this path alike.
  std::vector<std::size_t> at(world.blocks_.size(), world.blocks_.size());
  for (std::size_t i = 0; i < world.blocks_.size(); ++i) {
    if (resting_[i] == 0) continue;
    at[i] = out.size();
    out.emplace_back(static_cast<int>(i), Eigen::Vector3d::Zero());
  }
  if (out.empty()) return out;
  // The owned contacts with a resting block, merged to process 0 in (a, b) order and summed
  // there as sum_resting_loads sums them; then the sums to every process.
  const int rank = world.settings_.distribution->rank();
  std::vector<const World::PairSlot*> mine;
  for (const World::PairSlot& s : world.slots_) {
    if (s.active && (resting_[s.a] != 0 || resting_[s.b] != 0) &&
        pair_owner(world, s.a, s.b) == rank)
      mine.push_back(&s);
  }
  struct Term {
    std::int32_t a, b;
    double f[3];
  };
  merge_to_root(
      world, mine.size(),
      [&](std::size_t k) {
        return (static_cast<std::uint64_t>(mine[k]->a) << 32) |
               static_cast<std::uint32_t>(mine[k]->b);
      },
      [&](std::size_t k, std::string& text) {
        const Eigen::Vector3d f = world.contact_of(*mine[k]).force_on_b();
        const Term t{mine[k]->a, mine[k]->b, {f.x(), f.y(), f.z()}};
        text.append(reinterpret_cast<const char*>(&t), sizeof t);
      },
      [&](std::string_view text) {
        Term t;
        std::memcpy(static_cast<void*>(&t), text.data(), sizeof t);
        const Eigen::Vector3d f(t.f[0], t.f[1], t.f[2]);
        for (const int i : {t.a, t.b}) {
          const std::size_t j = at[static_cast<std::size_t>(i)];
          if (j == world.blocks_.size()) continue;
          if (i == t.b)
            out[j].second += f;
          else
            out[j].second -= f;
        }
      });
  std::vector<char> bytes;
  for (const auto& [i, f] : out) put3(bytes, f);
  world.settings_.distribution->broadcast(bytes);
  if (bytes.size() != out.size() * 24)
    throw std::logic_error("resting contact forces: a malformed broadcast");
  for (std::size_t k = 0; k < out.size(); ++k) out[k].second = get3(bytes, 24 * k);
  return out;
}

void Decomposition::mark_resting(World& world) {
  require_replica("mark_resting");
  // A fixed block keeps its pose, and its zero velocities, until a caller changes it on a whole
  // world: its state is then the same bytes on every process, and it needs no owner's loads.
  resting_.assign(world.blocks_.size(), 0);
  for (std::size_t i = 0; i < world.blocks_.size(); ++i)
    resting_[i] = at_rest(world.blocks_[i]) ? 1 : 0;
  list_own_blocks(world);
}

void Decomposition::list_own_blocks(World& world) {
  const std::size_t n = world.blocks_.size();
  own_list_.clear();
  moving_list_.clear();
  kept_list_.clear();
  keeps_loads_.assign(n, 0);
  // Before the first partition (mark_resting runs first), own_ is not yet the world's.
  if (own_.size() != n || resting_.size() != n) return;
  for (std::size_t i = 0; i < n; ++i) {
    const int b = static_cast<int>(i);
    if (own_[i] != 0) own_list_.push_back(b);
    if (own_[i] != 0 && resting_[i] == 0) moving_list_.push_back(b);
    if (own_[i] != 0 || resting_[i] != 0) {
      kept_list_.push_back(b);
      keeps_loads_[i] = 1;
    }
  }
}

void Decomposition::sum_resting_loads(World& world) {
  // The loads on a resting block come from pairs that other processes own, and no process keeps
  // them whole between refreshes (nothing in a step reads them). On a whole world they are summed
  // again from every slot with scatter_loads's arithmetic, in its (a, b) order, and the energy
  // ledger's record of the step's contact impulses (EnergyLedger::block_terms: dt F, dt T for a
  // block that does not move) follows, so the world is one process's, bit for bit.
  const std::size_t n = world.blocks_.size();
  if (resting_.size() != n) return;
  bool any = false;
  for (std::size_t i = 0; i < n; ++i) {
    if (resting_[i] == 0) continue;
    Block& b = world.blocks_[i];
    b.force.setZero();
    b.torque.setZero();
    b.contact_force.setZero();
    world.stiffness_[i] = 0.0;
    world.rotational_stiffness_[i] = 0.0;
    any = true;
  }
  if (!any) return;
  for (const World::PairSlot& s : world.slots_) {
    if (!s.active) continue;
    const Contact& ct = world.contact_of(s);
    const Eigen::Vector3d& xf = ct.force_point();
    const Eigen::Vector3d f = ct.force_on_b();
    const double spread = ct.compressed_area() / 12.0;
    for (const int i : {ct.a, ct.b}) {
      const auto k = static_cast<std::size_t>(i);
      if (resting_[k] == 0) continue;
      Block& b = world.blocks_[k];
      if (i == ct.b) {
        b.force += f;
        b.contact_force += f;
        b.torque += (xf - b.position).cross(f);
        if (ct.couple_about_normal() != 0.0)
          b.torque += ct.couple_about_normal() * ct.geometry.normal;
      } else {
        b.force -= f;
        b.contact_force -= f;
        b.torque -= (xf - b.position).cross(f);
        if (ct.couple_about_normal() != 0.0)
          b.torque -= ct.couple_about_normal() * ct.geometry.normal;
      }
      world.stiffness_[k] += ct.stiffness;
      world.rotational_stiffness_[k] += ct.stiffness * ((xf - b.position).squaredNorm() + spread);
      world.rotational_stiffness_[k] += ct.twist_stiffness;
    }
  }
  if (world.step_count_ == 0) return;
  world.energy_.prepare(n);
  double record[EnergyLedger::kBlockRecordDoubles];
  constexpr std::size_t kContact = 24;  // the record's dt F, then dt T (block_record's order)
  for (std::size_t i = 0; i < n; ++i) {
    if (resting_[i] == 0) continue;
    world.energy_.block_record(i, record);
    const Eigen::Vector3d impulse = world.last_dt_ * world.blocks_[i].contact_force;
    const Eigen::Vector3d angular = world.last_dt_ * world.blocks_[i].torque;
    for (int k = 0; k < 3; ++k) {
      record[kContact + static_cast<std::size_t>(k)] = impulse[k];
      record[kContact + 3 + static_cast<std::size_t>(k)] = angular[k];
    }
    world.energy_.set_block_record(i, record);
  }
}

void Decomposition::partition_blocks(World& world) {
  require_replica("partition");
  mark_resting(world);
  // Weight: one for the block plus one per candidate pair it is in (the narrow phase's work),
  // which a resting block leaves to the other block's owner.
  std::vector<Eigen::Vector3d> points(world.blocks_.size());
  std::vector<double> weights(world.blocks_.size(), 1.0);
  for (std::size_t i = 0; i < world.blocks_.size(); ++i) points[i] = world.blocks_[i].position;
  for (const auto& s : world.slots_) {
    for (const int i : {s.a, s.b})
      if (resting_[static_cast<std::size_t>(i)] == 0) weights[static_cast<std::size_t>(i)] += 1.0;
  }
  owner_ = world.settings_.distribution->partition(points, weights);
  if (owner_.size() != world.blocks_.size())
    throw std::logic_error("partition: one owner per block expected");
  const int rank = world.settings_.distribution->rank();
  own_.assign(world.blocks_.size(), 0);
  for (std::size_t i = 0; i < world.blocks_.size(); ++i) own_[i] = owner_[i] == rank ? 1 : 0;
  list_own_blocks(world);
  partition_step_ = world.step_count_;
  ++dist_stats_.partitions;
}

}  // namespace blockdem
