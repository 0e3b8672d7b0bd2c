// The explicit step pipeline of DESIGN section 5 and the contact force assembly of section 2.
#include "blockdem/world/world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "blockdem/contact/normal_integral.hpp"
#include "blockdem/dynamics/integrator.hpp"

namespace blockdem {
namespace {

std::uint64_t pair_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

}  // namespace

const char* to_string(ContactMode mode) {
  return mode == ContactMode::face_integrated ? "face_integrated" : "boon2012";
}

void WorldSettings::validate() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
  if (!gravity.allFinite()) fail("gravity must be finite");
  if (!(damping >= 0.0 && damping < 1.0))
    fail("damping must be in [0, 1), got " + std::to_string(damping));
  if (!(time_step >= 0.0) || !std::isfinite(time_step))
    fail("time_step must be >= 0 (0: automatic)");
  if (!(safety_factor > 0.0 && safety_factor <= 1.0)) fail("safety_factor must be in (0, 1]");
  if (!(boon2012.rounding_distance > 0.0)) fail("rounding_distance must be positive");
  if (!(max_speed > 0.0)) fail("max_speed must be positive");
  if (!(max_overlap_fraction > 0.0)) fail("max_overlap_fraction must be positive");
}

World::World(WorldSettings settings) : settings_(std::move(settings)) {
  settings_.validate();
}

int World::add_block(Block block) {
  block.index = static_cast<int>(blocks_.size());
  if (block.motion == Motion::free)
    block.angular_momentum = block.world_inertia() * block.angular_velocity;
  block.update_world_geometry();
  blocks_.push_back(std::move(block));
  return blocks_.back().index;
}

int World::add_joint_law(JointLaw law) {
  validate(law.normal);
  validate(law.shear);
  laws_.push_back(std::move(law));
  return static_cast<int>(laws_.size()) - 1;
}

void World::replace_joint_law(int index, JointLaw law) {
  if (index < 0 || index >= static_cast<int>(laws_.size()))
    throw std::invalid_argument("no joint law " + std::to_string(index));
  validate(law.normal);
  validate(law.shear);
  laws_[static_cast<std::size_t>(index)] = std::move(law);
}

void World::add_joint_rule(JointRule rule) {
  if (rule.law < 0 || rule.law >= static_cast<int>(laws_.size())) {
    throw std::invalid_argument("joint rule refers to an unknown joint law");
  }
  rules_.push_back(std::move(rule));
}

int World::find_block(const std::string& name) const {
  for (const auto& b : blocks_) {
    if (b.name == name) return b.index;
  }
  return -1;
}

int World::law_for(int a, int b) const {
  const std::string& ga = blocks_[a].group;
  const std::string& gb = blocks_[b].group;
  auto matches = [](const std::string& rule, const std::string& group) {
    return rule.empty() || rule == group;
  };
  // The last matching rule wins, so a specific rule can follow a general one.
  int found = -1;
  for (const auto& r : rules_) {
    if ((matches(r.group_a, ga) && matches(r.group_b, gb)) ||
        (matches(r.group_a, gb) && matches(r.group_b, ga))) {
      found = r.law;
    }
  }
  return found;
}

std::vector<const Contact*> World::contacts() const {
  std::vector<const Contact*> out;
  out.reserve(contacts_.size());
  for (const auto& [key, c] : contacts_) out.push_back(&c);
  std::sort(out.begin(), out.end(), [](const Contact* x, const Contact* y) {
    return std::make_pair(x->a, x->b) < std::make_pair(y->a, y->b);
  });
  return out;
}

void World::update_geometry() {
  box_min_.resize(blocks_.size());
  box_max_.resize(blocks_.size());
  for (auto& b : blocks_) {
    b.update_world_geometry();
    box_min_[b.index] = b.aabb_min;
    box_max_[b.index] = b.aabb_max;
  }
}

double World::a_priori_time_step() const {
  // Before contacts form: each block against one contact of its largest face, at the joint
  // laws' stiffness at zero closure (normal) and zero stress (shear).
  double k_law = 0.0;
  for (const auto& law : laws_) {
    k_law = std::max(k_law, normal_tangent_stiffness(law.normal, 0.0));
    k_law = std::max(k_law, shear_stiffness_estimate(law.shear, 0.0));
  }
  if (k_law == 0.0) return std::numeric_limits<double>::infinity();
  double dt = std::numeric_limits<double>::infinity();
  for (const auto& b : blocks_) {
    if (!b.is_dynamic()) continue;
    double area = 0.0;
    for (int f = 0; f < static_cast<int>(b.shape.faces().size()); ++f)
      area = std::max(area, b.shape.face_area(f));
    const double k = k_law * area;
    const double r2 = b.shape.bounding_radius() * b.shape.bounding_radius();
    dt = std::min(dt, std::sqrt(b.mass / k));
    dt = std::min(dt, std::sqrt(b.inertia.minCoeff() / (k * (r2 + area / 12.0))));
  }
  return settings_.safety_factor * dt;
}

