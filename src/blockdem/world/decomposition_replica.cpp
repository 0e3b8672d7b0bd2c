// A distributed world made whole, or written whole without being made so: the divergence
// checkpoint in parts and its gather, the restart file merged to process 0, a block's whole state
// as bytes, and the replica refresh (every block and pair slot to every process).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "blockdem/world/bolt_state.hpp"
#include "blockdem/world/decomposition.hpp"
#include "blockdem/world/decomposition_wire.hpp"
#include "blockdem/world/pair_owner.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

using namespace decomposition_wire;

namespace {

/// Bytes of a block of a divergence checkpoint's part (part_block_record).
constexpr std::size_t kPartBlockBytes =
    2 * sizeof(std::int64_t) + kMotionRecordBytes + EnergyLedger::kBlockRecordDoubles * 8;

/// A block of a divergence checkpoint's part: its index, motion state (motion_record, as the
/// restart file and a ghost send it), motion and energy record.
template <class Ar, class S, class M>
void part_block_record(Ar& ar, std::int64_t& index, S& state, M& motion,
                       double (&energy)[EnergyLedger::kBlockRecordDoubles]) {
  ar(index);
  motion_record(ar, state);
  ar.template as<std::int64_t>(motion);
  for (double& e : energy) ar(e);
}

}  // namespace

void Decomposition::save_checkpoint_part(World& world) {
  // What save_checkpoint takes from a whole world, taken from this process's exact part: its
  // blocks (own_) and the pairs it owns, each by the same rule (bench/scaling-log.md, "The
  // divergence checkpoint in parts"). Every process saves at the same step, so the parts are alike
  // in kind everywhere.
  const int rank = world.settings_.distribution->rank();
  const std::size_t n = world.blocks_.size();
  std::vector<int> part;
  for (std::size_t i = 0; i < n; ++i)
    if (own_[i] != 0) part.push_back(static_cast<int>(i));
  std::vector<World::BlockState> states;
  std::vector<Motion> motions;
  states.reserve(part.size());
  motions.reserve(part.size());
  world.checkpoint_.servos.clear();
  for (const int i : part) {
    const Block& b = world.blocks_[static_cast<std::size_t>(i)];
    states.push_back(
        {b.position, b.velocity, b.angular_velocity, b.angular_momentum, b.orientation});
    motions.push_back(b.motion);
    if (!same_bits(b.servo(), Servo{}))
      world.checkpoint_.servos.emplace_back(static_cast<std::size_t>(i), b.servo());
  }
  world.checkpoint_.blocks = std::move(states);
  world.checkpoint_.motions = std::move(motions);
  world.checkpoint_.part_blocks = std::move(part);
  // The slots save_checkpoint keeps, of the pairs this process owns, in (a, b) order.
  std::vector<World::ContactHistory> contacts;
  std::vector<World::BondHistory> bonds;
  for (const auto& s : world.slots_)
    if (pair_owner(world, s.a, s.b) == rank) world.keep_slot(s, contacts, bonds);
  world.checkpoint_.contacts = std::move(contacts);
  world.checkpoint_.bonds = std::move(bonds);
  // A resting block's energy record holds the step's contact impulses, which a refresh sums
  // from every process's contacts (sum_resting_loads): the terms of this process's contacts on
  // resting blocks, in (a, b) order, summed when the parts are gathered. First (kept here, alike
  // everywhere) the step and the resting blocks, then 12 values per contact.
  std::vector<double> rest{world.last_dt_, 0.0};
  if (resting_.size() == n) {
    for (std::size_t i = 0; i < n; ++i)
      if (resting_[i] != 0) rest.push_back(static_cast<double>(i));
    rest[1] = static_cast<double>(rest.size() - 2);
    for (const auto& s : world.slots_) {
      if (!s.active || pair_owner(world, s.a, s.b) != rank) continue;
      if (resting_[static_cast<std::size_t>(s.a)] == 0 &&
          resting_[static_cast<std::size_t>(s.b)] == 0)
        continue;
      const Contact& ct = world.contact_of(s);
      const Eigen::Vector3d xf = ct.force_point(), f = ct.force_on_b();
      rest.insert(rest.end(),
                  {static_cast<double>(ct.a), static_cast<double>(ct.b), f[0], f[1], f[2], xf[0],
                   xf[1], xf[2], ct.couple_about_normal(), ct.geometry.normal[0],
                   ct.geometry.normal[1], ct.geometry.normal[2]});
    }
  }
  world.checkpoint_.part_resting = std::move(rest);
  world.checkpoint_.time = world.time_;
  world.checkpoint_.step_count = world.step_count_;
  world.checkpoint_.broken_bonds = world.broken_bonds_;
  world.checkpoint_.broken_by_set = world.broken_by_set_;
  // The whole ledger: its budget is every process's; of its per-block records only the own
  // blocks' are exact, the others are set when the parts are gathered (as synchronize sets them).
  world.checkpoint_.energy = world.energy_;
  world.checkpoint_.valid = true;
  world.checkpoint_.partial = true;
  world.checkpoint_.file.reset();  // a part is kept in memory
}

