// Energy budget bookkeeping: trapezoidal works of central differences, joint energies.
#include "blockdem/world/energy_budget.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "blockdem/dynamics/integrator.hpp"
#include "blockdem/response/contact_twist.hpp"

namespace blockdem {

double EnergyBudget::residual() const {
  return kinetic + elastic + friction_dissipation + damping_dissipation + contact_damping -
         (initial + gravity_work + load_work + boundary_work);
}

double EnergyBudget::scale() const {
  double s = 0.0;
  for (double v : {kinetic, elastic, friction_dissipation, damping_dissipation, contact_damping,
                   initial, gravity_work, load_work, boundary_work})
    s = std::max(s, std::abs(v));
  return s;
}

double joint_elastic_energy(const Contact& c) {
  return c.normal_energy() + c.shear.elastic_energy;
}

void EnergyStepSums::add_block(const BlockEnergyTerms& t) {
  if (t.dynamic != 0.0) {
    gravity.add(t.gravity);
    load.add(t.load);
    damping.add(t.damping);
    kinetic.add(t.kinetic);
    water.add(t.water);
    water_next.add(t.water_next);
    seismic.add(t.seismic);
    seismic_next.add(t.seismic_next);
  } else {
    boundary.add(t.boundary);
  }
}

void EnergyStepSums::add_contact(const Contact& contact, double twist_stiffness, double slip) {
  elastic.add(joint_elastic_energy(contact));
  elastic.add(twist_elastic_energy(contact.twist.moment, twist_stiffness));
  slip_work.add(slip);
  if (const double d = contact.damping_work(); d != 0.0) contact_damping.add(d);
}

EnergyStepSums& EnergyStepSums::operator+=(const EnergyStepSums& other) {
  gravity += other.gravity;
  load += other.load;
  damping += other.damping;
  kinetic += other.kinetic;
  boundary += other.boundary;
  elastic += other.elastic;
  slip_work += other.slip_work;
  water += other.water;
  water_next += other.water_next;
  seismic += other.seismic;
  seismic_next += other.seismic_next;
  contact_damping += other.contact_damping;
  return *this;
}

std::vector<std::int64_t> EnergyStepSums::limbs() const {
  std::vector<std::int64_t> out;
  out.reserve(kLimbs);
  for (const ExactSum* s : {&gravity, &load, &damping, &kinetic, &boundary, &elastic, &slip_work,
                            &water, &water_next, &seismic, &seismic_next, &contact_damping}) {
    const auto l = s->limbs();
    out.insert(out.end(), l.begin(), l.end());
  }
  return out;
}

EnergyStepSums EnergyStepSums::from_limbs(std::span<const std::int64_t> limbs) {
  EnergyStepSums sums;
  std::size_t at = 0;
  for (ExactSum* s : {&sums.gravity, &sums.load, &sums.damping, &sums.kinetic, &sums.boundary,
                      &sums.elastic, &sums.slip_work, &sums.water, &sums.water_next, &sums.seismic,
                      &sums.seismic_next, &sums.contact_damping}) {
    *s = ExactSum::from_limbs(limbs.subspan(at, ExactSum::kLimbs));
    at += ExactSum::kLimbs;
  }
  return sums;
}

void EnergyLedger::before_integration(const std::vector<Block>& blocks) {
  if (started_ && previous_.size() == blocks.size()) {
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      if (free_[i] != static_cast<std::uint8_t>(blocks[i].is_dynamic())) swap_kind(i);
    }
  } else {
    // The accounting starts (or starts again) at this level: no previous step to pair with.
    previous_.assign(blocks.size(), Previous{});
    free_.resize(blocks.size());
    loads_.clear();
    dormant_.clear();
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      previous_[i].velocity = blocks[i].velocity;
      previous_[i].angular_velocity = blocks[i].angular_velocity;
      previous_[i].angular_momentum = blocks[i].angular_momentum;
      free_[i] = static_cast<std::uint8_t>(blocks[i].is_dynamic());
    }
    started_ = false;
  }
  // block_terms records the free blocks' load impulses Δt F_ext, Δt T_ext in loads_ (from its
  // threads, which cannot size it): made here once some block's are not +0.0 (Δt > 0).
  if (loads_.empty()) {
    for (const Block& b : blocks) {
      if (b.is_dynamic() && !(zero_bits(b.applied_force()) && zero_bits(b.applied_torque()))) {
        keep_loads();
        break;
      }
    }
  }
}

