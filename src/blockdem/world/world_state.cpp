// The world's complete dynamic state as bytes (for restart files): everything a step reads that
// the scenario does not give, so that a world built from the scenario and loaded with this state
// continues bit-identically. Unlike the compact divergence checkpoint, nothing is re-derived.
#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>
#include <string>

#include "blockdem/world/bolt_state.hpp"
#include "blockdem/world/state_record.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {
namespace {

using Saver = SaveArchive<StateWriter>;
using Loader = LoadArchive<StateReader>;

void write_doubles(StateWriter& w, const std::vector<double>& v) {
  w.size(v.size());
  for (double x : v) w.pod(x);
}

std::vector<double> read_doubles(StateReader& r) {
  std::vector<double> v(r.size());
  for (double& x : v) r.pod(x);
  return v;
}

struct CheckpointHead {
  bool valid;
  double time;
  std::int64_t step_count, broken_bonds;
};

// The divergence checkpoint's layout (restart files, and a checkpoint kept in a scratch file):
// its header, each block's record, the kept slots' histories in (a, b) order, the energy ledger.
// `each_block(record)` calls record(state, motion, servo) for every block in order, `each_kept`
// record(history) for every kept slot: a checkpoint in memory and the world itself give the same
// bytes.
template <class EachBlock, class EachKept>
void write_checkpoint_section(StateWriter& w, const CheckpointHead& head, std::size_t blocks,
                              EachBlock each_block, std::size_t kept, EachKept each_kept,
                              const EnergyLedger& energy, bool dashpots) {
  Saver ar(w);
  w.pod(static_cast<std::uint8_t>(head.valid));
  w.pod(head.time);
  w.pod(head.step_count);
  w.pod(head.broken_bonds);
  w.size(blocks);
  each_block([&](const auto& state, const Motion& motion, const Servo& servo) {
    checkpoint_block_record(ar, state, motion, servo);
  });
  w.size(kept);
  each_kept([&](const auto& history) { history_record(ar, history); });
  energy.save_state(w, dashpots);
}

}  // namespace

void World::save_state(StateWriter& w) const {
  decomposition_.require_replica("save_state");
  if (checkpoint_.partial)
    throw std::logic_error("save_state: the divergence checkpoint is in parts; call synchronize()");
  // Settings a stage changes.
  w.vec(settings_.gravity);
  w.pod(settings_.damping);
  w.size(laws_.size());
  w.size(blocks_.size());
  for (std::size_t i = 0; i < blocks_.size(); ++i) save_block(w, i, nullptr);
  write_doubles(w, stiffness_);
  write_doubles(w, rotational_stiffness_);
  save_counters(w, overlap_violation_);
  // The broad phase's pairs of the last step, which its merge made the slots' pairs (a restart
  // reads them and leaves them to the next broad phase; the step frees its own list).
  w.size(slots_.size());
  for (const PairSlot& s : slots_) {
    w.pod(static_cast<std::int32_t>(s.a));
    w.pod(static_cast<std::int32_t>(s.b));
  }
  w.size(slots_.size());
  for (const PairSlot& s : slots_) save_slot(w, s, s.contact >= 0 ? &contact_of(s) : nullptr);
  // The bolts, and those of the divergence checkpoint (format version 6).
  save_bolts(w, bolts_);
  save_bolts(w, checkpoint_.bolts);
  save_divergence_checkpoint(w);
  // Contact damping: the last step's dashpots' halves of work the next step adds.
  if (settings_.contact_damping > 0.0) {
    for (const std::int64_t limb : dashpot_pending().limbs()) w.pod(limb);
  }
  // The energy ledger last: level_state() and energy_budget() read it.
  energy_.save_state(w, settings_.contact_damping > 0.0);
}

void World::save_block(StateWriter& w, std::size_t i, const Eigen::Vector3d* loads) const {
  Saver ar(w);
  const std::span<const int> laws = face_laws(static_cast<int>(i));
  block_record(ar, blocks_[i], box_min_[i], box_max_[i], laws, loads,
               static_cast<int>(laws_.size()));
}