double World::next_time_step() const {
  if (settings_.time_step > 0.0) return settings_.time_step;
  double dt = a_priori_time_step();
  if (contact_dt_ > 0.0) dt = std::min(dt, contact_dt_);
  if (!std::isfinite(dt)) {
    throw std::runtime_error(
        "cannot choose an automatic time step: no joint law has stiffness; set time_step");
  }
  return dt;
}

double World::critical_time_step() const {
  double dt = a_priori_time_step();
  if (contact_dt_ > 0.0) dt = std::min(dt, contact_dt_);
  return dt / settings_.safety_factor;
}

void World::compute_contacts(double dt) {
  // Broad phase: pairs where at least one block can move and a joint law applies.
  broad_phase_.find_pairs(
      box_min_, box_max_,
      [&](int a, int b) {
        return (blocks_[a].motion != Motion::fixed || blocks_[b].motion != Motion::fixed) &&
               (blocks_[a].is_dynamic() || blocks_[b].is_dynamic());
      },
      pairs_);

  stiffness_.assign(blocks_.size(), 0.0);
  rotational_stiffness_.assign(blocks_.size(), 0.0);
  for (auto& [key, c] : contacts_) c.law = -2;  // mark as not seen this step

  for (const auto& [ia, ib] : pairs_) {
    const int law_index = law_for(ia, ib);
    if (law_index < 0) continue;
    Block& a = blocks_[ia];
    Block& b = blocks_[ib];
    const std::uint64_t key = pair_key(ia, ib);
    auto it = contacts_.find(key);
    Contact fresh;
    Contact& c = it != contacts_.end() ? it->second : fresh;
    const double extent = 2.0 * (a.shape.bounding_radius() + b.shape.bounding_radius());
    ContactGeometry g = boon2012_contact(a.world_planes, b.world_planes, extent, settings_.boon2012,
                                         &c.narrow_cache);
    if (!g.touching || !(g.area > 0.0) || !(g.overlap > 0.0)) continue;
    if (it == contacts_.end()) {
      fresh.a = ia;
      fresh.b = ib;
      it = contacts_.emplace(key, std::move(fresh)).first;
    }
    Contact& ct = it->second;
    ct.law = law_index;
    ct.geometry = std::move(g);
    const JointLaw& law = laws_[law_index];
    const Eigen::Vector3d& n = ct.geometry.normal;

    // Normal force: σ_n(δ) A_c at x_c (DESIGN section 2 step 6), or the law integrated over
    // the contact, acting at the centre of pressure (section 3).
    ct.integrated = false;
    if (settings_.contact_mode == ContactMode::face_integrated) {
      const FaceContactGeometry fc = face_contact_geometry(
          a.world_planes, b.world_planes, ct.geometry.point, n, extent, settings_.face_contact);
      if (fc.face_type) {
        double force = 0.0, compressed = 0.0, peak = 0.0, closure = 0.0;
        Eigen::Vector3d moment = Eigen::Vector3d::Zero();
        for (const auto& cell : fc.cells) {
          const PolygonStressResultant r =
              integrate_normal_stress_over_polygon(law.normal, cell.vertices, cell.closures);
          force += r.force;
          compressed += r.compressed_area;
          peak = std::max(peak, r.peak_stress);
          if (r.centre_of_pressure) moment += r.force * *r.centre_of_pressure;
          for (double gc : cell.closures) closure = std::max(closure, gc);
        }
        if (!(force > 0.0)) {
          // Touching, but no closure anywhere to integrate: no force this step.
          contacts_.erase(it);
          continue;
        }
        ct.integrated = true;
        ct.normal_force = force;
        ct.compressed_area = compressed;
        ct.normal_stress = force / compressed;
        ct.peak_stress = peak;
        ct.peak_closure = closure;
        ct.force_point = moment / force;
      }
    }
    if (!ct.integrated) {
      ct.normal_stress = normal_stress(law.normal, ct.geometry.overlap);
      ct.normal_force = ct.normal_stress * ct.geometry.area;
      ct.force_point = ct.geometry.point;
      ct.compressed_area = ct.geometry.area;
      ct.peak_stress = ct.normal_stress;
      ct.peak_closure = ct.geometry.overlap;
    }
    const Eigen::Vector3d& xf = ct.force_point;

    // Shear: carry the stored force into the new tangent plane, then add the increment from the
    // relative velocity of the material points at x_c over the step (DESIGN section 4).
    if (ct.has_history) rotate_into_plane(ct.shear, ct.previous_normal, n);
    const Eigen::Vector3d v_rel = b.point_velocity(xf) - a.point_velocity(xf);
    ShearIncrement inc;
    inc.displacement =
        ct.has_history ? Eigen::Vector3d((v_rel - v_rel.dot(n) * n) * dt) : Eigen::Vector3d::Zero();
    inc.normal_force = ct.normal_force;
    inc.normal_stress = ct.normal_stress;
    inc.contact_area = ct.compressed_area;
    inc.normal = n;
    const ShearResult sr = update_shear(law.shear, ct.shear, inc);
    ct.sliding = sr.sliding;
    ct.previous_normal = n;
    ct.has_history = true;

    // Loads on both blocks, applied at the force point.
    const Eigen::Vector3d f = ct.force_on_b();
    b.force += f;
    b.contact_force += f;
    b.torque += (xf - b.position).cross(f);
    a.force -= f;
    a.contact_force -= f;
    a.torque -= (xf - a.position).cross(f);

    // Stiffness sums for the automatic time step: normal and shear springs k A (N/m), and for
    // rotation k A (|r|² + A/12), the second term the rocking stiffness of a spread face.
    const double kn = normal_tangent_stiffness(law.normal, ct.peak_closure) * ct.compressed_area;
    const double ks = sr.stiffness;
    const double k = kn + ks;
    const double spread = ct.compressed_area / 12.0;
    stiffness_[ia] += k;
    stiffness_[ib] += k;
    rotational_stiffness_[ia] += k * ((xf - a.position).squaredNorm() + spread);
    rotational_stiffness_[ib] += k * ((xf - b.position).squaredNorm() + spread);
  }
  std::erase_if(contacts_, [](const auto& kv) { return kv.second.law == -2; });

  contact_dt_ = 0.0;
  double dt_min = std::numeric_limits<double>::infinity();
  for (const auto& bl : blocks_) {
    if (!bl.is_dynamic() || stiffness_[bl.index] <= 0.0) continue;
    dt_min = std::min(dt_min, std::sqrt(bl.mass / stiffness_[bl.index]));
    dt_min = std::min(dt_min, std::sqrt(bl.inertia.minCoeff() / rotational_stiffness_[bl.index]));
  }
  if (std::isfinite(dt_min)) contact_dt_ = settings_.safety_factor * dt_min;
}