std::vector<char> Decomposition::checkpoint_part(World& world) {
  const World::Checkpoint& cp = world.checkpoint_;
  std::vector<char> out;
  put(out, static_cast<std::uint64_t>(cp.part_blocks.size()));
  put(out, static_cast<std::uint64_t>(cp.servos.size()));
  put(out, static_cast<std::uint64_t>(cp.contacts.size()));
  put(out, static_cast<std::uint64_t>(cp.bonds.size()));
  WireWriter w(out);
  SaveArchive ar(w);
  for (std::size_t k = 0; k < cp.part_blocks.size(); ++k) {
    std::int64_t index = cp.part_blocks[k];
    double energy[EnergyLedger::kBlockRecordDoubles];
    world.checkpoint_.energy.block_record(static_cast<std::size_t>(index), energy);
    part_block_record(ar, index, cp.blocks[k], cp.motions[k], energy);
  }
  for (const auto& [i, servo] : cp.servos) {
    put(out, static_cast<std::uint64_t>(i));
    put_bytes(out, &servo, sizeof(Servo));
  }
  for (const World::ContactHistory& h : cp.contacts)
    put_bytes(out, &h, sizeof(World::ContactHistory));
  for (const World::BondHistory& h : cp.bonds) put_bytes(out, &h, sizeof(World::BondHistory));
  const std::vector<double>& rest = cp.part_resting;
  const auto resting_count = static_cast<std::size_t>(rest.size() >= 2 ? rest[1] : 0.0);
  const std::size_t terms_at = 2 + resting_count;
  if (rest.size() < terms_at || (rest.size() - terms_at) % 12 != 0)
    throw std::logic_error("checkpoint gather: a malformed part");
  put(out, static_cast<std::uint64_t>((rest.size() - terms_at) / 12));
  put_bytes(out, rest.data() + terms_at, (rest.size() - terms_at) * sizeof(double));
  return out;
}