void World::save_counters(StateWriter& w, std::int64_t overlap_violation) const {
  w.pod(contact_dt_);
  w.pod(time_);
  w.pod(step_count_);
  w.pod(last_dt_);
  w.pod(broken_bonds_);
  w.pod(overlap_violation);
  w.pod(static_cast<std::uint8_t>(slots_rules_version_ == rules_version_));
  // A gradual excavation's loads (none on a distributed world, which refuses one).
  w.size(relaxation_.size());
  for (const Relaxation& x : relaxation_) {
    w.pod(static_cast<std::int32_t>(x.block));
    for (const Eigen::Vector3d* v : {&x.base_force, &x.base_torque, &x.force, &x.torque}) w.vec(*v);
  }
  w.size(broken_by_set_.size());
  for (const auto& row : broken_by_set_) {
    w.pod(row[0]);
    w.pod(row[1]);
  }
}

void World::save_slot(StateWriter& w, const PairSlot& s, const Contact* contact) const {
  const Contact& c = contact ? *contact : fresh_contact(s);
  const Boon2012Cache cache = unpack_warm_start(s.narrow_cache);
  Saver ar(w);
  contact_record(ar, c, cache);
  slot_record(ar, s, c);
}

void World::save_divergence_checkpoint(StateWriter& w) const {
  // The divergence checkpoint, so that a blow-up after a restart rolls back to the same state.
  if (checkpoint_.file) {
    checkpoint_.file->copy_to(w);  // written in this layout by write_checkpoint_of_world
    return;
  }
  const Checkpoint& cp = checkpoint_;
  write_checkpoint_section(
      w, {cp.valid, cp.time, cp.step_count, cp.broken_bonds}, cp.blocks.size(),
      [&](const auto& record) {
        std::size_t servo = 0;  // the next of cp.servos (the others are Servo{})
        for (std::size_t i = 0; i < cp.blocks.size(); ++i) {
          const bool listed = servo < cp.servos.size() && cp.servos[servo].first == i;
          record(cp.blocks[i], cp.motions[i], listed ? cp.servos[servo++].second : Servo{});
        }
      },
      cp.kept_slots(), [&](const auto& record) { cp.for_each_kept_slot(record); }, cp.energy,
      settings_.contact_damping > 0.0);
}

void World::write_checkpoint_of_world(StateWriter& w, std::size_t kept) const {
  write_checkpoint_section(
      w, {true, time_, step_count_, broken_bonds_}, blocks_.size(),
      [&](const auto& record) {
        for (const Block& b : blocks_) record(b, b.motion, b.servo());
      },
      kept,
      [&](const auto& record) {
        for (const PairSlot& s : slots_) {
          if (const auto h = checkpoint_history(s)) record(*h);
        }
      },
      energy_, settings_.contact_damping > 0.0);
}

void World::load_state(StateReader& r) {
  // Loaded alike on every process: the world is whole, and is partitioned again at its next step.
  decomposition_.forget_partition();
  drop_primed();
  settings_.gravity = r.vec();
  r.pod(settings_.damping);
  if (r.size() != laws_.size())
    throw StateError("the saved state has another number of joint laws than the scenario");
  load_blocks(r);
  load_counters(r);
  load_slots(r);
  bolts_ = load_bolts(r, blocks_.size());
  checkpoint_.bolts = load_bolts(r, blocks_.size());
  load_divergence_checkpoint(r);
  checkpoint_.energy.load_state(r, settings_.contact_damping > 0.0);
  spill_loaded_checkpoint();
  dashpot_restored_ = ExactSum{};
  if (settings_.contact_damping > 0.0) {
    std::array<std::int64_t, ExactSum::kLimbs> limbs{};
    for (std::int64_t& limb : limbs) r.pod(limb);
    dashpot_restored_ = ExactSum::from_limbs(limbs);
  }
  // After remove_blocks above, which starts the accounting again.
  energy_.load_state(r, settings_.contact_damping > 0.0);
}