void World::apply_servos(double dt) {
  for (auto& b : blocks_) {
    if (b.motion != Motion::servo) continue;
    Servo& s = b.servo;
    if (s.hold) {
      b.velocity.setZero();
      b.angular_velocity.setZero();
      continue;
    }
    // Reaction: how hard the block is pushed back against its direction of travel.
    const double reaction = -b.contact_force.dot(s.axis);
    const double k = std::max(stiffness_[b.index], 1e-300);
    // Default gain: close 2% of the force error per step at the current contact stiffness.
    const double gain = s.gain > 0.0 ? s.gain : 0.02 / (k * dt);
    // Default speed limit: 1e-5 of the block size per step.
    const double vmax = s.max_speed > 0.0 ? s.max_speed : 1e-5 * b.shape.bounding_radius() / dt;
    const double v = stiffness_[b.index] > 0.0 ? gain * (s.target_force - reaction) : vmax;
    b.velocity = std::clamp(v, -vmax, vmax) * s.axis;
    b.angular_velocity.setZero();
  }
}

void World::check_divergence() {
  std::ostringstream why;
  for (const auto& b : blocks_) {
    if (!b.position.allFinite() || !b.velocity.allFinite() || !b.angular_velocity.allFinite() ||
        !b.orientation.coeffs().allFinite()) {
      why << "block '" << b.name << "' has a non-finite position or velocity";
      break;
    }
    if (b.velocity.norm() > settings_.max_speed) {
      why << "block '" << b.name << "' moves at " << b.velocity.norm() << " m/s (limit "
          << settings_.max_speed << " m/s)";
      break;
    }
  }
  if (why.str().empty()) {
    for (const auto& [key, c] : contacts_) {
      const double size =
          std::min(blocks_[c.a].shape.bounding_radius(), blocks_[c.b].shape.bounding_radius());
      if (c.geometry.overlap > settings_.max_overlap_fraction * size) {
        why << "blocks '" << blocks_[c.a].name << "' and '" << blocks_[c.b].name << "' overlap by "
            << c.geometry.overlap << " m, more than " << settings_.max_overlap_fraction
            << " of the smaller block's radius";
        break;
      }
    }
  }
  if (!why.str().empty()) {
    const std::int64_t failed_step = step_count_;
    const double failed_time = time_;
    restore_checkpoint();
    std::ostringstream msg;
    msg << "the run diverged at step " << failed_step << " (t = " << failed_time
        << " s): " << why.str() << ". The world was reset to its last good state (step "
        << step_count_
        << "). Try a smaller safety_factor or time_step, more damping, or check the joint "
           "stiffness.";
    throw DivergenceError(msg.str());
  }
}

