// A step spread over processes (settings().distribution). Each process owns the blocks of its
// subdomain (recursive coordinate bisection) and the pairs the ownership rule gives it; it finds
// the pairs of its own blocks, evaluates its own pairs, sends each pair slot to the owner of the
// pair's other block, sums the loads on its own blocks in the serial (a, b) order, integrates
// them, and sends their new states to the processes that hold them as ghosts. Global quantities
// are reduced exactly (minima, integer sums, exact accumulators of doubles). Every
// exact block and slot is bit for bit what one process computes; synchronize() gathers the
// whole world when a caller reads it. A new partition moves only the blocks that change owner,
// point to point, with their slots (migrate_blocks).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "blockdem/dynamics/integrator.hpp"
#include "blockdem/world/pair_owner.hpp"
#include "blockdem/world/world.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace blockdem {
namespace {

/// A process's figures of one step, gathered to every process (a few bytes per process).
struct StepHeader {
  double seconds = 0.0;      ///< time in this step's own pair work (s)
  std::uint64_t slots = 0;   ///< pairs it evaluated (-)
  std::uint64_t failed = 0;  ///< 1: a pair of this process refused a value; 2: another error
};

/// A block's state as a ghost needs it: the pose and the velocities at the half step.
struct GhostState {
  std::int64_t index = 0;
  double position[3];
  double orientation[4];
  double velocity[3];
  double angular_velocity[3];
  double angular_momentum[3];
};

/// A block's whole step state, for a replica refresh.
struct ReplicaBlock {
  GhostState state;
  double force[3];
  double torque[3];
  double contact_force[3];
  double stiffness = 0.0;
  double rotational_stiffness = 0.0;
  double energy[EnergyLedger::kBlockRecordDoubles];
  double aabb_min[3];  ///< the box and the world planes (which follow) of the step's start pose
  double aabb_max[3];
  std::uint64_t planes = 0;
};

/// Rebalance when the slowest process's pair work exceeds the mean by this factor (-)...
constexpr double kImbalanceThreshold = 1.25;
/// ... and at least this many steps have passed since the last partition (-).
constexpr std::int64_t kMinStepsBetweenPartitions = 100;
/// ... and the slowest process loses more than this per step against the mean (s): below it the
/// measured times are mostly noise, and an imbalance costs nothing worth a partition.
constexpr double kMinImbalanceSeconds = 1e-3;
/// ... and the processes' pair counts are uneven by this factor too (-): the bisection balances
/// pair counts, so only then can a new partition help (and counts carry no timing noise).
constexpr double kPairCountThreshold = 1.1;

void put_bytes(std::vector<char>& out, const void* p, std::size_t n) {
  // An empty part's data() may be null, which memcpy may not be given even for no bytes.
  if (n == 0) return;
  const std::size_t at = out.size();
  out.resize(at + n);
  std::memcpy(out.data() + at, p, n);
}

template <class T>
void put(std::vector<char>& out, const T& value) {
  static_assert(std::is_trivially_copyable_v<T>);
  put_bytes(out, &value, sizeof(T));
}

template <class T>
T get(const std::vector<char>& in, std::size_t offset) {
  T value;
  std::memcpy(static_cast<void*>(&value), in.data() + offset, sizeof(T));
  return value;
}

void put3(std::vector<char>& out, const Eigen::Vector3d& v) {
  for (int k = 0; k < 3; ++k) put(out, v[k]);
}

Eigen::Vector3d get3(const std::vector<char>& in, std::size_t offset) {
  return {get<double>(in, offset), get<double>(in, offset + 8), get<double>(in, offset + 16)};
}

GhostState ghost_of(const Block& b) {
  GhostState g;
  g.index = b.index;
  for (int k = 0; k < 3; ++k) {
    g.position[k] = b.position[k];
    g.velocity[k] = b.velocity[k];
    g.angular_velocity[k] = b.angular_velocity[k];
    g.angular_momentum[k] = b.angular_momentum[k];
  }
  for (int k = 0; k < 4; ++k) g.orientation[k] = b.orientation.coeffs()[k];
  return g;
}

void set_ghost(Block& b, const GhostState& g) {
  for (int k = 0; k < 3; ++k) {
    b.position[k] = g.position[k];
    b.velocity[k] = g.velocity[k];
    b.angular_velocity[k] = g.angular_velocity[k];
    b.angular_momentum[k] = g.angular_momentum[k];
  }
  for (int k = 0; k < 4; ++k) b.orientation.coeffs()[k] = g.orientation[k];
}

/// A pair slot on the wire: its bytes, then its contact's when a force acts (`contact`, non-null
/// exactly then; contact_to_bytes). A slot holds fixed-size data only (no pointers, no heap
/// storage), and every process runs the same program.
template <class Slot>
void put_slot(std::vector<char>& out, const Slot& s, const Contact* contact) {
  static_assert(std::is_trivially_destructible_v<Slot>, "a pair slot must be plain data");
  put_bytes(out, &s, sizeof(Slot));
  if (!s.active) return;
  char bytes[kContactBytes];
  contact_to_bytes(*contact, bytes);
  put_bytes(out, bytes, kContactBytes);
}

/// Reads put_slot's record at `at` (advanced past it), not beyond `end`; false when malformed.
template <class Slot>
bool get_slot(const std::vector<char>& in, std::size_t& at, std::size_t end, Slot& s,
              Contact& contact) {
  if (at + sizeof(Slot) > end) return false;
  std::memcpy(static_cast<void*>(&s), in.data() + at, sizeof(Slot));
  at += sizeof(Slot);
  if (!s.active) return true;
  if (at + kContactBytes > end) return false;
  contact = contact_from_bytes(in.data() + at);
  at += kContactBytes;
  return true;
}

/// A block that mark_resting marks resting: fixed, with zero velocities.
bool at_rest(const Block& b) {
  return b.motion == Motion::fixed && (b.velocity.array() == 0.0).all() &&
         (b.angular_velocity.array() == 0.0).all();
}

/// The slot list's index of the pair whose key (a n + b) is `key`, among the slots `counts`
/// accepts, or -1: the first too-deep overlap a reduction found, located in a process's slots.
template <class Slots, class Accept>
std::int64_t slot_of_key(const Slots& slots, std::size_t n, double key, const Accept& counts) {
  if (!std::isfinite(key)) return -1;
  for (std::size_t k = 0; k < slots.size(); ++k) {
    const auto& c = slots[k];
    if (static_cast<double>(c.a) * static_cast<double>(n) + c.b == key && counts(c))
      return static_cast<std::int64_t>(k);
  }
  return -1;
}

bool boxes_overlap(const Eigen::Vector3d& min_a, const Eigen::Vector3d& max_a,
                   const Eigen::Vector3d& min_b, const Eigen::Vector3d& max_b) {
  return (min_a.array() <= max_b.array()).all() && (min_b.array() <= max_a.array()).all();
}

}  // namespace

void World::require_replica(const char* what) const {
  if (!replica_complete_)
    throw std::logic_error(std::string(what) +
                           ": the distributed world is not whole here; call synchronize() first");
}

int World::pair_owner(int a, int b) const {
  // One owner per pair, by a rule on the blocks' global indices (world/pair_owner.hpp).
  return pair_owner_process(owner_, a, blocks_[a].is_dynamic(), b, blocks_[b].is_dynamic());
}

std::vector<const Contact*> World::counted_contacts() const {
  const auto counted = [&](const PairSlot& s) {
    return s.active && (replica_complete_ || pair_owner(s) == settings_.distribution->rank());
  };
  // Sized exactly: grown by doubling, the list (an output's, at the run's peak of memory) would
  // hold up to twice its pointers, and three times while it moves.
  std::vector<const Contact*> out;
  out.reserve(static_cast<std::size_t>(std::count_if(slots_.begin(), slots_.end(), counted)));
  for (const auto& s : slots_) {
    if (counted(s)) out.push_back(&contact_of(s));
  }
  return out;
}

bool World::counts_contact(const Contact& c) const {
  return replica_complete_ || pair_owner(c.a, c.b) == settings_.distribution->rank();
}