void EnergyLedger::before_integration(const std::vector<Block>& blocks, std::span<const int> only) {
  if (!(started_ && previous_.size() == blocks.size())) {
    before_integration(blocks);
    return;
  }
  // A record's bytes (full_record) do not depend on which kind it is kept as, so a block
  // whose kind is left stale here reads the same when its owner's record replaces it.
  for (const int k : only) {
    const auto i = static_cast<std::size_t>(k);
    if (free_[i] != static_cast<std::uint8_t>(blocks[i].is_dynamic())) swap_kind(i);
  }
  // loads_ only holds +0.0 until made: made for the blocks here as the whole world's pass would.
  if (loads_.empty()) {
    for (const int k : only) {
      const Block& b = blocks[static_cast<std::size_t>(k)];
      if (b.is_dynamic() && !(zero_bits(b.applied_force()) && zero_bits(b.applied_torque()))) {
        keep_loads();
        break;
      }
    }
  }
}

void EnergyLedger::keep_loads() {
  if (loads_.empty())
    loads_.assign(previous_.size(), {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()});
}

bool EnergyLedger::zero_bits(const Eigen::Vector3d& x) {
  for (int k = 0; k < 3; ++k) {
    if (std::bit_cast<std::uint64_t>(x[k]) != 0) return false;
  }
  return true;
}

bool EnergyLedger::zero_bits(const Impulses& v) {
  return std::all_of(v.begin(), v.end(), [](const Eigen::Vector3d& x) { return zero_bits(x); });
}

EnergyLedger::Impulses EnergyLedger::own_impulses(std::size_t i) const {
  const Previous& p = previous_[i];
  Impulses q = zero_impulses();
  if (free_[i] != 0) {
    q[kGravity] = p.impulse[kKeptGravity];
    q[kDamping] = p.impulse[kKeptDamping];
    q[kDampingTorque] = p.impulse[kKeptDampingTorque];
    if (!loads_.empty()) {
      q[kLoad] = loads_[i][0];
      q[kLoadTorque] = loads_[i][1];
    }
  } else {
    q[kContact] = p.impulse[0];
    q[kContactTorque] = p.impulse[1];
  }
  return q;
}

void EnergyLedger::set_own_impulses(std::size_t i, const Impulses& q) {
  Previous& p = previous_[i];
  const Eigen::Vector3d z = Eigen::Vector3d::Zero();
  if (free_[i] != 0) {
    p.impulse = {q[kGravity], q[kDamping], q[kDampingTorque]};
    if (!(zero_bits(q[kLoad]) && zero_bits(q[kLoadTorque]))) keep_loads();
    if (!loads_.empty()) loads_[i] = {q[kLoad], q[kLoadTorque]};
  } else {
    // The other kinds use the first two impulses only (block_terms, set_full_record).
    p.impulse = {q[kContact], q[kContactTorque], z};
    if (!loads_.empty()) loads_[i] = {z, z};
  }
}

void EnergyLedger::swap_kind(std::size_t i) {
  const Impulses own = own_impulses(i);
  const auto it = dormant_.find(i);
  const Impulses other = it == dormant_.end() ? zero_impulses() : it->second;
  if (zero_bits(own)) {
    if (it != dormant_.end()) dormant_.erase(it);
  } else {
    dormant_[i] = own;
  }
  free_[i] ^= 1;
  set_own_impulses(i, other);
}

void EnergyLedger::full_record(std::size_t i, Eigen::Vector3d* out) const {
  const Previous& p = previous_[i];
  out[0] = p.velocity;
  out[1] = p.angular_velocity;
  out[2] = p.angular_momentum;
  const auto it = dormant_.find(i);
  const Impulses other = it == dormant_.end() ? zero_impulses() : it->second;
  const Impulses own = own_impulses(i);
  const Impulses& free = free_[i] != 0 ? own : other;
  const Impulses& fixed = free_[i] != 0 ? other : own;
  for (std::size_t k = 0; k < 5; ++k) out[3 + k] = free[k];
  out[8] = fixed[kContact];
  out[9] = fixed[kContactTorque];
}

void EnergyLedger::set_full_record(std::size_t i, const Eigen::Vector3d* in) {
  Previous& p = previous_[i];
  p.velocity = in[0];
  p.angular_velocity = in[1];
  p.angular_momentum = in[2];
  Impulses free = zero_impulses(), fixed = zero_impulses();
  for (std::size_t k = 0; k < 5; ++k) free[k] = in[3 + k];
  fixed[kContact] = in[8];
  fixed[kContactTorque] = in[9];
  set_own_impulses(i, free_[i] != 0 ? free : fixed);
  const Impulses& other = free_[i] != 0 ? fixed : free;
  if (zero_bits(other)) {
    dormant_.erase(i);
  } else {
    dormant_[i] = other;
  }
}

