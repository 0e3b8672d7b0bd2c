// Energy budget bookkeeping: trapezoidal works of central differences, joint energies.
#include "blockdem/world/energy_budget.hpp"

#include <algorithm>
#include <cmath>

#include "blockdem/dynamics/integrator.hpp"
#include "blockdem/world/contact_twist.hpp"

namespace blockdem {

double EnergyBudget::residual() const {
  return kinetic + elastic + friction_dissipation + damping_dissipation -
         (initial + gravity_work + load_work + boundary_work);
}

double EnergyBudget::scale() const {
  double s = 0.0;
  for (double v : {kinetic, elastic, friction_dissipation, damping_dissipation, initial,
                   gravity_work, load_work, boundary_work})
    s = std::max(s, std::abs(v));
  return s;
}

double joint_elastic_energy(const Contact& c) {
  const double normal = 0.5 * c.normal_force * c.geometry.overlap;
  const double shear =
      c.shear_stiffness > 0.0 ? 0.5 * c.shear.force.squaredNorm() / c.shear_stiffness : 0.0;
  return normal + shear;
}

void EnergyStepSums::add_block(const BlockEnergyTerms& t) {
  if (t.dynamic != 0.0) {
    gravity.add(t.gravity);
    load.add(t.load);
    damping.add(t.damping);
    kinetic.add(t.kinetic);
  } else {
    boundary.add(t.boundary);
  }
}

void EnergyStepSums::add_contact(const Contact& contact, double twist_stiffness, double slip) {
  elastic.add(joint_elastic_energy(contact));
  elastic.add(twist_elastic_energy(contact.twist.moment, twist_stiffness));
  slip_work.add(slip);
}

EnergyStepSums& EnergyStepSums::operator+=(const EnergyStepSums& other) {
  gravity += other.gravity;
  load += other.load;
  damping += other.damping;
  kinetic += other.kinetic;
  boundary += other.boundary;
  elastic += other.elastic;
  slip_work += other.slip_work;
  return *this;
}

std::vector<std::int64_t> EnergyStepSums::limbs() const {
  std::vector<std::int64_t> out;
  out.reserve(kLimbs);
  for (const ExactSum* s : {&gravity, &load, &damping, &kinetic, &boundary, &elastic, &slip_work}) {
    const auto l = s->limbs();
    out.insert(out.end(), l.begin(), l.end());
  }
  return out;
}

EnergyStepSums EnergyStepSums::from_limbs(std::span<const std::int64_t> limbs) {
  EnergyStepSums sums;
  std::size_t at = 0;
  for (ExactSum* s : {&sums.gravity, &sums.load, &sums.damping, &sums.kinetic, &sums.boundary,
                      &sums.elastic, &sums.slip_work}) {
    *s = ExactSum::from_limbs(limbs.subspan(at, ExactSum::kLimbs));
    at += ExactSum::kLimbs;
  }
  return sums;
}

void EnergyLedger::before_integration(const std::vector<Block>& blocks) {
  if (started_ && previous_.size() == blocks.size()) return;
  // The accounting starts (or starts again) at this level: no previous step to pair with.
  previous_.assign(blocks.size(), Previous{});
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    previous_[i].velocity = blocks[i].velocity;
    previous_[i].angular_velocity = blocks[i].angular_velocity;
    previous_[i].angular_momentum = blocks[i].angular_momentum;
  }
  started_ = false;
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
    const Eigen::Vector3d il = dt * b.external_force;
    const Eigen::Vector3d tl = dt * b.external_torque;
    const Eigen::Vector3d id = dt * (b.force - local_damping(b.force, u, damping));
    const Eigen::Vector3d td = dt * (b.torque - local_damping(b.torque, w, damping));
    t.dynamic = 1.0;
    t.gravity = 0.5 * u.dot(ig + p.gravity);
    t.load = 0.5 * (u.dot(il + p.load) + w.dot(tl + p.load_torque));
    t.damping = 0.5 * (u.dot(id + p.damping) + w.dot(td + p.damping_torque));
    t.kinetic = 0.5 * b.mass * u.dot(b.velocity) +
                0.25 * (w.dot(b.angular_momentum) + b.angular_velocity.dot(p.angular_momentum));
    p.gravity = ig;
    p.load = il;
    p.load_torque = tl;
    p.damping = id;
    p.damping_torque = td;
  } else {
    // A moving boundary does work -F·dx on the model through the contact force F it feels.
    const Eigen::Vector3d ic = dt * b.contact_force;
    const Eigen::Vector3d tc = dt * b.torque;
    t.boundary = 0.5 * (u.dot(ic + p.contact) + w.dot(tc + p.contact_torque));
    p.contact = ic;
    p.contact_torque = tc;
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
    e.damping_dissipation += sums.damping.value();
    e.boundary_work -= sums.boundary.value();
  }
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
  const Previous& p = previous_[i];
  for (const Eigen::Vector3d* v :
       {&p.velocity, &p.angular_velocity, &p.angular_momentum, &p.gravity, &p.load, &p.load_torque,
        &p.damping, &p.damping_torque, &p.contact, &p.contact_torque, &level_velocity_[i],
        &level_angular_velocity_[i]}) {
    for (int k = 0; k < 3; ++k) *out++ = (*v)[k];
  }
}

void EnergyLedger::set_block_record(std::size_t i, const double* in) {
  Previous& p = previous_[i];
  for (Eigen::Vector3d* v : {&p.velocity, &p.angular_velocity, &p.angular_momentum, &p.gravity,
                             &p.load, &p.load_torque, &p.damping, &p.damping_torque, &p.contact,
                             &p.contact_torque, &level_velocity_[i], &level_angular_velocity_[i]}) {
    for (int k = 0; k < 3; ++k) (*v)[k] = *in++;
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

void EnergyLedger::save_state(StateWriter& w) const {
  const EnergyBudget& e = budget_;
  for (double v : {e.kinetic, e.elastic, e.gravity_work, e.load_work, e.boundary_work,
                   e.friction_dissipation, e.damping_dissipation, e.initial})
    w.pod(v);
  w.size(previous_.size());
  for (const Previous& p : previous_) {
    for (const Eigen::Vector3d* v :
         {&p.velocity, &p.angular_velocity, &p.angular_momentum, &p.gravity, &p.load,
          &p.load_torque, &p.damping, &p.damping_torque, &p.contact, &p.contact_torque})
      w.vec(*v);
  }
  for (const auto* list : {&level_velocity_, &level_angular_velocity_}) {
    w.size(list->size());
    for (const Eigen::Vector3d& v : *list) w.vec(v);
  }
  w.pod(static_cast<std::uint8_t>(started_));
}

void EnergyLedger::load_state(StateReader& r) {
  EnergyBudget& e = budget_;
  for (double* v : {&e.kinetic, &e.elastic, &e.gravity_work, &e.load_work, &e.boundary_work,
                    &e.friction_dissipation, &e.damping_dissipation, &e.initial})
    r.pod(*v);
  previous_.resize(r.size());
  for (Previous& p : previous_) {
    for (Eigen::Vector3d* v :
         {&p.velocity, &p.angular_velocity, &p.angular_momentum, &p.gravity, &p.load,
          &p.load_torque, &p.damping, &p.damping_torque, &p.contact, &p.contact_torque})
      *v = r.vec();
  }
  for (auto* list : {&level_velocity_, &level_angular_velocity_}) {
    list->resize(r.size());
    for (Eigen::Vector3d& v : *list) v = r.vec();
  }
  started_ = r.pod<std::uint8_t>() != 0;
}

}  // namespace blockdem