void Decomposition::gather_checkpoint(World& world) {
  if (!world.checkpoint_.partial) return;
  static_assert(std::is_trivially_destructible_v<World::ContactHistory>);
  static_assert(std::is_trivially_copyable_v<World::BondHistory>);
  PairDistribution& dist = *world.settings_.distribution;
  const int rank = dist.rank();
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t n = world.blocks_.size();
  World::Checkpoint& cp = world.checkpoint_;
  cp.energy.prepare(n);
  // This process's part: its blocks (index, state, motion, energy record), servos and contacts.
  const std::vector<char> out = checkpoint_part(world);
  const std::vector<double>& rest = cp.part_resting;
  const auto resting_count = static_cast<std::size_t>(rest.size() >= 2 ? rest[1] : 0.0);
  std::vector<std::size_t> counts;
  const std::vector<char> all = dist.all_gather(out, counts);

  // The whole checkpoint, as save_checkpoint takes it from the whole world that synchronize
  // makes: blocks by index, servos by index, contacts by (a, b), the other processes' energy
  // records set in process order.
  std::vector<World::BlockState> states(n);
  std::vector<Motion> motions(n, Motion::free);
  std::vector<char> seen(n, 0);
  std::vector<std::pair<std::size_t, Servo>> servos;
  std::vector<World::ContactHistory> contacts;
  std::vector<World::BondHistory> bonds;
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
        32 + blocks_in * kPartBlockBytes + servos_in * (8 + sizeof(Servo)) +
        contacts_in * sizeof(World::ContactHistory) + bonds_in * sizeof(World::BondHistory);
    if (counts[r] < fixed_part + 8 ||
        counts[r] != fixed_part + 8 + get<std::uint64_t>(all, begin + fixed_part) * 96)
      throw std::logic_error("checkpoint gather: a process sent a malformed part");
    std::size_t at = begin + 32;
    WireReader in(all, at, end, "checkpoint gather");
    LoadArchive ar(in);
    for (std::uint64_t k = 0; k < blocks_in; ++k) {
      std::int64_t index = 0;
      World::BlockState s;
      Motion motion = Motion::free;
      double energy[EnergyLedger::kBlockRecordDoubles];
      part_block_record(ar, index, s, motion, energy);
      const auto i = static_cast<std::size_t>(index);
      if (index < 0 || i >= n || seen[i] != 0)
        throw std::logic_error("checkpoint gather: a process sent a malformed block");
      seen[i] = 1;
      states[i] = s;
      motions[i] = motion;
      if (static_cast<int>(r) != rank) cp.energy.set_block_record(i, energy);
    }
    for (std::uint64_t k = 0; k < servos_in; ++k, at += 8 + sizeof(Servo)) {
      Servo servo;
      std::memcpy(static_cast<void*>(&servo), all.data() + at + 8, sizeof(Servo));
      servos.emplace_back(static_cast<std::size_t>(get<std::uint64_t>(all, at)), servo);
    }
    for (std::uint64_t k = 0; k < contacts_in; ++k, at += sizeof(World::ContactHistory)) {
      World::ContactHistory h;
      std::memcpy(static_cast<void*>(&h), all.data() + at, sizeof(World::ContactHistory));
      contacts.push_back(h);
    }
    for (std::uint64_t k = 0; k < bonds_in; ++k, at += sizeof(World::BondHistory))
      bonds.push_back(get<World::BondHistory>(all, at));
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
  cp.blocks = std::move(states);
  cp.motions = std::move(motions);
  cp.servos = std::move(servos);
  cp.contacts = std::move(contacts);
  cp.bonds = std::move(bonds);
  sum_checkpoint_resting(world, terms, resting_count);
  std::vector<int>().swap(cp.part_blocks);
  std::vector<double>().swap(cp.part_resting);
  cp.partial = false;
  dist_stats_.checkpoint_gathers += 1;
  dist_stats_.checkpoint_bytes_sent += static_cast<std::int64_t>(out.size());
  dist_stats_.checkpoint_bytes_received += static_cast<std::int64_t>(all.size() - out.size());
  dist_stats_.replica_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void Decomposition::sum_checkpoint_resting(World& world, std::vector<std::array<double, 12>>& terms,
                                           std::size_t resting_count) {
  World::Checkpoint& cp = world.checkpoint_;
  const std::vector<double>& rest = cp.part_resting;
  const std::size_t n = world.blocks_.size();
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
        const Eigen::Vector3d& position = cp.blocks[k].position;
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
}

/// save_state_to_root's stream: process 0's own bytes between the merges (which emit theirs as
/// they come); flush() hands them on.
struct Decomposition::RootStream {
  const std::function<void(std::string_view)>& emit;
  bool root = false;
  StateWriter w;
  void flush() {
    if (root && !w.bytes().empty())
      emit(std::string_view(reinterpret_cast<const char*>(w.bytes().data()), w.bytes().size()));
    w.bytes().clear();
  }
};

void Decomposition::save_state_to_root(World& world,
                                       const std::function<void(std::string_view)>& emit) {
  // The divergence checkpoint's parts are gathered as synchronize() gathers them (into
  // the checkpoint's own per-block records, which every process keeps: no whole world).
  if (world.settings_.distribution) gather_checkpoint(world);
  const bool root = !world.settings_.distribution || world.settings_.distribution->rank() == 0;
  if (!world.settings_.distribution || replica_complete_) {
    if (!root) return;
    // Handed on in pieces as save_state writes them: the state (~5 KB per block in a settled
    // pile) is never held whole beside the world.
    StateWriter w(emit);
    world.save_state(w);
    w.flush();
    return;
  }
  // save_state's bytes as they would be after synchronize(), in its order, each section
  // merged to process 0 from the processes that keep it exact (docs/restart.md, "Under MPI"): the
  // blocks by index from their owners, the slots by (a, b) from the pairs' owners, the energy
  // records by index. What synchronize() re-derives is derived here alike: the resting
  // blocks' loads (sum_resting_loads), the index of the overlap violation in the whole slot list.
  const std::size_t n = world.blocks_.size();
  if (world.energy_.records() != n)
    throw std::logic_error("save_state_to_root: the energy ledger has another number of blocks");
  std::vector<std::size_t> mine;  // this process's blocks
  for (std::size_t i = 0; i < n; ++i)
    if (own_[i] != 0) mine.push_back(i);

  const RestingTerms rest = resting_terms(world);
  // Process 0's own bytes between the merges (which emit theirs as they come): flush() emits.
  RootStream out{emit, root, {}};
  out.w.vec(world.settings_.gravity);
  out.w.pod(world.settings_.damping);
  out.w.size(world.laws_.size());
  out.w.size(n);
  blocks_to_root(world, out, rest, mine);
  slots_to_root(world, out);
  energy_to_root(world, out, rest, mine);
}

Decomposition::RestingTerms Decomposition::resting_terms(World& world) {
  PairDistribution& dist = *world.settings_.distribution;
  const int rank = dist.rank();
  const std::size_t n = world.blocks_.size();
  // The resting blocks' loads and stiffness sums, as sum_resting_loads sums them on a whole
  // world (every active slot in (a, b) order, its arithmetic), on every process: 11 values each.
  RestingTerms rest;
  rest.at.assign(n, n);
  if (resting_.size() == n) {
    for (std::size_t i = 0; i < n; ++i) {
      if (resting_[i] == 0) continue;
      rest.at[i] = rest.values.size() / kRest;
      rest.values.resize(rest.values.size() + kRest, 0.0);
    }
  }
  if (!rest.values.empty()) {
    std::vector<const World::PairSlot*> terms;
    for (const World::PairSlot& s : world.slots_) {
      if (s.active && (resting_[s.a] != 0 || resting_[s.b] != 0) &&
          pair_owner(world, s.a, s.b) == rank)
        terms.push_back(&s);
    }
    struct Term {
      std::int32_t a, b;
      double f[3], xf[3], normal[3];
      double twist, spread, stiffness, twist_stiffness;
    };
    static_assert(std::is_trivially_copyable_v<Term>);
    merge_to_root(
        world, terms.size(),
        [&](std::size_t k) {
          return (static_cast<std::uint64_t>(terms[k]->a) << 32) |
                 static_cast<std::uint32_t>(terms[k]->b);
        },
        [&](std::size_t k, std::string& text) {
          const Contact& ct = world.contact_of(*terms[k]);
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
            const std::size_t j = rest.at[static_cast<std::size_t>(i)];
            if (j == n) continue;
            double* r = rest.values.data() + j * kRest;
            Eigen::Map<Eigen::Vector3d> force(r), torque(r + 3), contact_force(r + 6);
            const Eigen::Vector3d& position = world.blocks_[static_cast<std::size_t>(i)].position;
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
    std::vector<char> bytes(rest.values.size() * sizeof(double));
    if (!bytes.empty()) std::memcpy(bytes.data(), rest.values.data(), bytes.size());
    dist.broadcast(bytes);
    if (bytes.size() != rest.values.size() * sizeof(double))
      throw std::logic_error("save_state_to_root: a malformed broadcast");
    if (!bytes.empty()) std::memcpy(rest.values.data(), bytes.data(), bytes.size());
  }
  return rest;
}

void Decomposition::blocks_to_root(World& world, RootStream& out, const RestingTerms& rest,
                                   const std::vector<std::size_t>& mine) {
  const std::size_t n = world.blocks_.size();
  const auto loads_of = [&](std::size_t i, Eigen::Vector3d* loads) -> const Eigen::Vector3d* {
    if (rest.at[i] == n) return nullptr;
    const double* r = rest.values.data() + rest.at[i] * kRest;
    for (int k = 0; k < 3; ++k) loads[k] = Eigen::Vector3d(r[3 * k], r[3 * k + 1], r[3 * k + 2]);
    return loads;
  };
  // The blocks, each with its stiffness sums (kept for the section after the blocks).
  std::vector<double> stiffness(out.root ? 2 * n : 0, 0.0);
  out.flush();
  merge_to_root(
      world, mine.size(), [&](std::size_t k) { return static_cast<std::uint64_t>(mine[k]); },
      [&](std::size_t k, std::string& text) {
        const std::size_t i = mine[k];
        Eigen::Vector3d loads[3];
        const double* r = rest.at[i] == n ? nullptr : rest.values.data() + rest.at[i] * kRest;
        const double head[3] = {
            static_cast<double>(i),
            r ? r[9] : (i < world.stiffness_.size() ? world.stiffness_[i] : 0.0),
            r ? r[10]
              : (i < world.rotational_stiffness_.size() ? world.rotational_stiffness_[i] : 0.0)};
        text.append(reinterpret_cast<const char*>(head), sizeof head);
        StateWriter b;
        world.save_block(b, i, loads_of(i, loads));
        text.append(reinterpret_cast<const char*>(b.bytes().data()), b.bytes().size());
      },
      [&](std::string_view text) {
        double head[3];
        std::memcpy(head, text.data(), sizeof head);
        const auto i = static_cast<std::size_t>(head[0]);
        stiffness[i] = head[1];
        stiffness[n + i] = head[2];
        out.emit(text.substr(sizeof head));
      });
  if (out.root) {
    out.w.size(n);
    for (std::size_t i = 0; i < n; ++i) out.w.pod(stiffness[i]);
    out.w.size(n);
    for (std::size_t i = 0; i < n; ++i) out.w.pod(stiffness[n + i]);
  }
  std::vector<double>().swap(stiffness);
}

void Decomposition::slots_to_root(World& world, RootStream& out) {
  const int rank = world.settings_.distribution->rank();
  const std::size_t n = world.blocks_.size();
  // The counters, with the overlap violation's index in the whole (a, b)-sorted slot list:
  // the owned slots before its pair, summed over the processes.
  std::vector<const World::PairSlot*> owned;
  for (const World::PairSlot& s : world.slots_)
    if (pair_owner(world, s.a, s.b) == rank) owned.push_back(&s);
  std::int64_t counts[3] = {static_cast<std::int64_t>(owned.size()), 0, 0};
  if (std::isfinite(overlap_key_)) {
    for (const World::PairSlot* s : owned) {
      const double key = static_cast<double>(s->a) * static_cast<double>(n) + s->b;
      counts[1] += key < overlap_key_ ? 1 : 0;
      counts[2] += key == overlap_key_ ? 1 : 0;
    }
  }
  reduce_partials(world, {}, {}, counts);
  if (out.root) world.save_counters(out.w, counts[2] > 0 ? counts[1] : -1);
  const auto pair_key = [&](std::size_t k) {
    return (static_cast<std::uint64_t>(owned[k]->a) << 32) |
           static_cast<std::uint32_t>(owned[k]->b);
  };
  // The slots' pairs, then their records (a contact state where a force acts, as synchronize
  // keeps it: through its bytes).
  if (out.root) out.w.size(static_cast<std::size_t>(counts[0]));
  out.flush();
  merge_to_root(
      world, owned.size(), pair_key,
      [&](std::size_t k, std::string& text) {
        const std::int32_t ab[2] = {owned[k]->a, owned[k]->b};
        text.append(reinterpret_cast<const char*>(ab), sizeof ab);
      },
      out.emit);
  if (out.root) out.w.size(static_cast<std::size_t>(counts[0]));
  out.flush();
  merge_to_root(
      world, owned.size(), pair_key,
      [&](std::size_t k, std::string& text) {
        const World::PairSlot& s = *owned[k];
        StateWriter b;
        if (s.active) {
          char bytes[kContactBytes];
          contact_to_bytes(world.contact_of(s), bytes);
          const Contact c = contact_from_bytes(bytes);
          world.save_slot(b, s, &c);
        } else {
          world.save_slot(b, s, nullptr);
        }
        text.append(reinterpret_cast<const char*>(b.bytes().data()), b.bytes().size());
      },
      out.emit);
  if (out.root) {
    // save_state's layout: the bolts (none on a distributed world, which refuses them) before
    // the divergence checkpoint.
    save_bolts(out.w, world.bolts_);
    save_bolts(out.w, world.checkpoint_.bolts);
    world.save_divergence_checkpoint(out.w);
  }
  out.flush();
}

void Decomposition::energy_to_root(World& world, RootStream& out, const RestingTerms& rest,
                                   const std::vector<std::size_t>& mine) {
  const std::size_t n = world.blocks_.size();
  // The energy ledger (EnergyLedger::save_state's layout): the budget (every process's), each
  // block's record from its owner (a resting block's contact impulses from the sums above, as
  // sum_resting_loads sets them), the level velocities (kept for their two lists), the flag.
  const EnergyBudget& e = world.energy_.budget();
  if (out.root) {
    for (double v : {e.kinetic, e.elastic, e.gravity_work, e.load_work, e.boundary_work,
                     e.friction_dissipation, e.damping_dissipation, e.initial})
      out.w.pod(v);
    out.w.size(n);
  }
  constexpr std::size_t kRecord = EnergyLedger::kBlockRecordDoubles;
  constexpr std::size_t kLevel = kRecord - 6;  // the record's level velocities
  std::vector<double> level(out.root ? 6 * n : 0, 0.0);
  out.flush();
  merge_to_root(
      world, mine.size(), [&](std::size_t k) { return static_cast<std::uint64_t>(mine[k]); },
      [&](std::size_t k, std::string& text) {
        const std::size_t i = mine[k];
        double record[1 + kRecord];
        record[0] = static_cast<double>(i);
        world.energy_.block_record(i, record + 1);
        if (rest.at[i] != n && world.step_count_ != 0) {
          constexpr std::size_t kContact = 1 + 24;  // as sum_resting_loads
          const double* r = rest.values.data() + rest.at[i] * kRest;
          const Eigen::Vector3d impulse = world.last_dt_ * Eigen::Vector3d(r[6], r[7], r[8]);
          const Eigen::Vector3d angular = world.last_dt_ * Eigen::Vector3d(r[3], r[4], r[5]);
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
        out.emit(text.substr(sizeof(double), kLevel * sizeof(double)));
        for (std::size_t c = 0; c < 6; ++c) level[6 * i + c] = record[1 + kLevel + c];
      });
  if (!out.root) return;
  for (const std::size_t at : {std::size_t{0}, std::size_t{3}}) {
    out.w.size(n);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t c = 0; c < 3; ++c) out.w.pod(level[6 * i + at + c]);
  }
  out.w.pod(static_cast<std::uint8_t>(world.energy_.started()));
  for (double v : world.energy_.field_terms()) out.w.pod(v);
  out.flush();
}

void Decomposition::put_block_state(const World& world, std::vector<char>& out,
                                    std::size_t i) const {
  // A block's whole step state: its index and motion state (as a ghost), its loads and stiffness
  // sums, its energy record, and the box and world planes of the step's start pose.
  const Block& b = world.blocks_[i];
  WireWriter w(out);
  SaveArchive ar(w);
  ar.as<std::int64_t>(b.index);
  motion_record(ar, b);
  ar(b.force);
  ar(b.torque);
  ar(b.contact_force);
  ar(i < world.stiffness_.size() ? world.stiffness_[i] : 0.0);
  ar(i < world.rotational_stiffness_.size() ? world.rotational_stiffness_[i] : 0.0);
  double energy[EnergyLedger::kBlockRecordDoubles];
  world.energy_.block_record(i, energy);
  for (const double e : energy) ar(e);
  ar(world.box_min_[i]);
  ar(world.box_max_[i]);
  ar.as<std::uint64_t>(b.world_planes.size());
  for (const Halfspace& h : b.world_planes) {
    ar(h.normal);
    ar(h.offset);
  }
}

std::size_t Decomposition::take_block_state(World& world, const std::vector<char>& in,
                                            std::size_t at, std::size_t end, bool apply,
                                            std::size_t& i) {
  // put_block_state's record, read into the block when `apply` (else past it). The receiver has
  // sized stiffness_, rotational_stiffness_ and the energy records (prepare).
  WireReader r(in, at, end, "block state");
  LoadArchive ar(r);
  const auto index = r.pod<std::int64_t>();
  i = static_cast<std::size_t>(index);
  if (index < 0 || i >= world.blocks_.size())
    throw std::logic_error("block state: a process sent a malformed block");
  Block passed;  // where a record not applied is read
  Block& b = apply ? world.blocks_[i] : passed;
  motion_record(ar, b);
  ar(b.force);
  ar(b.torque);
  ar(b.contact_force);
  double stiffness = 0.0, rotational_stiffness = 0.0;
  ar(stiffness);
  ar(rotational_stiffness);
  double energy[EnergyLedger::kBlockRecordDoubles];
  for (double& e : energy) ar(e);
  Eigen::Vector3d box_min, box_max;
  ar(box_min);
  ar(box_max);
  const auto planes = r.pod<std::uint64_t>();
  if (planes != world.blocks_[i].shape.planes().size() || planes * 32 > end - at)
    throw std::logic_error("block state: a process sent a malformed block");
  if (!apply) return at + planes * 32;
  b.world_planes.resize(planes);
  for (Halfspace& h : b.world_planes) {
    ar(h.normal);
    ar(h.offset);
  }
  world.box_min_[i] = box_min;
  world.box_max_[i] = box_max;
  world.stiffness_[i] = stiffness;
  world.rotational_stiffness_[i] = rotational_stiffness;
  world.energy_.set_block_record(i, energy);
  return at;
}

void Decomposition::synchronize(World& world) {
  // A divergence checkpoint in parts is made whole with the world (its readers, the reset to it
  // and the restart file, read a whole world).
  if (world.settings_.distribution) gather_checkpoint(world);
  if (!world.settings_.distribution || replica_complete_) return;
  // A slot travels as raw bytes (put_slot).
  PairDistribution& dist = *world.settings_.distribution;
  const int rank = dist.rank();
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t n = world.blocks_.size();
  world.energy_.prepare(n);

  // This process's blocks, then the pairs it owns (the two counts first).
  std::vector<char> out;
  std::uint64_t own_count = 0, slot_count = 0;
  for (std::size_t i = 0; i < n; ++i) own_count += own_[i];
  for (const auto& s : world.slots_) slot_count += pair_owner(world, s.a, s.b) == rank ? 1 : 0;
  put(out, own_count);
  put(out, slot_count);
  for (std::size_t i = 0; i < n; ++i) {
    if (own_[i] != 0) put_block_state(world, out, i);
  }
  for (const auto& s : world.slots_) {
    if (pair_owner(world, s.a, s.b) != rank) continue;
    put_slot(out, s, s.active ? &world.contact_of(s) : nullptr);
  }
  std::vector<std::size_t> counts;
  std::vector<char> all = dist.all_gather(out, counts);
  // The refresh is the peak of a distributed run's memory (docs/scaling.md, "Memory"): this
  // process's part is freed at once, the slots are reserved exactly, and the contact states are
  // read from the gathered bytes in place (by offset) and copied once, into the new store.
  const std::size_t out_bytes = out.size(), all_bytes = all.size();
  std::vector<char>().swap(out);

  // Every process's blocks into place, every owned slot into one list sorted by (a, b).
  world.stiffness_.resize(n, 0.0);
  world.rotational_stiffness_.resize(n, 0.0);
  std::vector<World::PairSlot> slots;
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
      at = take_block_state(world, all, at, begin + counts[r], static_cast<int>(r) != rank, i);
    }
    for (std::uint64_t k = 0; k < slots_in; ++k) {
      World::PairSlot s;
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
  std::sort(slots.begin(), slots.end(), [](const World::PairSlot& x, const World::PairSlot& y) {
    return x.a < y.a || (x.a == y.a && x.b < y.b);
  });
  world.slots_ = std::move(slots);
  world.contacts_.clear();
  world.contacts_.reserve(states.size());
  for (World::PairSlot& s : world.slots_) {
    if (s.contact < 0) continue;
    world.contacts_.push_back(
        contact_from_bytes(all.data() + states[static_cast<std::size_t>(s.contact)]));
    s.contact = static_cast<std::int32_t>(world.contacts_.size() - 1);
  }
  std::vector<char>().swap(all);
  sum_resting_loads(world);
  // The candidate list as one process leaves it after a step: the pairs of the slots, in order
  // (this process found only its own blocks' pairs; a checkpoint saves the list).
  world.pairs_.resize(world.slots_.size());
  for (std::size_t k = 0; k < world.slots_.size(); ++k)
    world.pairs_[k] = {world.slots_[k].a, world.slots_[k].b};
  world.overlap_violation_ =
      slot_of_key(world.slots_, n, overlap_key_, [](const World::PairSlot&) { return true; });
  local_.assign(n, 1);
  ghosts_listed_ = false;
  replica_complete_ = true;
  dist_stats_.replica_refreshes += 1;
  dist_stats_.replica_bytes_sent += static_cast<std::int64_t>(out_bytes);
  dist_stats_.replica_bytes_received += static_cast<std::int64_t>(all_bytes - out_bytes);
  dist_stats_.replica_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace blockdem