void World::load_blocks(StateReader& r) {
  // Blocks removed by earlier stages (an excavation) are removed here too, matched by name.
  const std::size_t n = r.size();
  density_scaled_ = false;
  std::vector<Block> saved(n);
  std::vector<Eigen::Vector3d> saved_min(n), saved_max(n);
  std::vector<std::vector<int>> saved_laws(n);
  Loader ar(r);
  for (std::size_t i = 0; i < n; ++i)
    block_record(ar, saved[i], saved_min[i], saved_max[i], saved_laws[i], nullptr,
                 static_cast<int>(laws_.size()));
  if (n != blocks_.size()) {
    std::vector<int> gone;
    std::size_t j = 0;
    for (std::size_t i = 0; i < blocks_.size(); ++i) {
      if (j < n && blocks_[i].name == saved[j].name) {
        ++j;
      } else {
        gone.push_back(static_cast<int>(i));
      }
    }
    if (j != n || n > blocks_.size())
      throw StateError("the saved blocks are not the scenario's blocks");
    remove_blocks(gone);
  }
  for (std::size_t i = 0; i < n; ++i) {
    Block& b = blocks_[i];
    Block& s = saved[i];
    if (b.name != s.name) throw StateError("the saved blocks are not the scenario's blocks");
    if (s.world_planes.size() != b.shape.planes().size())
      throw StateError("block '" + b.name + "' has another shape than in the saved state");
    b.position = s.position;
    b.orientation = s.orientation;
    b.velocity = s.velocity;
    b.angular_velocity = s.angular_velocity;
    b.angular_momentum = s.angular_momentum;
    b.mass_scale = s.mass_scale;
    b.inertia_scale = s.inertia_scale;
    density_scaled_ = density_scaled_ || s.mass_scale != 1.0 || s.inertia_scale != 1.0;
    b.motion = s.motion;
    b.set_servo(s.servo());
    b.force = s.force;
    b.torque = s.torque;
    b.contact_force = s.contact_force;
    b.world_planes = std::move(s.world_planes);
    box_min_[i] = saved_min[i];
    box_max_[i] = saved_max[i];
    b.initial_position = s.initial_position;
    b.initial_orientation = s.initial_orientation;
    if (!saved_laws[i].empty() && saved_laws[i].size() != b.shape.planes().size())
      throw StateError("block '" + b.name + "' has another shape than in the saved state");
    if (!saved_laws[i].empty() || face_laws_.has(i)) face_laws_.set(i, saved_laws[i]);
    std::vector<int>().swap(saved_laws[i]);
  }
}

void World::load_counters(StateReader& r) {
  const std::size_t n = blocks_.size();
  stiffness_ = read_doubles(r);
  rotational_stiffness_ = read_doubles(r);
  if (stiffness_.size() > n || rotational_stiffness_.size() > n)
    throw StateError("saved state is corrupt (stiffness per block)");
  r.pod(contact_dt_);
  r.pod(time_);
  r.pod(step_count_);
  r.pod(last_dt_);
  r.pod(broken_bonds_);
  r.pod(overlap_violation_);
  const bool rules_current = r.pod<std::uint8_t>() != 0;
  slots_rules_version_ = rules_current ? rules_version_ : rules_version_ - 1;
  relaxation_.resize(r.size());
  for (Relaxation& x : relaxation_) {
    x.block = r.pod<std::int32_t>();
    if (x.block < 0 || x.block >= static_cast<int>(blocks_.size()))
      throw StateError("a relaxed block of the saved state is not the scenario's");
    for (Eigen::Vector3d* v : {&x.base_force, &x.base_torque, &x.force, &x.torque}) *v = r.vec();
  }
  broken_by_set_.resize(r.size());
  for (auto& row : broken_by_set_) {
    r.pod(row[0]);
    r.pod(row[1]);
  }
}