void EnergyLedger::after_integration(const std::vector<Block>& blocks,
                                     const Eigen::Vector3d& gravity, double damping, double dt,
                                     EnergyStepSums contacts) {
  prepare(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i)
    contacts.add_block(block_terms(i, blocks[i], gravity, damping, dt));
  add_step(contacts);
}

void EnergyLedger::prepare(std::size_t blocks) {
  level_velocity_.resize(blocks);
  level_angular_velocity_.resize(blocks);
}

BlockEnergyTerms EnergyLedger::block_terms(std::size_t i, const Block& b,
                                           const Eigen::Vector3d& gravity, double damping,
                                           double dt) {
  BlockEnergyTerms t;
  Previous& p = previous_[i];
  const Eigen::Vector3d& u = p.velocity;          // v_{n-1/2}
  const Eigen::Vector3d& w = p.angular_velocity;  // ω_{n-1/2}
  level_velocity_[i] = 0.5 * (u + b.velocity);
  level_angular_velocity_[i] = 0.5 * (w + b.angular_velocity);
  if (b.is_dynamic()) {
    // This step's impulses; the damping force is what local_damping took off the load.
    const Eigen::Vector3d ig = dt * b.mass * gravity;
    const Eigen::Vector3d il = dt * b.applied_force();
    const Eigen::Vector3d tl = dt * b.applied_torque();
    const Eigen::Vector3d id = dt * (b.force - local_damping(b.force, u, damping));
    const Eigen::Vector3d td = dt * (b.torque - local_damping(b.torque, w, damping));
    // before_integration gave the record a free block's impulses; with loads_ empty, the load
    // impulses of the previous step and of this one are +0.0.
    auto& q = p.impulse;
    const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
    const Eigen::Vector3d& ql = loads_.empty() ? zero : loads_[i][0];
    const Eigen::Vector3d& qt = loads_.empty() ? zero : loads_[i][1];
    t.dynamic = 1.0;
    t.gravity = 0.5 * u.dot(ig + q[kKeptGravity]);
    t.load = 0.5 * (u.dot(il + ql) + w.dot(tl + qt));
    t.damping = 0.5 * (u.dot(id + q[kKeptDamping]) + w.dot(td + q[kKeptDampingTorque]));
    t.kinetic = 0.5 * b.inertial_mass() * u.dot(b.velocity) +
                0.25 * (w.dot(b.angular_momentum) + b.angular_velocity.dot(p.angular_momentum));
    // The water's and the earthquake's parts of the load's work: this step's half with
    // v_{n-1/2}, and the half with v_{n+1/2} that the next step adds (add_step).
    const Eigen::Vector3d iw = dt * b.water_force(), tw = dt * b.water_torque();
    const Eigen::Vector3d is = dt * b.seismic_force();
    t.water = 0.5 * (u.dot(iw) + w.dot(tw));
    t.water_next = 0.5 * (b.velocity.dot(iw) + b.angular_velocity.dot(tw));
    t.seismic = 0.5 * u.dot(is);
    t.seismic_next = 0.5 * b.velocity.dot(is);
    q[kKeptGravity] = ig;
    q[kKeptDamping] = id;
    q[kKeptDampingTorque] = td;
    if (!loads_.empty()) loads_[i] = {il, tl};
  } else {
    // A moving boundary does work -F·dx on the model through the contact force F it feels.
    auto& q = p.impulse;
    const Eigen::Vector3d ic = dt * b.contact_force;
    const Eigen::Vector3d tc = dt * b.torque;
    t.boundary = 0.5 * (u.dot(ic + q[0]) + w.dot(tc + q[1]));
    q[0] = ic;
    q[1] = tc;
  }
  p.velocity = b.velocity;
  p.angular_velocity = b.angular_velocity;
  p.angular_momentum = b.angular_momentum;
  return t;
}

