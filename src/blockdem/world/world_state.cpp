// The world's complete dynamic state as bytes (for restart files): everything a step reads that
// the scenario does not give, so that a world built from the scenario and loaded with this state
// continues bit-identically. Unlike the compact divergence checkpoint, nothing is re-derived.
#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

#include "blockdem/world/world.hpp"

namespace blockdem {
namespace {

void write_servo(StateWriter& w, const Servo& s) {
  w.vec(s.axis);
  w.pod(s.target_force);
  w.pod(s.gain);
  w.pod(s.max_speed);
  w.pod(s.tolerance);
  w.pod(static_cast<std::uint8_t>(s.hold));
}

Servo read_servo(StateReader& r) {
  Servo s;
  s.axis = r.vec();
  r.pod(s.target_force);
  r.pod(s.gain);
  r.pod(s.max_speed);
  r.pod(s.tolerance);
  s.hold = r.pod<std::uint8_t>() != 0;
  return s;
}

void write_shear(StateWriter& w, const ShearState& s) {
  w.vec(s.force);
  w.vec(s.elastic_displacement);
  w.pod(s.plastic_slip);
  w.pod(s.elastic_energy);
  w.pod(static_cast<std::int32_t>(s.bond));
}

ShearState read_shear(StateReader& r) {
  ShearState s;
  s.force = r.vec();
  s.elastic_displacement = r.vec();
  r.pod(s.plastic_slip);
  r.pod(s.elastic_energy);
  const auto bond = r.pod<std::int32_t>();
  if (bond < 0 || bond > static_cast<std::int32_t>(BondState::unbonded))
    throw StateError("saved bond state is corrupt");
  s.bond = static_cast<BondState>(bond);
  return s;
}

void write_motion(StateWriter& w, Motion m) {
  w.pod(static_cast<std::int32_t>(m));
}
Motion read_motion(StateReader& r) {
  return static_cast<Motion>(r.pod<std::int32_t>());
}

void write_cache(StateWriter& w, const Boon2012Cache& c) {
  w.pod(static_cast<std::int32_t>(c.planes_a));
  w.pod(static_cast<std::int32_t>(c.planes_b));
  w.pod(c.ball.radius);
  w.vec(c.ball.center);
  w.pod(static_cast<std::uint8_t>(c.ball.bounded));
  w.pod(static_cast<std::int32_t>(c.ball.iterations));
  for (int i : c.ball.active) w.pod(static_cast<std::int32_t>(i));
  w.pod(static_cast<std::int32_t>(c.ball.num_active));
  w.pod(static_cast<std::uint8_t>(c.has_ball));
  w.vec(c.last_point);
  w.pod(static_cast<std::uint8_t>(c.has_point));
  for (int i : c.slice.edge_planes) w.pod(static_cast<std::int32_t>(i));
  w.size(c.slice.count);
}

Boon2012Cache read_cache(StateReader& r) {
  Boon2012Cache c;
  c.planes_a = r.pod<std::int32_t>();
  c.planes_b = r.pod<std::int32_t>();
  r.pod(c.ball.radius);
  c.ball.center = r.vec();
  c.ball.bounded = r.pod<std::uint8_t>() != 0;
  c.ball.iterations = r.pod<std::int32_t>();
  for (int& i : c.ball.active) i = r.pod<std::int32_t>();
  c.ball.num_active = r.pod<std::int32_t>();
  c.has_ball = r.pod<std::uint8_t>() != 0;
  c.last_point = r.vec();
  c.has_point = r.pod<std::uint8_t>() != 0;
  for (int& i : c.slice.edge_planes) i = r.pod<std::int32_t>();
  c.slice.count = static_cast<std::size_t>(r.pod<std::uint64_t>());
  if (c.slice.count > c.slice.edge_planes.size()) throw StateError("saved contact is corrupt");
  return c;
}

// A slot's contact and warm start, as one record (the layout of a pair before its state was kept
// apart): a slot without a contact state writes the fresh contact it would start from.
void write_contact(StateWriter& w, const Contact& c, const Boon2012Cache& cache) {
  w.pod(static_cast<std::int32_t>(c.a));
  w.pod(static_cast<std::int32_t>(c.b));
  w.pod(static_cast<std::int32_t>(c.law));
  const ContactGeometryRecord& g = c.geometry;
  w.pod(static_cast<std::uint8_t>(c.touching));
  w.vec(g.point);
  w.vec(g.normal);
  w.pod(g.overlap);
  w.pod(g.area);
  // The overlap LP's ball, which a contact kept in this record's place: the warm start's.
  w.pod(cache.ball.radius);
  w.vec(cache.ball.center);
  write_shear(w, c.shear);
  w.pod(static_cast<std::uint8_t>(c.has_history));
  w.vec(c.previous_normal());
  w.pod(c.normal_stress);
  w.vec(c.force_point());
  w.pod(static_cast<std::uint8_t>(c.integrated));
  w.pod(c.compressed_area());
  w.pod(c.peak_stress());
  w.pod(c.peak_closure());
  w.pod(c.normal_energy());
  w.pod(c.normal_force);
  w.pod(static_cast<std::uint8_t>(c.sliding));
  w.pod(c.twist.moment);
  write_cache(w, cache);
}

Contact read_contact(StateReader& r, Boon2012Cache& cache) {
  Contact c;
  c.a = r.pod<std::int32_t>();
  c.b = r.pod<std::int32_t>();
  c.law = r.pod<std::int32_t>();
  ContactGeometryRecord& g = c.geometry;
  c.touching = r.pod<std::uint8_t>() != 0;
  g.point = r.vec();
  g.normal = r.vec();
  r.pod(g.overlap);
  r.pod(g.area);
  r.pod<double>();  // the overlap LP's ball: the warm start's, read with it below
  r.vec();
  c.shear = read_shear(r);
  c.has_history = r.pod<std::uint8_t>() != 0;
  const Eigen::Vector3d previous_normal = r.vec();
  r.pod(c.normal_stress);
  const Eigen::Vector3d force_point = r.vec();
  c.integrated = r.pod<std::uint8_t>() != 0;
  const double compressed_area = r.pod<double>();
  const double peak_stress = r.pod<double>();
  const double peak_closure = r.pod<double>();
  const double normal_energy = r.pod<double>();
  r.pod(c.normal_force);
  c.sliding = r.pod<std::uint8_t>() != 0;
  r.pod(c.twist.moment);
  // Kept apart only where they are not the point contact's (the same bits either way).
  c.set_previous_normal(previous_normal);
  c.set_force_values(force_point, compressed_area, peak_stress, peak_closure, normal_energy);
  const auto same = [](const auto& x, const auto& y) {
    static_assert(sizeof(x) == sizeof(y));
    return std::memcmp(&x, &y, sizeof(x)) == 0;
  };
  if (same(force_point, c.geometry.point) && same(compressed_area, c.geometry.area) &&
      same(peak_stress, c.normal_stress) && same(peak_closure, c.geometry.overlap) &&
      same(normal_energy, 0.5 * c.normal_force * c.geometry.overlap))
    c.take_point_values();
  cache = read_cache(r);
  return c;
}

void write_doubles(StateWriter& w, const std::vector<double>& v) {
  w.size(v.size());
  for (double x : v) w.pod(x);
}

std::vector<double> read_doubles(StateReader& r) {
  std::vector<double> v(r.size());
  for (double& x : v) r.pod(x);
  return v;
}

}  // namespace

void World::save_state(StateWriter& w) const {
  decomposition_.require_replica("save_state");
  if (checkpoint_.partial)
    throw std::logic_error("save_state: the divergence checkpoint is in parts; call synchronize()");
  // Bolts are not in the state's bytes: a restart would lose them.
  if (!bolts_.empty())
    throw std::invalid_argument("save_state: a world with bolts cannot be saved for a restart yet");
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
  save_divergence_checkpoint(w);
  // The energy ledger last: level_state() and energy_budget() read it.
  energy_.save_state(w);
}

void World::save_block(StateWriter& w, std::size_t i, const Eigen::Vector3d* loads) const {
  const Block& b = blocks_[i];
  w.str(b.name);
  w.vec(b.position);
  w.quat(b.orientation);
  w.vec(b.velocity);
  w.vec(b.angular_velocity);
  w.vec(b.angular_momentum);
  w.pod(b.mass_scale);
  w.pod(b.inertia_scale);
  write_motion(w, b.motion);
  write_servo(w, b.servo());
  w.vec(loads ? loads[0] : b.force);
  w.vec(loads ? loads[1] : b.torque);
  w.vec(loads ? loads[2] : b.contact_force);
  // World planes and box as the last step left them (a restart does not refresh them).
  w.size(b.world_planes.size());
  for (const Halfspace& h : b.world_planes) {
    w.vec(h.normal);
    w.pod(h.offset);
  }
  w.vec(box_min_[i]);
  w.vec(box_max_[i]);
  // The displacements' reference and the faces' laws, which stages may change.
  w.vec(b.initial_position);
  w.quat(b.initial_orientation);
  const std::vector<int>& laws = face_laws(static_cast<int>(i));
  w.size(laws.size());
  for (int law : laws) w.pod(static_cast<std::int32_t>(law));
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
  write_contact(w, c, unpack_warm_start(s.narrow_cache));
  w.pod(static_cast<std::int32_t>(s.group_law));
  w.pod(static_cast<std::uint8_t>(s.broke));
  // The step's terms of a pair: its contact's where a force acts, else zero (as the per-pair
  // pass leaves them).
  w.pod(s.active ? c.slip_work : 0.0);
  w.pod(s.active ? c.stiffness : 0.0);
  w.pod(s.active ? c.twist_stiffness : 0.0);
  w.pod(static_cast<std::uint8_t>(s.active));
}

void World::save_divergence_checkpoint(StateWriter& w) const {
  // The divergence checkpoint, so that a blow-up after a restart rolls back to the same state.
  w.pod(static_cast<std::uint8_t>(checkpoint_.valid));
  w.pod(checkpoint_.time);
  w.pod(checkpoint_.step_count);
  w.pod(checkpoint_.broken_bonds);
  w.size(checkpoint_.blocks.size());
  std::size_t servo = 0;  // the next of checkpoint_.servos (the others are Servo{})
  for (std::size_t i = 0; i < checkpoint_.blocks.size(); ++i) {
    const BlockState& s = checkpoint_.blocks[i];
    w.vec(s.position);
    w.vec(s.velocity);
    w.vec(s.angular_velocity);
    w.vec(s.angular_momentum);
    w.quat(s.orientation);
    write_motion(w, checkpoint_.motions[i]);
    const auto& servos = checkpoint_.servos;
    write_servo(
        w, servo < servos.size() && servos[servo].first == i ? servos[servo++].second : Servo{});
  }
  w.size(checkpoint_.kept_slots());
  checkpoint_.for_each_kept_slot([&](const ContactHistory& h) {
    w.pod(static_cast<std::int32_t>(h.a));
    w.pod(static_cast<std::int32_t>(h.b));
    w.pod(static_cast<std::int32_t>(h.law));
    w.pod(static_cast<std::uint8_t>(h.has_history));
    write_shear(w, h.shear);
    w.pod(h.twist.moment);
    w.vec(h.previous_normal);
    w.vec(h.point);
    w.pod(h.closure);
    w.pod(h.area);
  });
  checkpoint_.energy.save_state(w);
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
  load_divergence_checkpoint(r);
  checkpoint_.energy.load_state(r);
  energy_.load_state(r);  // after remove_blocks above, which starts the accounting again
}

void World::load_blocks(StateReader& r) {
  // Blocks removed by earlier stages (an excavation) are removed here too, matched by name.
  const std::size_t n = r.size();
  density_scaled_ = false;
  std::vector<Block> saved(n);
  std::vector<Eigen::Vector3d> saved_min(n), saved_max(n);
  std::vector<std::vector<int>> saved_laws(n);
  for (std::size_t i = 0; i < n; ++i) {
    Block& b = saved[i];
    b.name = r.str();
    b.position = r.vec();
    b.orientation = r.quat();
    b.velocity = r.vec();
    b.angular_velocity = r.vec();
    b.angular_momentum = r.vec();
    r.pod(b.mass_scale);
    r.pod(b.inertia_scale);
    b.motion = read_motion(r);
    b.set_servo(read_servo(r));
    b.force = r.vec();
    b.torque = r.vec();
    b.contact_force = r.vec();
    b.world_planes.resize(r.size());
    for (Halfspace& h : b.world_planes) {
      h.normal = r.vec();
      r.pod(h.offset);
    }
    saved_min[i] = r.vec();
    saved_max[i] = r.vec();
    b.initial_position = r.vec();
    b.initial_orientation = r.quat();
    saved_laws[i].resize(r.size());
    for (int& law : saved_laws[i]) {
      std::int32_t l = 0;
      r.pod(l);
      if (l < -1 || l >= static_cast<std::int32_t>(laws_.size()))
        throw StateError("block '" + b.name + "' has a face law the scenario does not have");
      law = l;
    }
  }
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
    if (!saved_laws[i].empty() || i < face_laws_.size()) {
      if (face_laws_.size() <= i) face_laws_.resize(blocks_.size());
      face_laws_[i] = std::move(saved_laws[i]);
    }
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
  for (PairSlot& s : slots_) {
    Boon2012Cache cache;
    Contact c = read_contact(r, cache);
    s.narrow_cache = pack_warm_start(cache);
    check_pair(c.a, c.b);
    if (c.law < -1 || c.law >= law_count) throw StateError("saved contact is corrupt");
    s.a = c.a;
    s.b = c.b;
    s.bond = c.shear.bond;
    s.group_law = r.pod<std::int32_t>();
    if (s.group_law < -1 || s.group_law >= law_count) throw StateError("saved contact is corrupt");
    s.broke = r.pod<std::uint8_t>() != 0;
    r.pod(c.slip_work);
    r.pod(c.stiffness);
    r.pod(c.twist_stiffness);
    s.active = r.pod<std::uint8_t>() != 0;
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
  std::vector<int>().swap(checkpoint_.part_blocks);
  r.pod(checkpoint_.time);
  r.pod(checkpoint_.step_count);
  r.pod(checkpoint_.broken_bonds);
  checkpoint_.blocks.resize(r.size());
  checkpoint_.motions.resize(checkpoint_.blocks.size());
  checkpoint_.servos.clear();
  for (std::size_t i = 0; i < checkpoint_.blocks.size(); ++i) {
    BlockState& s = checkpoint_.blocks[i];
    s.position = r.vec();
    s.velocity = r.vec();
    s.angular_velocity = r.vec();
    s.angular_momentum = r.vec();
    s.orientation = r.quat();
    checkpoint_.motions[i] = read_motion(r);
    const Servo servo = read_servo(r);
    if (!same_bits(servo, Servo{})) checkpoint_.servos.emplace_back(i, servo);
  }
  checkpoint_.contacts.clear();
  checkpoint_.bonds.clear();
  const std::size_t kept = r.size();
  int last_a = -1, last_b = -1;
  for (std::size_t k = 0; k < kept; ++k) {
    ContactHistory h;
    h.a = r.pod<std::int32_t>();
    h.b = r.pod<std::int32_t>();
    check_pair(h.a, h.b);
    h.law = r.pod<std::int32_t>();
    if (h.law < -1 || h.law >= law_count) throw StateError("saved checkpoint contact is corrupt");
    h.has_history = r.pod<std::uint8_t>() != 0;
    h.shear = read_shear(r);
    r.pod(h.twist.moment);
    h.previous_normal = r.vec();
    h.point = r.vec();
    r.pod(h.closure);
    r.pod(h.area);
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