void World::step() {
  if (!checkpoint_.valid) save_checkpoint();
  const double dt = next_time_step();
  update_geometry();
  for (auto& b : blocks_) {
    b.force = b.is_dynamic() ? Eigen::Vector3d(b.mass * settings_.gravity + b.external_force)
                             : Eigen::Vector3d::Zero();
    b.torque = b.is_dynamic() ? b.external_torque : Eigen::Vector3d::Zero();
    b.contact_force.setZero();
  }
  compute_contacts(dt);
  apply_servos(dt);
  for (auto& b : blocks_) integrate_block(b, dt, settings_.damping);
  time_ += dt;
  ++step_count_;
  last_dt_ = dt;
  check_divergence();
  if (step_count_ % 200 == 0) save_checkpoint();
}

EquilibriumMeasures World::equilibrium() const {
  EquilibriumMeasures m;
  double contact_sum = 0.0, energy = 0.0;
  for (const auto& [key, c] : contacts_) {
    contact_sum += c.force_on_b().norm();
    energy += 0.5 * c.normal_force * c.geometry.overlap;
  }
  m.mean_contact_force =
      contacts_.empty() ? 0.0 : contact_sum / static_cast<double>(contacts_.size());
  double unbalanced = 0.0;
  int free_blocks = 0;
  for (const auto& b : blocks_) {
    m.kinetic_energy += b.kinetic_energy();
    if (!b.is_dynamic()) continue;
    ++free_blocks;
    unbalanced += b.force.norm() + b.torque.norm() / b.shape.bounding_radius();
  }
  if (free_blocks == 0) {
    m.unbalanced_force_ratio = 0.0;
  } else if (m.mean_contact_force > 0.0) {
    m.unbalanced_force_ratio = unbalanced / free_blocks / m.mean_contact_force;
  } else {
    m.unbalanced_force_ratio = unbalanced > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
  }
  m.kinetic_energy_ratio =
      energy > 0.0 ? m.kinetic_energy / energy
                   : (m.kinetic_energy > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
  return m;
}

void World::save_checkpoint() {
  checkpoint_.blocks.resize(blocks_.size());
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    const Block& b = blocks_[i];
    checkpoint_.blocks[i] = {
        b.position, b.velocity, b.angular_velocity, b.angular_momentum, b.orientation,
        b.motion,   b.servo};
  }
  checkpoint_.contacts = contacts_;
  checkpoint_.time = time_;
  checkpoint_.step_count = step_count_;
  checkpoint_.valid = true;
}

void World::restore_checkpoint() {
  if (!checkpoint_.valid) return;
  for (std::size_t i = 0; i < blocks_.size() && i < checkpoint_.blocks.size(); ++i) {
    Block& b = blocks_[i];
    const BlockState& s = checkpoint_.blocks[i];
    b.position = s.position;
    b.velocity = s.velocity;
    b.angular_velocity = s.angular_velocity;
    b.angular_momentum = s.angular_momentum;
    b.orientation = s.orientation;
    b.motion = s.motion;
    b.servo = s.servo;
    b.update_world_geometry();
  }
  contacts_ = checkpoint_.contacts;
  time_ = checkpoint_.time;
  step_count_ = checkpoint_.step_count;
}

}  // namespace blockdem