void World::load_slots(StateReader& r) {
  const int block_count = static_cast<int>(blocks_.size());
  const int law_count = static_cast<int>(laws_.size());
  auto check_pair = [&](int a, int b) {
    if (a < 0 || b <= a || b >= block_count) throw StateError("saved contact is corrupt");
  };
  // The last step's pairs, which the next broad phase finds again: checked, not kept.
  std::vector<std::pair<int, int>>().swap(pairs_);
  for (std::size_t k = r.size(); k-- > 0;) {
    const int a = r.pod<std::int32_t>();
    const int b = r.pod<std::int32_t>();
    check_pair(a, b);
  }
  slots_.clear();
  slots_.resize(r.size());
  contacts_.clear();
  // Room for a state per slot (a settled pile has nearly one): pages that no state fills are
  // never touched, and the store does not grow by doubling (3 times its size for a moment).
  contacts_.reserve(slots_.size());
  active_count_ = 0;
  Loader ar(r);
  for (PairSlot& s : slots_) {
    Boon2012Cache cache;
    Contact c;
    contact_record(ar, c, cache);
    s.narrow_cache = pack_warm_start(cache);
    check_pair(c.a, c.b);
    if (c.law < -1 || c.law >= law_count) throw StateError("saved contact is corrupt");
    s.a = c.a;
    s.b = c.b;
    s.bond = c.shear.bond;
    slot_record(ar, s, c);
    if (s.group_law < -1 || s.group_law >= law_count) throw StateError("saved contact is corrupt");
    active_count_ += s.active ? 1 : 0;
    if (s.active || c.has_history) {
      s.contact = static_cast<std::int32_t>(contacts_.size());
      contacts_.push_back(std::move(c));
    }
  }
}

void World::load_divergence_checkpoint(StateReader& r) {
  const int block_count = static_cast<int>(blocks_.size());
  const int law_count = static_cast<int>(laws_.size());
  auto check_pair = [&](int a, int b) {
    if (a < 0 || b <= a || b >= block_count) throw StateError("saved contact is corrupt");
  };
  checkpoint_.valid = r.pod<std::uint8_t>() != 0;
  checkpoint_.partial = false;  // a restart file holds the whole checkpoint
  checkpoint_.file.reset();     // and is read into memory
  std::vector<int>().swap(checkpoint_.part_blocks);
  r.pod(checkpoint_.time);
  r.pod(checkpoint_.step_count);
  r.pod(checkpoint_.broken_bonds);
  checkpoint_.blocks.resize(r.size());
  checkpoint_.motions.resize(checkpoint_.blocks.size());
  checkpoint_.servos.clear();
  Loader ar(r);
  for (std::size_t i = 0; i < checkpoint_.blocks.size(); ++i) {
    Servo servo;
    checkpoint_block_record(ar, checkpoint_.blocks[i], checkpoint_.motions[i], servo);
    if (!same_bits(servo, Servo{})) checkpoint_.servos.emplace_back(i, servo);
  }
  checkpoint_.contacts.clear();
  checkpoint_.bonds.clear();
  const std::size_t kept = r.size();
  int last_a = -1, last_b = -1;
  for (std::size_t k = 0; k < kept; ++k) {
    ContactHistory h;
    history_record(ar, h);
    check_pair(h.a, h.b);
    if (h.law < -1 || h.law >= law_count) throw StateError("saved checkpoint contact is corrupt");
    // In (a, b) order, as saved: each list keeps it, and restore and save walk them merged.
    if (h.a < last_a || (h.a == last_a && h.b <= last_b))
      throw StateError("saved checkpoint contacts are out of order");
    last_a = h.a;
    last_b = h.b;
    if (const auto bond = BondHistory::of(h)) {
      checkpoint_.bonds.push_back(*bond);
    } else {
      checkpoint_.contacts.push_back(h);
    }
  }
}

}  // namespace blockdem