void World::reduce_partials(std::span<ExactSum> sums, std::span<double> maxima,
                            std::span<std::int64_t> counts) const {
  if (replica_complete_) return;
  PairDistribution& dist = *settings_.distribution;
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

std::vector<int> World::gather_indices(const std::vector<int>& mine) const {
  if (replica_complete_) return mine;
  std::vector<char> bytes(mine.size() * sizeof(std::int32_t));
  for (std::size_t k = 0; k < mine.size(); ++k) {
    const auto v = static_cast<std::int32_t>(mine[k]);
    std::memcpy(bytes.data() + k * sizeof v, &v, sizeof v);
  }
  std::vector<std::size_t> counts;
  const std::vector<char> all = settings_.distribution->all_gather(bytes, counts);
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

void World::merge_to_root(std::size_t count, const std::function<std::uint64_t(std::size_t)>& key,
                          const std::function<void(std::size_t, std::string&)>& record,
                          const std::function<void(std::string_view)>& emit) const {
  std::string text;
  if (replica_complete_ || !settings_.distribution) {
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
  PairDistribution& dist = *settings_.distribution;
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
      while (next < count && chunk.size() < kMergeChunkBytes) {
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

std::vector<std::pair<int, Eigen::Vector3d>> World::resting_contact_forces() const {
  std::vector<std::pair<int, Eigen::Vector3d>> out;
  if (replica_complete_ || !settings_.distribution || resting_.size() != blocks_.size()) return out;
  // Every process marks the same resting blocks (on a whole world), so all take this path alike.
  std::vector<std::size_t> at(blocks_.size(), blocks_.size());
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    if (resting_[i] == 0) continue;
    at[i] = out.size();
    out.emplace_back(static_cast<int>(i), Eigen::Vector3d::Zero());
  }
  if (out.empty()) return out;
  // The owned contacts with a resting block, merged to process 0 in (a, b) order and summed
  // there as sum_resting_loads sums them; then the sums to every process.
  const int rank = settings_.distribution->rank();
  std::vector<const PairSlot*> mine;
  for (const PairSlot& s : slots_) {
    if (s.active && (resting_[s.a] != 0 || resting_[s.b] != 0) && pair_owner(s) == rank)
      mine.push_back(&s);
  }
  struct Term {
    std::int32_t a, b;
    double f[3];
  };
  merge_to_root(
      mine.size(),
      [&](std::size_t k) {
        return (static_cast<std::uint64_t>(mine[k]->a) << 32) |
               static_cast<std::uint32_t>(mine[k]->b);
      },
      [&](std::size_t k, std::string& text) {
        const Eigen::Vector3d f = contact_of(*mine[k]).force_on_b();
        const Term t{mine[k]->a, mine[k]->b, {f.x(), f.y(), f.z()}};
        text.append(reinterpret_cast<const char*>(&t), sizeof t);
      },
      [&](std::string_view text) {
        Term t;
        std::memcpy(static_cast<void*>(&t), text.data(), sizeof t);
        const Eigen::Vector3d f(t.f[0], t.f[1], t.f[2]);
        for (const int i : {t.a, t.b}) {
          const std::size_t j = at[static_cast<std::size_t>(i)];
          if (j == blocks_.size()) continue;
          if (i == t.b)
            out[j].second += f;
          else
            out[j].second -= f;
        }
      });
  std::vector<char> bytes;
  for (const auto& [i, f] : out) put3(bytes, f);
  settings_.distribution->broadcast(bytes);
  if (bytes.size() != out.size() * 24)
    throw std::logic_error("resting contact forces: a malformed broadcast");
  for (std::size_t k = 0; k < out.size(); ++k) out[k].second = get3(bytes, 24 * k);
  return out;
}

void World::mark_resting() {
  require_replica("mark_resting");
  // A fixed block keeps its pose, and its zero velocities, until a caller changes it on a whole
  // world: its state is then the same bytes on every process, and it needs no owner's loads.
  resting_.assign(blocks_.size(), 0);
  for (std::size_t i = 0; i < blocks_.size(); ++i) resting_[i] = at_rest(blocks_[i]) ? 1 : 0;
  list_own_blocks();
}

void World::list_own_blocks() {
  const std::size_t n = blocks_.size();
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

void World::sum_resting_loads() {
  // The loads on a resting block come from pairs that other processes own, and no process keeps
  // them whole between refreshes (nothing in a step reads them). On a whole world they are summed
  // again from every slot with scatter_loads's arithmetic, in its (a, b) order, and the energy
  // ledger's record of the step's contact impulses (EnergyLedger::block_terms: dt F, dt T for a
  // block that does not move) follows, so the world is one process's, bit for bit.
  const std::size_t n = blocks_.size();
  if (resting_.size() != n) return;
  bool any = false;
  for (std::size_t i = 0; i < n; ++i) {
    if (resting_[i] == 0) continue;
    Block& b = blocks_[i];
    b.force.setZero();
    b.torque.setZero();
    b.contact_force.setZero();
    stiffness_[i] = 0.0;
    rotational_stiffness_[i] = 0.0;
    any = true;
  }
  if (!any) return;
  for (const PairSlot& s : slots_) {
    if (!s.active) continue;
    const Contact& ct = contact_of(s);
    const Eigen::Vector3d& xf = ct.force_point();
    const Eigen::Vector3d f = ct.force_on_b();
    const double spread = ct.compressed_area() / 12.0;
    for (const int i : {ct.a, ct.b}) {
      const auto k = static_cast<std::size_t>(i);
      if (resting_[k] == 0) continue;
      Block& b = blocks_[k];
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
      stiffness_[k] += ct.stiffness;
      rotational_stiffness_[k] += ct.stiffness * ((xf - b.position).squaredNorm() + spread);
      rotational_stiffness_[k] += ct.twist_stiffness;
    }
  }
  if (step_count_ == 0) return;
  energy_.prepare(n);
  double record[EnergyLedger::kBlockRecordDoubles];
  constexpr std::size_t kContact = 24;  // the record's dt F, then dt T (block_record's order)
  for (std::size_t i = 0; i < n; ++i) {
    if (resting_[i] == 0) continue;
    energy_.block_record(i, record);
    const Eigen::Vector3d impulse = last_dt_ * blocks_[i].contact_force;
    const Eigen::Vector3d angular = last_dt_ * blocks_[i].torque;
    for (int k = 0; k < 3; ++k) {
      record[kContact + static_cast<std::size_t>(k)] = impulse[k];
      record[kContact + 3 + static_cast<std::size_t>(k)] = angular[k];
    }
    energy_.set_block_record(i, record);
  }
}

void World::partition_blocks() {
  require_replica("partition");
  mark_resting();
  // Weight: one for the block plus one per candidate pair it is in (the narrow phase's work),
  // which a resting block leaves to the other block's owner.
  std::vector<Eigen::Vector3d> points(blocks_.size());
  std::vector<double> weights(blocks_.size(), 1.0);
  for (std::size_t i = 0; i < blocks_.size(); ++i) points[i] = blocks_[i].position;
  for (const auto& s : slots_) {
    for (const int i : {s.a, s.b})
      if (resting_[static_cast<std::size_t>(i)] == 0) weights[static_cast<std::size_t>(i)] += 1.0;
  }
  owner_ = settings_.distribution->partition(points, weights);
  if (owner_.size() != blocks_.size())
    throw std::logic_error("partition: one owner per block expected");
  const int rank = settings_.distribution->rank();
  own_.assign(blocks_.size(), 0);
  for (std::size_t i = 0; i < blocks_.size(); ++i) own_[i] = owner_[i] == rank ? 1 : 0;
  list_own_blocks();
  partition_step_ = step_count_;
  ++dist_stats_.partitions;
}

void World::migrate_blocks() {
  PairDistribution& dist = *settings_.distribution;
  const int rank = dist.rank();
  const auto k_ranks = static_cast<std::size_t>(dist.size());
  const std::size_t n = blocks_.size();
  const auto t0 = std::chrono::steady_clock::now();
  std::int64_t sent = 0, received = 0;

  // 1. The partition's input, as partition_blocks() takes it from a whole world: each block's
  // centroid, whether it is at rest (mark_resting), and the number of slots it is in. Its owner
  // holds them exactly: after the step's pair exchange every slot of an own block that is not
  // resting is here, exact (the pair's owner, which is one of the two blocks' owners, sent it),
  // and no slot is here twice. A record of 28 bytes per block, gathered to every process in the
  // order of the owners' block lists, which every process knows (owner_).
  std::vector<std::uint32_t> pair_count(n, 0);
  for (const PairSlot& s : slots_) {
    for (const int i : {s.a, s.b})
      if (own_[static_cast<std::size_t>(i)] != 0) ++pair_count[static_cast<std::size_t>(i)];
  }
  constexpr std::size_t kInput = 3 * sizeof(double) + sizeof(std::uint32_t);
  std::vector<char> input;
  input.reserve(own_list_.size() * kInput);
  for (const int h : own_list_) {
    const auto i = static_cast<std::size_t>(h);
    if (pair_count[i] > (std::numeric_limits<std::uint32_t>::max() >> 1))
      throw std::logic_error("migration: a block in too many pairs");
    put3(input, blocks_[i].position);
    put(input, static_cast<std::uint32_t>(pair_count[i] << 1 | (at_rest(blocks_[i]) ? 1u : 0u)));
  }
  std::vector<std::size_t> counts;
  const std::vector<char> inputs = dist.all_gather(input, counts);
  sent += static_cast<std::int64_t>(input.size());
  received += static_cast<std::int64_t>(inputs.size() - input.size());
  std::vector<std::uint32_t>().swap(pair_count);
  std::vector<std::size_t> cursor(k_ranks, 0);
  for (std::size_t r = 1; r < k_ranks; ++r) cursor[r] = cursor[r - 1] + counts[r - 1];
  std::vector<Eigen::Vector3d> points(n);
  std::vector<double> weights(n, 1.0);
  bool rest_changed = false;
  for (std::size_t i = 0; i < n; ++i) {
    const auto r = static_cast<std::size_t>(owner_[i]);
    std::size_t& at = cursor[r];
    if (at + kInput > inputs.size())
      throw std::logic_error("migration: a process sent a malformed partition input");
    points[i] = get3(inputs, at);
    const auto word = get<std::uint32_t>(inputs, at + 24);
    at += kInput;
    const bool resting = (word & 1u) != 0;
    rest_changed = rest_changed || resting != (resting_[i] != 0);
    // 1 + the pair count, as partition_blocks adds 1.0 per slot (exact: integers).
    if (!resting) weights[i] += static_cast<double>(word >> 1);
  }
  for (std::size_t r = 0, end = 0; r < k_ranks; ++r) {
    end += counts[r];
    if (cursor[r] != end)
      throw std::logic_error("migration: a process sent a malformed partition input");
  }
  if (rest_changed) {
    // A block came to rest or left it (a caller's change, or a servo that stopped a fixed block):
    // the resting blocks' loads are summed only on a whole world, so every process (all see the
    // same flags) makes it whole and partitions it.
    dist_stats_.migration_bytes_sent += sent;
    dist_stats_.migration_bytes_received += received;
    synchronize();
    partition_blocks();
    return;
  }
  std::vector<int> owners = dist.partition(points, weights);
  if (owners.size() != n) throw std::logic_error("partition: one owner per block expected");
  std::vector<Eigen::Vector3d>().swap(points);
  std::vector<double>().swap(weights);

  // 2. Each own block whose owner changes, to its new owner: its state, loads, stiffness sums,
  // energy record, world planes and box (what a refresh would send; a divergence checkpoint in
  // parts stays as it is, gathered from the parts as they were saved). Its servo and applied
  // loads change only on a whole world, alike everywhere. With it, its slots (contact states
  // included) that the new owner does not hold exactly: all but those whose other block that
  // process owns and does not rest. The new owner needs every slot of its blocks that do not
  // rest: its own pairs among them, and the others' for the loads' sums in (a, b) order.
  std::vector<std::vector<char>> block_part(k_ranks), slot_part(k_ranks);
  std::vector<std::uint64_t> blocks_to(k_ranks, 0), slots_to(k_ranks, 0);
  for (const int h : own_list_) {
    const auto i = static_cast<std::size_t>(h);
    const auto q = static_cast<std::size_t>(owners[i]);
    if (static_cast<int>(q) == rank) continue;
    put_block_state(block_part[q], i);
    ++blocks_to[q];
  }
  const auto moving_to = [&](int block) {
    const auto i = static_cast<std::size_t>(block);
    return own_[i] != 0 && resting_[i] == 0 && owners[i] != rank ? owners[i] : -1;
  };
  const auto holds = [&](int q, int block) {
    const auto i = static_cast<std::size_t>(block);
    return owner_[i] == q && resting_[i] == 0;
  };
  for (const PairSlot& s : slots_) {
    const int qa = moving_to(s.a), qb = moving_to(s.b);
    if (qa < 0 && qb < 0) continue;
    const Contact* state = s.active ? &contact_of(s) : nullptr;
    if (qa >= 0 && !holds(qa, s.b)) {
      put_slot(slot_part[static_cast<std::size_t>(qa)], s, state);
      ++slots_to[static_cast<std::size_t>(qa)];
    }
    if (qb >= 0 && qb != qa && !holds(qb, s.a)) {
      put_slot(slot_part[static_cast<std::size_t>(qb)], s, state);
      ++slots_to[static_cast<std::size_t>(qb)];
    }
  }
  std::vector<std::vector<char>> to(k_ranks);
  for (std::size_t q = 0; q < k_ranks; ++q) {
    if (blocks_to[q] == 0 && slots_to[q] == 0) continue;
    to[q].reserve(16 + block_part[q].size() + slot_part[q].size());
    put(to[q], blocks_to[q]);
    put(to[q], slots_to[q]);
    put_bytes(to[q], block_part[q].data(), block_part[q].size());
    put_bytes(to[q], slot_part[q].data(), slot_part[q].size());
    std::vector<char>().swap(block_part[q]);
    std::vector<char>().swap(slot_part[q]);
    dist_stats_.migrated_blocks += static_cast<std::int64_t>(blocks_to[q]);
    dist_stats_.migrated_slots += static_cast<std::int64_t>(slots_to[q]);
    sent += static_cast<std::int64_t>(to[q].size());
  }
  const std::vector<std::vector<char>> from = dist.exchange(to);
  std::vector<std::vector<char>>().swap(to);

  // 3. The received blocks into place; the received slots in a list, their states apart.
  stiffness_.resize(n, 0.0);
  rotational_stiffness_.resize(n, 0.0);
  energy_.prepare(n);
  std::vector<PairSlot> arrived;
  std::vector<Contact> arrived_states;
  for (std::size_t r = 0; r < k_ranks; ++r) {
    const std::vector<char>& part = from[r];
    received += static_cast<std::int64_t>(part.size());
    if (part.empty()) continue;
    if (part.size() < 16) throw std::logic_error("migration: a process sent a malformed part");
    const auto blocks_in = get<std::uint64_t>(part, 0);
    const auto slots_in = get<std::uint64_t>(part, 8);
    std::size_t at = 16;
    for (std::uint64_t k = 0; k < blocks_in; ++k) {
      std::size_t i = 0;
      at = take_block_state(part, at, part.size(), true, i);
      if (owner_[i] != static_cast<int>(r) || owners[i] != rank)
        throw std::logic_error("migration: a block came from a process that did not own it");
    }
    for (std::uint64_t k = 0; k < slots_in; ++k) {
      PairSlot s;
      Contact c;
      if (!get_slot(part, at, part.size(), s, c))
        throw std::logic_error("migration: a process sent a malformed part");
      s.pending = false;
      s.contact = -1;
      if (s.active) {
        s.contact = static_cast<std::int32_t>(arrived_states.size());
        arrived_states.push_back(c);
      }
      arrived.push_back(s);
    }
    if (at != part.size()) throw std::logic_error("migration: a process sent a malformed part");
  }

  // 4. The new owners.
  owner_ = std::move(owners);
  for (std::size_t i = 0; i < n; ++i) own_[i] = owner_[i] == rank ? 1 : 0;
  list_own_blocks();
  partition_step_ = step_count_;
  ++dist_stats_.partitions;

  // 5. The slots as a step leaves them: those of the blocks this process now keeps (own, not
  // resting), in (a, b) order, every one exact; the contact states in slot order. A pair that
  // arrived from two processes (its blocks came from both) holds the same bytes in both.
  const auto keeps = [&](int block) {
    const auto i = static_cast<std::size_t>(block);
    return own_[i] != 0 && resting_[i] == 0;
  };
  const auto kept = [&](const PairSlot& s) { return keeps(s.a) || keeps(s.b); };
  std::erase_if(slots_, [&](const PairSlot& s) { return !kept(s); });
  const auto before = [](const PairSlot& x, const PairSlot& y) {
    return x.a < y.a || (x.a == y.a && x.b < y.b);
  };
  std::sort(arrived.begin(), arrived.end(), before);
  std::vector<PairSlot> slots;
  slots.reserve(slots_.size() + arrived.size());
  std::vector<Contact> contacts;
  std::size_t p = 0;
  for (std::size_t q = 0; q <= arrived.size(); ++q) {
    // The held slots before the next arrived one (all of them after the last), then that one
    // unless held or already taken.
    while (p < slots_.size() && (q == arrived.size() || !before(arrived[q], slots_[p]))) {
      PairSlot s = slots_[p++];
      if (s.active) {
        contacts.push_back(contact_of(s));
        s.contact = static_cast<std::int32_t>(contacts.size() - 1);
      } else {
        s.contact = -1;
      }
      slots.push_back(s);
    }
    if (q == arrived.size()) break;
    PairSlot s = arrived[q];
    if (!slots.empty() && slots.back().a == s.a && slots.back().b == s.b) continue;
    if (!kept(s)) throw std::logic_error("migration: a slot of no block this process keeps");
    if (s.active) {
      contacts.push_back(arrived_states[static_cast<std::size_t>(s.contact)]);
      s.contact = static_cast<std::int32_t>(contacts.size() - 1);
    }
    slots.push_back(s);
  }
  slots_ = std::move(slots);
  contacts_ = std::move(contacts);
  std::vector<PairSlot>().swap(arrived);
  std::vector<Contact>().swap(arrived_states);
  pairs_.resize(slots_.size());
  for (std::size_t k = 0; k < slots_.size(); ++k) pairs_[k] = {slots_[k].a, slots_[k].b};
  overlap_violation_ = slot_of_key(slots_, n, overlap_key_,
                                   [&](const PairSlot& c) { return pair_owner(c) == rank; });

  // 6. Ghosts for the next step, for the new subdomains: the ghost exchange with the slots' sends
  // (an own block to the owner of its pair's other block, neither resting) listed as the step
  // lists them.
  pair_sends_.clear();
  for (const PairSlot& c : slots_) {
    const auto ca = static_cast<std::size_t>(c.a), cb = static_cast<std::size_t>(c.b);
    if ((own_[ca] != 0 && own_[cb] != 0) || resting_[ca] != 0 || resting_[cb] != 0) continue;
    if (own_[ca] != 0) pair_sends_.emplace_back(c.a, owner_[cb]);
    if (own_[cb] != 0) pair_sends_.emplace_back(c.b, owner_[ca]);
  }
  const std::int64_t ghost_sent = dist_stats_.bytes_sent,
                     ghost_received = dist_stats_.bytes_received;
  ghosts_listed_ = false;
  exchange_ghosts();
  sent += dist_stats_.bytes_sent - ghost_sent;
  received += dist_stats_.bytes_received - ghost_received;
  dist_stats_.bytes_sent = ghost_sent;
  dist_stats_.bytes_received = ghost_received;

  dist_stats_.migrations += 1;
  dist_stats_.migration_bytes_sent += sent;
  dist_stats_.migration_bytes_received += received;
  dist_stats_.migration_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void World::save_checkpoint_part() {
  // What save_checkpoint takes from a whole world, taken from this process's exact part: its
  // blocks (own_) and the pairs it owns, each by the same rule (docs/scaling.md, "Checkpoints in
  // parts"). Every process saves at the same step, so the parts are alike in kind everywhere.
  const int rank = settings_.distribution->rank();
  const std::size_t n = blocks_.size();
  std::vector<int> part;
  for (std::size_t i = 0; i < n; ++i)
    if (own_[i] != 0) part.push_back(static_cast<int>(i));
  std::vector<BlockState> states;
  std::vector<Motion> motions;
  states.reserve(part.size());
  motions.reserve(part.size());
  checkpoint_.servos.clear();
  for (const int i : part) {
    const Block& b = blocks_[static_cast<std::size_t>(i)];
    states.push_back(
        {b.position, b.velocity, b.angular_velocity, b.angular_momentum, b.orientation});
    motions.push_back(b.motion);
    if (!same_bits(b.servo(), Servo{}))
      checkpoint_.servos.emplace_back(static_cast<std::size_t>(i), b.servo());
  }
  checkpoint_.blocks = std::move(states);
  checkpoint_.motions = std::move(motions);
  checkpoint_.part_blocks = std::move(part);
  // The slots save_checkpoint keeps, of the pairs this process owns, in (a, b) order.
  std::vector<ContactHistory> contacts;
  std::vector<BondHistory> bonds;
  for (const auto& s : slots_)
    if (pair_owner(s) == rank) keep_slot(s, contacts, bonds);
  checkpoint_.contacts = std::move(contacts);
  checkpoint_.bonds = std::move(bonds);
  // A resting block's energy record holds the step's contact impulses, which a refresh sums
  // from every process's contacts (sum_resting_loads): the terms of this process's contacts on
  // resting blocks, in (a, b) order, summed when the parts are gathered. First (kept here, alike
  // everywhere) the step and the resting blocks, then 12 values per contact.
  std::vector<double> rest{last_dt_, 0.0};
  if (resting_.size() == n) {
    for (std::size_t i = 0; i < n; ++i)
      if (resting_[i] != 0) rest.push_back(static_cast<double>(i));
    rest[1] = static_cast<double>(rest.size() - 2);
    for (const auto& s : slots_) {
      if (!s.active || pair_owner(s) != rank) continue;
      if (resting_[static_cast<std::size_t>(s.a)] == 0 &&
          resting_[static_cast<std::size_t>(s.b)] == 0)
        continue;
      const Contact& ct = contact_of(s);
      const Eigen::Vector3d xf = ct.force_point(), f = ct.force_on_b();
      rest.insert(rest.end(),
                  {static_cast<double>(ct.a), static_cast<double>(ct.b), f[0], f[1], f[2], xf[0],
                   xf[1], xf[2], ct.couple_about_normal(), ct.geometry.normal[0],
                   ct.geometry.normal[1], ct.geometry.normal[2]});
    }
  }
  checkpoint_.part_resting = std::move(rest);
  checkpoint_.time = time_;
  checkpoint_.step_count = step_count_;
  checkpoint_.broken_bonds = broken_bonds_;
  // The whole ledger: its budget is every process's; of its per-block records only the own
  // blocks' are exact, the others are set when the parts are gathered (as synchronize sets them).
  checkpoint_.energy = energy_;
  checkpoint_.valid = true;
  checkpoint_.partial = true;
}

void World::gather_checkpoint() {
  if (!checkpoint_.partial) return;
  static_assert(std::is_trivially_destructible_v<ContactHistory>);
  static_assert(std::is_trivially_copyable_v<BondHistory>);
  PairDistribution& dist = *settings_.distribution;
  const int rank = dist.rank();
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t n = blocks_.size();
  Checkpoint& cp = checkpoint_;
  cp.energy.prepare(n);
  // This process's part: its blocks (index, state, motion, energy record), servos and contacts.
  struct PartBlock {
    std::int64_t index = 0;
    double state[16];
    std::int64_t motion = 0;
    double energy[EnergyLedger::kBlockRecordDoubles];
  };
  static_assert(std::is_trivially_copyable_v<PartBlock>);
  std::vector<char> out;
  put(out, static_cast<std::uint64_t>(cp.part_blocks.size()));
  put(out, static_cast<std::uint64_t>(cp.servos.size()));
  put(out, static_cast<std::uint64_t>(cp.contacts.size()));
  put(out, static_cast<std::uint64_t>(cp.bonds.size()));
  for (std::size_t k = 0; k < cp.part_blocks.size(); ++k) {
    PartBlock p;
    p.index = cp.part_blocks[k];
    const BlockState& s = cp.blocks[k];
    for (int c = 0; c < 3; ++c) {
      p.state[c] = s.position[c];
      p.state[3 + c] = s.velocity[c];
      p.state[6 + c] = s.angular_velocity[c];
      p.state[9 + c] = s.angular_momentum[c];
    }
    for (int c = 0; c < 4; ++c) p.state[12 + c] = s.orientation.coeffs()[c];
    p.motion = static_cast<std::int64_t>(cp.motions[k]);
    cp.energy.block_record(static_cast<std::size_t>(p.index), p.energy);
    put(out, p);
  }
  for (const auto& [i, servo] : cp.servos) {
    put(out, static_cast<std::uint64_t>(i));
    put_bytes(out, &servo, sizeof(Servo));
  }
  for (const ContactHistory& h : cp.contacts) put_bytes(out, &h, sizeof(ContactHistory));
  for (const BondHistory& h : cp.bonds) put_bytes(out, &h, sizeof(BondHistory));
  const std::vector<double>& rest = cp.part_resting;
  const auto resting_count = static_cast<std::size_t>(rest.size() >= 2 ? rest[1] : 0.0);
  const std::size_t terms_at = 2 + resting_count;
  if (rest.size() < terms_at || (rest.size() - terms_at) % 12 != 0)
    throw std::logic_error("checkpoint gather: a malformed part");
  put(out, static_cast<std::uint64_t>((rest.size() - terms_at) / 12));
  put_bytes(out, rest.data() + terms_at, (rest.size() - terms_at) * sizeof(double));
  std::vector<std::size_t> counts;
  const std::vector<char> all = dist.all_gather(out, counts);

  // The whole checkpoint, as save_checkpoint takes it from the whole world that synchronize
  // makes: blocks by index, servos by index, contacts by (a, b), the other processes' energy
  // records set in process order.
  std::vector<BlockState> states(n);
  std::vector<Motion> motions(n, Motion::free);
  std::vector<char> seen(n, 0);
  std::vector<std::pair<std::size_t, Servo>> servos;
  std::vector<ContactHistory> contacts;
  std::vector<BondHistory> bonds;
  std::vector<std::array<double, 12>> terms;  // the resting blocks' contacts' terms
  std::size_t begin = 0;
  for (std::size_t r = 0; r < counts.size(); begin += counts[r], ++r) {
    const std::size_t end = begin + counts[r];
    if (counts[r] < 32)
      throw std::logic_error("checkpoint gather: a process sent a malformed part");
    const auto blocks_in = get<std::uint64_t>(all, begin);
    const auto servos_in = get<std::uint64_t>(all, begin + 8);
    const auto contacts_in = get<std::uint64_t>(all, begin + 16);
    const auto bonds_in = get<std::uint64_t>(all, begin + 24);
    const std::size_t fixed_part =
        32 + blocks_in * sizeof(PartBlock) + servos_in * (8 + sizeof(Servo)) +
        contacts_in * sizeof(ContactHistory) + bonds_in * sizeof(BondHistory);
    if (counts[r] < fixed_part + 8 ||
        counts[r] != fixed_part + 8 + get<std::uint64_t>(all, begin + fixed_part) * 96)
      throw std::logic_error("checkpoint gather: a process sent a malformed part");
    std::size_t at = begin + 32;
    for (std::uint64_t k = 0; k < blocks_in; ++k, at += sizeof(PartBlock)) {
      const auto p = get<PartBlock>(all, at);
      const auto i = static_cast<std::size_t>(p.index);
      if (p.index < 0 || i >= n || seen[i] != 0)
        throw std::logic_error("checkpoint gather: a process sent a malformed block");
      seen[i] = 1;
      BlockState& s = states[i];
      for (int c = 0; c < 3; ++c) {
        s.position[c] = p.state[c];
        s.velocity[c] = p.state[3 + c];
        s.angular_velocity[c] = p.state[6 + c];
        s.angular_momentum[c] = p.state[9 + c];
      }
      for (int c = 0; c < 4; ++c) s.orientation.coeffs()[c] = p.state[12 + c];
      motions[i] = static_cast<Motion>(p.motion);
      if (static_cast<int>(r) != rank) cp.energy.set_block_record(i, p.energy);
    }
    for (std::uint64_t k = 0; k < servos_in; ++k, at += 8 + sizeof(Servo)) {
      Servo servo;
      std::memcpy(static_cast<void*>(&servo), all.data() + at + 8, sizeof(Servo));
      servos.emplace_back(static_cast<std::size_t>(get<std::uint64_t>(all, at)), servo);
    }
    for (std::uint64_t k = 0; k < contacts_in; ++k, at += sizeof(ContactHistory)) {
      ContactHistory h;
      std::memcpy(static_cast<void*>(&h), all.data() + at, sizeof(ContactHistory));
      contacts.push_back(h);
    }
    for (std::uint64_t k = 0; k < bonds_in; ++k, at += sizeof(BondHistory))
      bonds.push_back(get<BondHistory>(all, at));
    const auto terms_in = get<std::uint64_t>(all, at);
    at += 8;
    for (std::uint64_t k = 0; k < terms_in; ++k, at += 96) {
      std::array<double, 12> t;
      std::memcpy(t.data(), all.data() + at, 96);
      terms.push_back(t);
    }
    if (at != end) throw std::logic_error("checkpoint gather: a process sent a malformed part");
  }
  if (std::count(seen.begin(), seen.end(), 0) != 0)
    throw std::logic_error("checkpoint gather: a block is in no process's part");
  std::sort(servos.begin(), servos.end(),
            [](const auto& x, const auto& y) { return x.first < y.first; });
  const auto by_pair = [](const auto& x, const auto& y) {
    return x.a < y.a || (x.a == y.a && x.b < y.b);
  };
  std::sort(contacts.begin(), contacts.end(), by_pair);
  std::sort(bonds.begin(), bonds.end(), by_pair);
  // The resting blocks' records as sum_resting_loads leaves them on the whole world of the
  // checkpoint's step: the contact force and torque summed with its arithmetic in (a, b) order.
  std::sort(terms.begin(), terms.end(), [](const auto& x, const auto& y) {
    return x[0] < y[0] || (x[0] == y[0] && x[1] < y[1]);
  });
  const double dt = rest.empty() ? 0.0 : rest[0];
  if (cp.step_count != 0) {
    std::vector<Eigen::Vector3d> force(n, Eigen::Vector3d::Zero()), torque(n, force[0]);
    std::vector<char> resting(n, 0);
    for (std::size_t k = 0; k < resting_count; ++k)
      resting[static_cast<std::size_t>(rest[2 + k])] = 1;
    for (const auto& t : terms) {
      const Eigen::Vector3d f(t[2], t[3], t[4]), xf(t[5], t[6], t[7]), normal(t[9], t[10], t[11]);
      for (const double ab : {t[0], t[1]}) {
        const auto k = static_cast<std::size_t>(ab);
        if (k >= n) throw std::logic_error("checkpoint gather: a malformed contact");
        if (resting[k] == 0) continue;
        const Eigen::Vector3d& position = states[k].position;
        if (ab == t[1]) {
          force[k] += f;
          torque[k] += (xf - position).cross(f);
          if (t[8] != 0.0) torque[k] += t[8] * normal;
        } else {
          force[k] -= f;
          torque[k] -= (xf - position).cross(f);
          if (t[8] != 0.0) torque[k] -= t[8] * normal;
        }
      }
    }
    double record[EnergyLedger::kBlockRecordDoubles];
    constexpr std::size_t kContact = 24;  // as sum_resting_loads
    for (std::size_t i = 0; i < n; ++i) {
      if (resting[i] == 0) continue;
      cp.energy.block_record(i, record);
      const Eigen::Vector3d impulse = dt * force[i];
      const Eigen::Vector3d angular = dt * torque[i];
      for (int k = 0; k < 3; ++k) {
        record[kContact + static_cast<std::size_t>(k)] = impulse[k];
        record[kContact + 3 + static_cast<std::size_t>(k)] = angular[k];
      }
      cp.energy.set_block_record(i, record);
    }
  }
  cp.blocks = std::move(states);
  cp.motions = std::move(motions);
  cp.servos = std::move(servos);
  cp.contacts = std::move(contacts);
  cp.bonds = std::move(bonds);
  std::vector<int>().swap(cp.part_blocks);
  std::vector<double>().swap(cp.part_resting);
  cp.partial = false;
  dist_stats_.checkpoint_gathers += 1;
  dist_stats_.checkpoint_bytes_sent += static_cast<std::int64_t>(out.size());
  dist_stats_.checkpoint_bytes_received += static_cast<std::int64_t>(all.size() - out.size());
  dist_stats_.replica_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void World::save_state_to_root(const std::function<void(std::string_view)>& emit) {
  // The divergence checkpoint's parts are gathered as synchronize() gathers them (into the
  // checkpoint's own per-block records, which every process keeps: no whole world).
  if (settings_.distribution) gather_checkpoint();
  const bool root = !settings_.distribution || settings_.distribution->rank() == 0;
  if (!settings_.distribution || replica_complete_) {
    if (!root) return;
    // Handed on in pieces as save_state writes them: the state (~5 KB per block in a settled
    // pile) is never held whole beside the world.
    StateWriter w(emit);
    save_state(w);
    w.flush();
    return;
  }
  // save_state's bytes as they would be after synchronize(), in its order, each section merged
  // to process 0 from the processes that keep it exact (docs/restart.md, "Under MPI"): the
  // blocks by index from their owners, the slots by (a, b) from the pairs' owners, the energy
  // records by index. What synchronize() re-derives is derived here alike: the resting blocks'
  // loads (sum_resting_loads), the index of the overlap violation in the whole slot list.
  PairDistribution& dist = *settings_.distribution;
  const int rank = dist.rank();
  const std::size_t n = blocks_.size();
  if (energy_.records() != n)
    throw std::logic_error("save_state_to_root: the energy ledger has another number of blocks");
  std::vector<std::size_t> mine;  // this process's blocks
  for (std::size_t i = 0; i < n; ++i)
    if (own_[i] != 0) mine.push_back(i);

  // The resting blocks' loads and stiffness sums, as sum_resting_loads sums them on a whole
  // world (every active slot in (a, b) order, its arithmetic), on every process: 11 values each.
  constexpr std::size_t kRest = 11;  // force, torque, contact force, stiffness, rotational
  std::vector<std::size_t> rest_at(n, n);
  std::vector<double> rest;
  if (resting_.size() == n) {
    for (std::size_t i = 0; i < n; ++i) {
      if (resting_[i] == 0) continue;
      rest_at[i] = rest.size() / kRest;
      rest.resize(rest.size() + kRest, 0.0);
    }
  }
  if (!rest.empty()) {
    std::vector<const PairSlot*> terms;
    for (const PairSlot& s : slots_) {
      if (s.active && (resting_[s.a] != 0 || resting_[s.b] != 0) && pair_owner(s) == rank)
        terms.push_back(&s);
    }
    struct Term {
      std::int32_t a, b;
      double f[3], xf[3], normal[3];
      double twist, spread, stiffness, twist_stiffness;
    };
    static_assert(std::is_trivially_copyable_v<Term>);
    merge_to_root(
        terms.size(),
        [&](std::size_t k) {
          return (static_cast<std::uint64_t>(terms[k]->a) << 32) |
                 static_cast<std::uint32_t>(terms[k]->b);
        },
        [&](std::size_t k, std::string& text) {
          const Contact& ct = contact_of(*terms[k]);
          const Eigen::Vector3d f = ct.force_on_b();
          Term t{ct.a,
                 ct.b,
                 {},
                 {},
                 {},
                 ct.couple_about_normal(),
                 ct.compressed_area() / 12.0,
                 ct.stiffness,
                 ct.twist_stiffness};
          for (int c = 0; c < 3; ++c) {
            t.f[c] = f[c];
            t.xf[c] = ct.force_point()[c];
            t.normal[c] = ct.geometry.normal[c];
          }
          text.append(reinterpret_cast<const char*>(&t), sizeof t);
        },
        [&](std::string_view text) {
          Term t;
          std::memcpy(static_cast<void*>(&t), text.data(), sizeof t);
          const Eigen::Vector3d f(t.f[0], t.f[1], t.f[2]), xf(t.xf[0], t.xf[1], t.xf[2]);
          const Eigen::Vector3d normal(t.normal[0], t.normal[1], t.normal[2]);
          for (const int i : {t.a, t.b}) {
            const std::size_t j = rest_at[static_cast<std::size_t>(i)];
            if (j == n) continue;
            double* r = rest.data() + j * kRest;
            Eigen::Map<Eigen::Vector3d> force(r), torque(r + 3), contact_force(r + 6);
            const Eigen::Vector3d& position = blocks_[static_cast<std::size_t>(i)].position;
            if (i == t.b) {
              force += f;
              contact_force += f;
              torque += (xf - position).cross(f);
              if (t.twist != 0.0) torque += t.twist * normal;
            } else {
              force -= f;
              contact_force -= f;
              torque -= (xf - position).cross(f);
              if (t.twist != 0.0) torque -= t.twist * normal;
            }
            r[9] += t.stiffness;
            r[10] += t.stiffness * ((xf - position).squaredNorm() + t.spread);
            r[10] += t.twist_stiffness;
          }
        });
    std::vector<char> bytes(rest.size() * sizeof(double));
    if (!bytes.empty()) std::memcpy(bytes.data(), rest.data(), bytes.size());
    dist.broadcast(bytes);
    if (bytes.size() != rest.size() * sizeof(double))
      throw std::logic_error("save_state_to_root: a malformed broadcast");
    if (!bytes.empty()) std::memcpy(rest.data(), bytes.data(), bytes.size());
  }
  const auto loads_of = [&](std::size_t i, Eigen::Vector3d* loads) -> const Eigen::Vector3d* {
    if (rest_at[i] == n) return nullptr;
    const double* r = rest.data() + rest_at[i] * kRest;
    for (int k = 0; k < 3; ++k) loads[k] = Eigen::Vector3d(r[3 * k], r[3 * k + 1], r[3 * k + 2]);
    return loads;
  };

  // Process 0's own bytes between the merges (which emit theirs as they come): flush() emits.
  StateWriter w;
  const auto flush = [&] {
    if (root && !w.bytes().empty())
      emit(std::string_view(reinterpret_cast<const char*>(w.bytes().data()), w.bytes().size()));
    w.bytes().clear();
  };
  w.vec(settings_.gravity);
  w.pod(settings_.damping);
  w.size(laws_.size());
  w.size(n);
  // The blocks, each with its stiffness sums (kept for the section after the blocks).
  std::vector<double> stiffness(root ? 2 * n : 0, 0.0);
  flush();
  merge_to_root(
      mine.size(), [&](std::size_t k) { return static_cast<std::uint64_t>(mine[k]); },
      [&](std::size_t k, std::string& text) {
        const std::size_t i = mine[k];
        Eigen::Vector3d loads[3];
        const double* r = rest_at[i] == n ? nullptr : rest.data() + rest_at[i] * kRest;
        const double head[3] = {
            static_cast<double>(i), r ? r[9] : (i < stiffness_.size() ? stiffness_[i] : 0.0),
            r ? r[10] : (i < rotational_stiffness_.size() ? rotational_stiffness_[i] : 0.0)};
        text.append(reinterpret_cast<const char*>(head), sizeof head);
        StateWriter b;
        save_block(b, i, loads_of(i, loads));
        text.append(reinterpret_cast<const char*>(b.bytes().data()), b.bytes().size());
      },
      [&](std::string_view text) {
        double head[3];
        std::memcpy(head, text.data(), sizeof head);
        const auto i = static_cast<std::size_t>(head[0]);
        stiffness[i] = head[1];
        stiffness[n + i] = head[2];
        emit(text.substr(sizeof head));
      });
  if (root) {
    w.size(n);
    for (std::size_t i = 0; i < n; ++i) w.pod(stiffness[i]);
    w.size(n);
    for (std::size_t i = 0; i < n; ++i) w.pod(stiffness[n + i]);
  }
  std::vector<double>().swap(stiffness);
  // The counters, with the overlap violation's index in the whole (a, b)-sorted slot list:
  // the owned slots before its pair, summed over the processes.
  std::vector<const PairSlot*> owned;
  for (const PairSlot& s : slots_)
    if (pair_owner(s) == rank) owned.push_back(&s);
  std::int64_t counts[3] = {static_cast<std::int64_t>(owned.size()), 0, 0};
  if (std::isfinite(overlap_key_)) {
    for (const PairSlot* s : owned) {
      const double key = static_cast<double>(s->a) * static_cast<double>(n) + s->b;
      counts[1] += key < overlap_key_ ? 1 : 0;
      counts[2] += key == overlap_key_ ? 1 : 0;
    }
  }
  reduce_partials({}, {}, counts);
  if (root) save_counters(w, counts[2] > 0 ? counts[1] : -1);
  const auto pair_key = [&](std::size_t k) {
    return (static_cast<std::uint64_t>(owned[k]->a) << 32) |
           static_cast<std::uint32_t>(owned[k]->b);
  };
  // The slots' pairs, then their records (a contact state where a force acts, as synchronize
  // keeps it: through its bytes).
  if (root) w.size(static_cast<std::size_t>(counts[0]));
  flush();
  merge_to_root(
      owned.size(), pair_key,
      [&](std::size_t k, std::string& text) {
        const std::int32_t ab[2] = {owned[k]->a, owned[k]->b};
        text.append(reinterpret_cast<const char*>(ab), sizeof ab);
      },
      emit);
  if (root) w.size(static_cast<std::size_t>(counts[0]));
  flush();
  merge_to_root(
      owned.size(), pair_key,
      [&](std::size_t k, std::string& text) {
        const PairSlot& s = *owned[k];
        StateWriter b;
        if (s.active) {
          char bytes[kContactBytes];
          contact_to_bytes(contact_of(s), bytes);
          const Contact c = contact_from_bytes(bytes);
          save_slot(b, s, &c);
        } else {
          save_slot(b, s, nullptr);
        }
        text.append(reinterpret_cast<const char*>(b.bytes().data()), b.bytes().size());
      },
      emit);
  if (root) save_divergence_checkpoint(w);
  flush();
  // The energy ledger (EnergyLedger::save_state's layout): the budget (every process's), each
  // block's record from its owner (a resting block's contact impulses from the sums above, as
  // sum_resting_loads sets them), the level velocities (kept for their two lists), the flag.
  const EnergyBudget& e = energy_.budget();
  if (root) {
    for (double v : {e.kinetic, e.elastic, e.gravity_work, e.load_work, e.boundary_work,
                     e.friction_dissipation, e.damping_dissipation, e.initial})
      w.pod(v);
    w.size(n);
  }
  constexpr std::size_t kRecord = EnergyLedger::kBlockRecordDoubles;
  constexpr std::size_t kLevel = kRecord - 6;  // the record's level velocities
  std::vector<double> level(root ? 6 * n : 0, 0.0);
  flush();
  merge_to_root(
      mine.size(), [&](std::size_t k) { return static_cast<std::uint64_t>(mine[k]); },
      [&](std::size_t k, std::string& text) {
        const std::size_t i = mine[k];
        double record[1 + kRecord];
        record[0] = static_cast<double>(i);
        energy_.block_record(i, record + 1);
        if (rest_at[i] != n && step_count_ != 0) {
          constexpr std::size_t kContact = 1 + 24;  // as sum_resting_loads
          const double* r = rest.data() + rest_at[i] * kRest;
          const Eigen::Vector3d impulse = last_dt_ * Eigen::Vector3d(r[6], r[7], r[8]);
          const Eigen::Vector3d angular = last_dt_ * Eigen::Vector3d(r[3], r[4], r[5]);
          for (int c = 0; c < 3; ++c) {
            record[kContact + static_cast<std::size_t>(c)] = impulse[c];
            record[kContact + 3 + static_cast<std::size_t>(c)] = angular[c];
          }
        }
        text.append(reinterpret_cast<const char*>(record), sizeof record);
      },
      [&](std::string_view text) {
        double record[1 + kRecord];
        std::memcpy(record, text.data(), sizeof record);
        const auto i = static_cast<std::size_t>(record[0]);
        emit(text.substr(sizeof(double), kLevel * sizeof(double)));
        for (std::size_t c = 0; c < 6; ++c) level[6 * i + c] = record[1 + kLevel + c];
      });
  if (!root) return;
  for (const std::size_t at : {std::size_t{0}, std::size_t{3}}) {
    w.size(n);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t c = 0; c < 3; ++c) w.pod(level[6 * i + at + c]);
  }
  w.pod(static_cast<std::uint8_t>(energy_.started()));
  flush();
}

void World::put_block_state(std::vector<char>& out, std::size_t i) const {
  static_assert(std::is_trivially_copyable_v<ReplicaBlock>);
  const Block& b = blocks_[i];
  ReplicaBlock r;
  r.state = ghost_of(b);
  for (int k = 0; k < 3; ++k) {
    r.force[k] = b.force[k];
    r.torque[k] = b.torque[k];
    r.contact_force[k] = b.contact_force[k];
  }
  r.stiffness = i < stiffness_.size() ? stiffness_[i] : 0.0;
  r.rotational_stiffness = i < rotational_stiffness_.size() ? rotational_stiffness_[i] : 0.0;
  energy_.block_record(i, r.energy);
  for (int k = 0; k < 3; ++k) {
    r.aabb_min[k] = box_min_[i][k];
    r.aabb_max[k] = box_max_[i][k];
  }
  r.planes = b.world_planes.size();
  put(out, r);
  for (const Halfspace& h : b.world_planes) {
    put3(out, h.normal);
    put(out, h.offset);
  }
}

std::size_t World::take_block_state(const std::vector<char>& in, std::size_t at, std::size_t end,
                                    bool apply, std::size_t& i) {
  // The receiver has sized stiffness_, rotational_stiffness_ and the energy records (prepare).
  if (at + sizeof(ReplicaBlock) > end)
    throw std::logic_error("block state: a process sent a malformed part");
  const auto rb = get<ReplicaBlock>(in, at);
  at += sizeof(ReplicaBlock);
  i = static_cast<std::size_t>(rb.state.index);
  if (rb.state.index < 0 || i >= blocks_.size() || rb.planes != blocks_[i].shape.planes().size() ||
      at + rb.planes * 32 > end)
    throw std::logic_error("block state: a process sent a malformed block");
  if (!apply) return at + rb.planes * 32;
  Block& b = blocks_[i];
  b.world_planes.resize(rb.planes);
  for (Halfspace& h : b.world_planes) {
    h.normal = get3(in, at);
    h.offset = get<double>(in, at + 24);
    at += 32;
  }
  for (int c = 0; c < 3; ++c) {
    box_min_[i][c] = rb.aabb_min[c];
    box_max_[i][c] = rb.aabb_max[c];
  }
  set_ghost(b, rb.state);
  for (int c = 0; c < 3; ++c) {
    b.force[c] = rb.force[c];
    b.torque[c] = rb.torque[c];
    b.contact_force[c] = rb.contact_force[c];
  }
  stiffness_[i] = rb.stiffness;
  rotational_stiffness_[i] = rb.rotational_stiffness;
  energy_.set_block_record(i, rb.energy);
  return at;
}

void World::synchronize() {
  // A divergence checkpoint in parts is made whole with the world (its readers, the reset to it
  // and the restart file, read a whole world).
  if (settings_.distribution) gather_checkpoint();
  if (!settings_.distribution || replica_complete_) return;
  // A slot travels as raw bytes (put_slot).
  static_assert(std::is_trivially_copyable_v<ReplicaBlock>);
  PairDistribution& dist = *settings_.distribution;
  const int rank = dist.rank();
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t n = blocks_.size();
  energy_.prepare(n);

  // This process's blocks, then the pairs it owns (the two counts first).
  std::vector<char> out;
  std::uint64_t own_count = 0, slot_count = 0;
  for (std::size_t i = 0; i < n; ++i) own_count += own_[i];
  for (const auto& s : slots_) slot_count += pair_owner(s) == rank ? 1 : 0;
  put(out, own_count);
  put(out, slot_count);
  for (std::size_t i = 0; i < n; ++i) {
    if (own_[i] != 0) put_block_state(out, i);
  }
  for (const auto& s : slots_) {
    if (pair_owner(s) != rank) continue;
    put_slot(out, s, s.active ? &contact_of(s) : nullptr);
  }
  std::vector<std::size_t> counts;
  std::vector<char> all = dist.all_gather(out, counts);
  // The refresh is the peak of a distributed run's memory (docs/scaling.md, "Memory"): this
  // process's part is freed at once, the slots are reserved exactly, and the contact states are
  // read from the gathered bytes in place (by offset) and copied once, into the new store.
  const std::size_t out_bytes = out.size(), all_bytes = all.size();
  std::vector<char>().swap(out);

  // Every process's blocks into place, every owned slot into one list sorted by (a, b).
  stiffness_.resize(n, 0.0);
  rotational_stiffness_.resize(n, 0.0);
  std::vector<PairSlot> slots;
  std::vector<std::size_t> states;  // the received slots' contact states (offsets in `all`)
  std::size_t begin = 0;
  for (std::size_t r = 0, total = 0; r < counts.size(); begin += counts[r], ++r) {
    if (counts[r] < 16) throw std::logic_error("replica refresh: a process sent a malformed part");
    total += get<std::uint64_t>(all, begin + 8);
    if (r + 1 == counts.size()) slots.reserve(total);
  }
  begin = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    const auto blocks_in = get<std::uint64_t>(all, begin);
    const auto slots_in = get<std::uint64_t>(all, begin + 8);
    std::size_t at = begin + 16;
    for (std::uint64_t k = 0; k < blocks_in; ++k) {
      std::size_t i = 0;
      at = take_block_state(all, at, begin + counts[r], static_cast<int>(r) != rank, i);
    }
    for (std::uint64_t k = 0; k < slots_in; ++k) {
      PairSlot s;
      Contact c;
      if (!get_slot(all, at, begin + counts[r], s, c))
        throw std::logic_error("replica refresh: a process sent a malformed part");
      s.contact = -1;
      if (s.active) {
        s.contact = static_cast<std::int32_t>(states.size());
        states.push_back(at - kContactBytes);
      }
      slots.push_back(s);
    }
    if (at != begin + counts[r])
      throw std::logic_error("replica refresh: a process sent a malformed part");
    begin += counts[r];
  }
  std::sort(slots.begin(), slots.end(), [](const PairSlot& x, const PairSlot& y) {
    return x.a < y.a || (x.a == y.a && x.b < y.b);
  });
  slots_ = std::move(slots);
  contacts_.clear();
  contacts_.reserve(states.size());
  for (PairSlot& s : slots_) {
    if (s.contact < 0) continue;
    contacts_.push_back(
        contact_from_bytes(all.data() + states[static_cast<std::size_t>(s.contact)]));
    s.contact = static_cast<std::int32_t>(contacts_.size() - 1);
  }
  std::vector<char>().swap(all);
  sum_resting_loads();
  // The candidate list as one process leaves it after a step: the pairs of the slots, in order
  // (this process found only its own blocks' pairs; a checkpoint saves the list).
  pairs_.resize(slots_.size());
  for (std::size_t k = 0; k < slots_.size(); ++k) pairs_[k] = {slots_[k].a, slots_[k].b};
  overlap_violation_ = slot_of_key(slots_, n, overlap_key_, [](const PairSlot&) { return true; });
  local_.assign(n, 1);
  ghosts_listed_ = false;
  replica_complete_ = true;
  dist_stats_.replica_refreshes += 1;
  dist_stats_.replica_bytes_sent += static_cast<std::int64_t>(out_bytes);
  dist_stats_.replica_bytes_received += static_cast<std::int64_t>(all_bytes - out_bytes);
  dist_stats_.replica_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void World::exchange_ghosts() {
  // After integration: each process's own blocks to every process whose subdomain box (the union
  // of its blocks' boxes) their box touches, and to the owners of their pairs' other blocks (an
  // open bond keeps a pair whose boxes have parted; listed by the step in pair_sends_). A
  // process then holds, exactly, every block whose box can touch one of its own: its next broad
  // phase and pair work need no other. The walks cover the moving own blocks and the received
  // ghosts only, in buffers kept between steps.
  PairDistribution& dist = *settings_.distribution;
  const int rank = dist.rank();
  const auto k = static_cast<std::size_t>(dist.size());
  const std::size_t n = blocks_.size();
  // The own blocks' boxes at their new poses (as the next step's geometry pass computes them;
  // the blocks keep this step's planes and boxes, as in one process). A process's subdomain is
  // published as the union of its movable blocks' boxes plus the box of each fixed block that is
  // not resting, so that a base plate under the whole model does not make the union the whole
  // model. A resting block is exact on every process: it is neither sent nor needs ghosts.
  const double inf = std::numeric_limits<double>::infinity();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(inf), hi = Eigen::Vector3d::Constant(-inf);
  const std::size_t moving = moving_list_.size();
  next_min_.assign(moving, lo);
  next_max_.assign(moving, hi);
  std::vector<char> box;
  for (std::size_t m = 0; m < moving; ++m) {
    const Block& b = blocks_[static_cast<std::size_t>(moving_list_[m])];
    const Eigen::Matrix3d rot = b.rotation();
    for (const auto& v : b.shape.vertices()) {
      const Eigen::Vector3d w = b.position + rot * v;
      next_min_[m] = next_min_[m].cwiseMin(w);
      next_max_[m] = next_max_[m].cwiseMax(w);
    }
    if (b.motion == Motion::fixed) {
      put3(box, next_min_[m]);
      put3(box, next_max_[m]);
    } else {
      lo = lo.cwiseMin(next_min_[m]);
      hi = hi.cwiseMax(next_max_[m]);
    }
  }
  put3(box, lo);
  put3(box, hi);
  std::vector<std::size_t> counts;
  const std::vector<char> boxes = dist.all_gather(box, counts);
  std::vector<std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>> subdomain(k);
  std::size_t begin = 0;
  for (std::size_t r = 0; r < k; ++r) {
    for (std::size_t at = begin; at + 48 <= begin + counts[r]; at += 48)
      subdomain[r].emplace_back(get3(boxes, at), get3(boxes, at + 24));
    begin += counts[r];
  }
  // (own block, destination) pairs: by the boxes, then the other owners of its pairs; each
  // message lists its blocks in index order.
  std::vector<std::pair<std::int64_t, int>>& sends = ghost_sends_;
  sends.clear();
  for (std::size_t m = 0; m < moving; ++m) {
    for (std::size_t r = 0; r < k; ++r) {
      if (static_cast<int>(r) == rank) continue;
      for (const auto& [box_lo, box_hi] : subdomain[r]) {
        if (boxes_overlap(next_min_[m], next_max_[m], box_lo, box_hi)) {
          sends.emplace_back(static_cast<std::int64_t>(moving_list_[m]), static_cast<int>(r));
          break;
        }
      }
    }
  }
  sends.insert(sends.end(), pair_sends_.begin(), pair_sends_.end());
  std::sort(sends.begin(), sends.end());
  sends.erase(std::unique(sends.begin(), sends.end()), sends.end());
  std::vector<std::vector<char>> to(k);
  for (const auto& [i, r] : sends)
    put(to[static_cast<std::size_t>(r)], ghost_of(blocks_[static_cast<std::size_t>(i)]));
  const std::vector<std::vector<char>> from = dist.exchange(to);
  // The last step's ghosts are exact here no more (every block, after a refresh).
  if (ghosts_listed_) {
    for (const int g : ghosts_) local_[static_cast<std::size_t>(g)] = 0;
  } else {
    for (std::size_t i = 0; i < n; ++i) local_[i] = own_[i] != 0 || resting_[i] != 0 ? 1 : 0;
  }
  ghosts_.clear();
  for (std::size_t r = 0; r < k; ++r) {
    if (from[r].size() % sizeof(GhostState) != 0)
      throw std::logic_error("ghost exchange: a process sent a malformed part");
    for (std::size_t at = 0; at < from[r].size(); at += sizeof(GhostState)) {
      const auto g = get<GhostState>(from[r], at);
      const auto i = static_cast<std::size_t>(g.index);
      if (i >= n || owner_[i] != static_cast<int>(r))
        throw std::logic_error("ghost exchange: a block came from a process that does not own it");
      set_ghost(blocks_[i], g);
      local_[i] = 1;
      ghosts_.push_back(static_cast<int>(i));
    }
    dist_stats_.bytes_received += static_cast<std::int64_t>(from[r].size());
  }
  // Each process's list is in index order, and the processes own disjoint blocks.
  std::sort(ghosts_.begin(), ghosts_.end());
  ghosts_listed_ = true;
  for (std::size_t r = 0; r < k; ++r)
    dist_stats_.bytes_sent += static_cast<std::int64_t>(to[r].size());
  dist_stats_.bytes_sent += static_cast<std::int64_t>(box.size());
  dist_stats_.bytes_received += static_cast<std::int64_t>(boxes.size() - box.size());
}

void World::begin_distributed_step(StepScratch& s) {
  drop_primed();  // the distributed step solves its own pairs
  const std::size_t n = blocks_.size();
  if (owner_.size() != n) {
    synchronize();
    partition_blocks();
  }
  if (replica_complete_) {
    local_.assign(n, 1);
    ghosts_listed_ = false;
    mark_resting();
  }
  // The exact blocks: the kept ones and the last exchange's ghosts (disjoint lists), or after a
  // refresh every block local_ marks.
  if (ghosts_listed_) {
    s.held.resize(kept_list_.size() + ghosts_.size());
    std::merge(kept_list_.begin(), kept_list_.end(), ghosts_.begin(), ghosts_.end(),
               s.held.begin());
  } else {
    s.held.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
      if (local_[i] != 0) s.held.push_back(static_cast<int>(i));
  }
}

void World::select_own_pairs(StepScratch& s) {
  const int rank = settings_.distribution->rank();
  const auto owner_of = [&](const PairSlot& c) {
    return pair_owner_process(owner_, c.a, s.moves[static_cast<std::size_t>(c.a)] != 0, c.b,
                              s.moves[static_cast<std::size_t>(c.b)] != 0);
  };
  // The same walk lists the (own block, process) pairs that the ghost exchange sends for the
  // slots: an own block to the owner of its pair's other block (an open bond keeps a pair whose
  // boxes have parted), neither block resting.
  std::vector<int> ghost;  // the other processes' blocks in this process's pairs
  s.mine.clear();
  s.is_mine.assign(slots_.size(), 0);
  pair_sends_.clear();
  for (std::size_t k = 0; k < slots_.size(); ++k) {
    const PairSlot& c = slots_[k];
    const int ca = c.a, cb = c.b;
    if ((own_[ca] == 0 || own_[cb] == 0) && resting_[ca] == 0 && resting_[cb] == 0) {
      if (own_[ca] != 0 && owner_[cb] != rank) pair_sends_.emplace_back(ca, owner_[cb]);
      if (own_[cb] != 0 && owner_[ca] != rank) pair_sends_.emplace_back(cb, owner_[ca]);
    }
    if (owner_of(c) != rank) continue;
    s.mine.push_back(static_cast<std::int64_t>(k));
    s.is_mine[k] = 1;
    if (own_[ca] == 0) ghost.push_back(ca);
    if (own_[cb] == 0) ghost.push_back(cb);
  }
  std::sort(ghost.begin(), ghost.end());
  dist_stats_.ghost_blocks += std::unique(ghost.begin(), ghost.end()) - ghost.begin();
}

void World::exchange_evaluated_slots(StepScratch& s, const std::exception_ptr& error) {
  PairDistribution& dist = *settings_.distribution;
  const int rank = dist.rank();
  const auto k_ranks = static_cast<std::size_t>(dist.size());
  using Clock = std::chrono::steady_clock;
  const auto seconds_since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };
  // Every process's figures (pair time and count, failure): all decide alike on failures and
  // on rebalancing.
  StepHeader header;
  header.seconds = s.pair_seconds;
  header.slots = static_cast<std::uint64_t>(s.mine.size());
  // A refused value (std::invalid_argument of a law or the narrow phase) and its message.
  std::string refused;
  if (error) {
    try {
      std::rethrow_exception(error);
    } catch (const std::invalid_argument& e) {
      refused = e.what();
    } catch (...) {
    }
  }
  header.failed = !error ? 0 : !refused.empty() ? 1 : 2;
  std::vector<char> head;
  put(head, header);
  std::vector<std::size_t> counts;
  auto tw = Clock::now();
  const std::vector<char> heads = dist.all_gather(head, counts);
  s.waiting += seconds_since(tw);
  for (std::size_t r = 0; r < k_ranks; ++r) {
    const auto h = get<StepHeader>(heads, r * sizeof(StepHeader));
    if (h.failed == 1) {
      // A value refused on process r (the first in process order): its message to every
      // process, the whole world on every process, and the one-process reset and StepFailure.
      settle_contacts();
      std::vector<std::size_t> sizes;
      const std::vector<char> texts =
          dist.all_gather(std::vector<char>(refused.begin(), refused.end()), sizes);
      std::size_t at = 0;
      for (std::size_t q = 0; q < r; ++q) at += sizes[q];
      const std::string why(texts.begin() + static_cast<std::ptrdiff_t>(at),
                            texts.begin() + static_cast<std::ptrdiff_t>(at + sizes[r]));
      synchronize();
      fail_step(why);
    }
    if (h.failed != 0) {
      settle_contacts();
      if (error) std::rethrow_exception(error);
      throw std::runtime_error("contact evaluation failed on process " + std::to_string(r));
    }
    s.slowest = std::max(s.slowest, h.seconds);
    s.total += h.seconds;
    s.most_pairs = std::max(s.most_pairs, static_cast<double>(h.slots));
    s.total_pairs += static_cast<double>(h.slots);
  }

  // Each evaluated slot to the owner of the pair's other block, byte for byte (not to a resting
  // block's owner: its loads wait for the whole world, sum_resting_loads).
  // A slot that formed a contact this step finds its state in its run's list.
  const auto state_of = [&](std::size_t k) -> const Contact* {
    const PairSlot& slot = slots_[k];
    if (!slot.active) return nullptr;
    if (!slot.pending) return &contact_of(slot);
    const std::vector<PendingContact>& list = pending_[k / pending_run_];
    const auto it =
        std::lower_bound(list.begin(), list.end(), k,
                         [](const PendingContact& p, std::size_t at) { return p.slot < at; });
    if (it == list.end() || it->slot != k)
      throw std::logic_error("pair exchange: a new contact state is missing");
    return &it->contact;
  };
  std::vector<std::vector<char>> to(k_ranks);
  for (std::int64_t i : s.mine) {
    const PairSlot& slot = slots_[static_cast<std::size_t>(i)];
    for (int block : {slot.a, slot.b}) {
      const int r = owner_[static_cast<std::size_t>(block)];
      if (r == rank || resting_[static_cast<std::size_t>(block)] != 0) continue;
      put_slot(to[static_cast<std::size_t>(r)], slot, state_of(static_cast<std::size_t>(i)));
    }
  }
  tw = Clock::now();
  const std::vector<std::vector<char>> from = dist.exchange(to);
  s.waiting += seconds_since(tw);
  // The received slots replace this process's (none of its own pairs); their contact states
  // join the new ones in pending_, each run's list then put back in slot order.
  if (pending_.size() != (slots_.size() + pending_run_ - 1) / pending_run_)
    throw std::logic_error("pair exchange: the new contact states are not the slots'");
  std::vector<char> joined(pending_.size(), 0);
  for (std::size_t r = 0; r < k_ranks; ++r) {
    std::size_t at = 0;
    while (at < from[r].size()) {
      PairSlot received;
      Contact state;
      if (!get_slot(from[r], at, from[r].size(), received, state))
        throw std::logic_error("pair exchange: a process sent a malformed part");
      const int ab[2] = {received.a, received.b};
      const auto it =
          std::lower_bound(slots_.begin(), slots_.end(), std::pair<int, int>(ab[0], ab[1]),
                           [](const PairSlot& x, const std::pair<int, int>& key) {
                             return x.a < key.first || (x.a == key.first && x.b < key.second);
                           });
      if (it == slots_.end() || it->a != ab[0] || it->b != ab[1])
        throw std::logic_error("pair exchange: a process sent a pair this one does not have");
      received.contact = it->contact;  // this process's old state, dropped by the settle
      received.pending = received.active;
      *it = received;
      if (received.active) {
        const auto k = static_cast<std::size_t>(it - slots_.begin());
        pending_[k / pending_run_].push_back({k, state});
        joined[k / pending_run_] = 1;
      }
    }
    dist_stats_.bytes_sent += static_cast<std::int64_t>(to[r].size());
    dist_stats_.bytes_received += static_cast<std::int64_t>(from[r].size());
  }
  for (std::size_t r = 0; r < pending_.size(); ++r) {
    if (joined[r] == 0) continue;
    std::sort(pending_[r].begin(), pending_[r].end(),
              [](const PendingContact& x, const PendingContact& y) { return x.slot < y.slot; });
  }
  settle_contacts();
  dist_stats_.bytes_sent += static_cast<std::int64_t>(head.size());
  dist_stats_.bytes_received += static_cast<std::int64_t>(heads.size() - head.size());
}

bool World::reduce_step_checks(StepScratch& s) {
  PairDistribution& dist = *settings_.distribution;
  // Ghosts for the next step, then the global checks: exact reductions (minima of indices and
  // time steps, integer sums).
  const auto tw = std::chrono::steady_clock::now();
  exchange_ghosts();
  double first_bad = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < own_list_.size() && std::isinf(first_bad); ++k) {
    const auto i = static_cast<std::size_t>(own_list_[k]);
    const Block& b = blocks_[i];
    if (!b.position.allFinite() || !b.velocity.allFinite() || !b.angular_velocity.allFinite() ||
        !b.orientation.coeffs().allFinite() || b.velocity.norm() > settings_.max_speed)
      first_bad = static_cast<double>(i);
  }
  const std::vector<double> minima = dist.min({s.dt_min, s.overlap_key, first_bad});
  const std::vector<std::int64_t> sums = dist.sum({s.active, s.broke});
  s.waiting += std::chrono::duration<double>(std::chrono::steady_clock::now() - tw).count();
  contact_dt_ = std::isfinite(minima[0]) ? settings_.safety_factor * minima[0] : 0.0;
  overlap_key_ = minima[1];
  active_count_ = static_cast<std::size_t>(sums[0]);
  broken_bonds_ = s.broken_before + sums[1];
  replica_complete_ = false;
  dist_stats_.steps += 1;
  dist_stats_.owned_pairs += static_cast<std::int64_t>(s.mine.size());
  dist_stats_.pair_seconds += s.pair_seconds;
  dist_stats_.exchange_seconds += s.waiting;
  return std::isfinite(minima[1]) || std::isfinite(minima[2]);
}

void World::end_distributed_step(StepScratch& s) {
  // Rebalancing: every process sees the same measured figures, so all decide alike. The answers
  // do not depend on the partition, only the speed does.
  PairDistribution& dist = *settings_.distribution;
  const auto k_ranks = static_cast<double>(dist.size());
  const double mean = s.total / k_ranks;
  dist_stats_.last_imbalance = mean > 0.0 ? s.slowest / mean : 1.0;
  const std::int64_t since = step_count_ - partition_step_;
  const std::int64_t every = dist.repartition_interval();
  const double mean_pairs = s.total_pairs / k_ranks;
  const bool uneven_pairs = s.most_pairs > kPairCountThreshold * mean_pairs;
  if ((dist_stats_.last_imbalance > kImbalanceThreshold &&
       s.slowest - mean > kMinImbalanceSeconds && uneven_pairs &&
       since >= kMinStepsBetweenPartitions) ||
      (every > 0 && since >= every)) {
    if (deferred_replica_ && !replica_complete_) {
      migrate_blocks();  // point to point: no whole world
    } else {
      synchronize();  // made whole anyway at the step's end
      partition_blocks();
    }
  }
  if (!deferred_replica_) {
    synchronize();
  } else if (!replica_complete_) {
    release_spare_room();
  }
}

namespace {

// Whether a store keeps much more room than it uses (a quarter more, and at least 256 entries
// more): after the world was whole, a process's stores hold only its part of it.
template <class T>
bool release_spare(std::vector<T>& store) {
  if (store.capacity() - store.size() <= store.size() / 4 + 256) return false;
  store.shrink_to_fit();
  return true;
}

}  // namespace

void World::release_spare_room() {
  bool released = release_spare(slots_);
  released = release_spare(contacts_) || released;
  released = release_spare(pairs_) || released;
#if defined(__GLIBC__)
  // The C library keeps freed blocks of the heap for later allocations; the stores just shrunk
  // are most of what a process holds, so give their pages back to the system now (rare: after
  // the world was whole).
  if (released) malloc_trim(0);
#endif
}

}  // namespace blockdem