void EnergyLedger::add_step(const EnergyStepSums& sums) {
  EnergyBudget& e = budget_;
  const double carried = started_ ? 0.0 : e.residual();
  // Each sum exact and rounded once: the same bits for any order or split of the terms.
  if (started_) {
    e.gravity_work += sums.gravity.value();
    e.load_work += sums.load.value();
    e.water_work += sums.water.value() + water_pending_;
    e.seismic_work += sums.seismic.value() + seismic_pending_;
    e.damping_dissipation += sums.damping.value();
    e.contact_damping += sums.contact_damping.value();
    e.boundary_work -= sums.boundary.value();
  }
  water_pending_ = sums.water_next.value();
  seismic_pending_ = sums.seismic_next.value();
  e.kinetic = sums.kinetic.value();
  e.elastic = sums.elastic.value();
  if (started_) {
    e.friction_dissipation += sums.slip_work.value();
  } else {
    // Start (or restart) the accounting here, keeping the residual carried so far.
    e.initial = 0.0;
    e.initial = e.residual() - carried;
    started_ = true;
  }
}

void EnergyLedger::block_record(std::size_t i, double* out) const {
  Eigen::Vector3d v[10];
  full_record(i, v);
  for (const Eigen::Vector3d& x : v) {
    for (int k = 0; k < 3; ++k) *out++ = x[k];
  }
  for (const Eigen::Vector3d* x : {&level_velocity_[i], &level_angular_velocity_[i]}) {
    for (int k = 0; k < 3; ++k) *out++ = (*x)[k];
  }
}

void EnergyLedger::set_block_record(std::size_t i, const double* in) {
  Eigen::Vector3d v[10];
  for (Eigen::Vector3d& x : v) {
    for (int k = 0; k < 3; ++k) x[k] = *in++;
  }
  set_full_record(i, v);
  for (Eigen::Vector3d* x : {&level_velocity_[i], &level_angular_velocity_[i]}) {
    for (int k = 0; k < 3; ++k) (*x)[k] = *in++;
  }
}

Eigen::Vector3d EnergyLedger::level_velocity(int i, const Block& b) const {
  const auto k = static_cast<std::size_t>(i);
  return k < level_velocity_.size() ? level_velocity_[k] : b.velocity;
}

Eigen::Vector3d EnergyLedger::level_angular_velocity(int i, const Block& b) const {
  const auto k = static_cast<std::size_t>(i);
  return k < level_angular_velocity_.size() ? level_angular_velocity_[k] : b.angular_velocity;
}

void EnergyLedger::save_state(StateWriter& w, bool dashpots) const {
  const EnergyBudget& e = budget_;
  for (double v : {e.kinetic, e.elastic, e.gravity_work, e.load_work, e.boundary_work,
                   e.friction_dissipation, e.damping_dissipation, e.initial})
    w.pod(v);
  w.size(previous_.size());
  for (std::size_t i = 0; i < previous_.size(); ++i) {
    Eigen::Vector3d v[10];
    full_record(i, v);
    for (const Eigen::Vector3d& x : v) w.vec(x);
  }
  for (const auto* list : {&level_velocity_, &level_angular_velocity_}) {
    w.size(list->size());
    for (const Eigen::Vector3d& v : *list) w.vec(v);
  }
  w.pod(static_cast<std::uint8_t>(started_));
  for (double v : {e.water_work, e.seismic_work, water_pending_, seismic_pending_}) w.pod(v);
  if (dashpots) w.pod(e.contact_damping);
}

void EnergyLedger::load_state(StateReader& r, bool dashpots) {
  EnergyBudget& e = budget_;
  for (double* v : {&e.kinetic, &e.elastic, &e.gravity_work, &e.load_work, &e.boundary_work,
                    &e.friction_dissipation, &e.damping_dissipation, &e.initial})
    r.pod(*v);
  previous_.resize(r.size());
  // Taken as free blocks' records; the next step's before_integration turns those of the other
  // blocks.
  free_.assign(previous_.size(), 1);
  loads_.clear();
  dormant_.clear();
  for (std::size_t i = 0; i < previous_.size(); ++i) {
    Eigen::Vector3d v[10];
    for (Eigen::Vector3d& x : v) x = r.vec();
    set_full_record(i, v);
  }
  for (auto* list : {&level_velocity_, &level_angular_velocity_}) {
    list->resize(r.size());
    for (Eigen::Vector3d& v : *list) v = r.vec();
  }
  started_ = r.pod<std::uint8_t>() != 0;
  for (double* v : {&e.water_work, &e.seismic_work, &water_pending_, &seismic_pending_}) r.pod(*v);
  e.contact_damping = 0.0;
  if (dashpots) r.pod(e.contact_damping);
}

}  // namespace blockdem
