// The world's set-up, the step pipeline (geometry, contacts, integration, checks) and the
// checkpoint; the contact passes are in world_contacts.cpp.
#include "blockdem/world/world.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <string_view>
#include <thread>
#include <unordered_map>
#include <vector>

#include "blockdem/dynamics/integrator.hpp"
#include "blockdem/numerics/number_text.hpp"
#include "blockdem/numerics/shares.hpp"
#include "blockdem/numerics/units.hpp"
#include "blockdem/world/pass_support.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace blockdem {
namespace {

// The passes read every step over every block (the a-priori time step, the divergence search)
// run on the threads from this many blocks; below, on the calling thread with nothing allocated.
constexpr std::int64_t kBlocksForThreads = 8192;

double largest_face_area(const Polyhedron& shape) {
  double area = 0.0;
  for (int f = 0; f < static_cast<int>(shape.faces().size()); ++f)
    area = std::max(area, shape.face_area(f));
  return area;
}

}  // namespace

const char* to_string(ContactMode mode) {
  switch (mode) {
    case ContactMode::boon2012:
      return "boon2012";
    case ContactMode::face_integrated:
      return "face_integrated";
  }
  return "boon2012";
}

void WorldSettings::validate() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
  if (!gravity.allFinite()) fail("gravity must be finite");
  if (!(damping >= 0.0 && damping < 1.0))
    fail("damping must be in [0, 1), got " + number_text(damping));
  if (!(time_step >= 0.0) || !std::isfinite(time_step))
    fail("time_step must be >= 0 (0: automatic)");
  if (!(safety_factor > 0.0 && safety_factor <= 1.0)) fail("safety_factor must be in (0, 1]");
  if (!(boon2012.rounding_distance > 0.0)) fail("rounding_distance must be positive");
  if (!(max_speed > 0.0)) fail("max_speed must be positive");
  if (!(max_overlap_fraction > 0.0)) fail("max_overlap_fraction must be positive");
  if (!(contact_damping >= 0.0 && contact_damping < 1.0))
    fail("contact_damping must be in [0, 1), got " + number_text(contact_damping));
  if (contact_damping > 0.0 && distribution)
    fail("contact_damping runs on one process (run without mpirun)");
  if (threads < 0) fail("threads must be >= 0 (0: every core)");
  seismic.validate();
  if (water && !(water->density > 0.0 && std::isfinite(water->density)))
    fail("water_density must be positive and finite, got " + number_text(water->density));
  if (threads > thread_limit())
    fail("threads must be at most " + std::to_string(thread_limit()) +
         " (64 per core of this machine, at most 1024), got " + std::to_string(threads));
}

Eigen::Vector3d SeismicLoad::acceleration(double gravity) const {
  if (horizontal == 0.0 && vertical == 0.0) return Eigen::Vector3d::Zero();
  const double a = deg_to_rad(direction_deg);
  return gravity * Eigen::Vector3d(horizontal * std::sin(a), horizontal * std::cos(a), vertical);
}

SeismicLoad SeismicLoad::toward(const SeismicLoad& to, double f) const {
  if (f >= 1.0) return to;
  const double a = deg_to_rad(direction_deg), b = deg_to_rad(to.direction_deg);
  // The horizontal coefficient as a vector (east, north), interpolated.
  const double east = (1.0 - f) * horizontal * std::sin(a) + f * to.horizontal * std::sin(b);
  const double north = (1.0 - f) * horizontal * std::cos(a) + f * to.horizontal * std::cos(b);
  SeismicLoad s;
  s.horizontal = std::hypot(east, north);
  s.direction_deg = s.horizontal > 0.0 ? rad_to_deg(std::atan2(east, north)) : to.direction_deg;
  s.vertical = (1.0 - f) * vertical + f * to.vertical;
  return s;
}

void SeismicLoad::validate() const {
  if (!std::isfinite(horizontal)) throw std::invalid_argument("seismic_kh must be finite");
  if (!std::isfinite(direction_deg))
    throw std::invalid_argument("seismic_direction_deg must be finite");
  if (!std::isfinite(vertical)) throw std::invalid_argument("seismic_kv must be finite");
}

int thread_limit() {
  const auto cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return std::min(1024, 64 * cores);
}

World::World(WorldSettings settings) : settings_(std::move(settings)) {
  settings_.validate();
}

int World::add_block(Block block) {
  block.index = static_cast<int>(blocks_.size());
  if (block.motion == Motion::free)
    block.angular_momentum = block.world_inertia() * block.angular_velocity;
  box_min_.resize(blocks_.size());
  box_max_.resize(blocks_.size());
  box_min_.emplace_back();
  box_max_.emplace_back();
  block.update_world_geometry(box_min_.back(), box_max_.back());
  const double radius = block.shape.bounding_radius();
  a_priori_shape_.push_back({largest_face_area(block.shape), radius * radius});
  blocks_.push_back(std::move(block));
  return blocks_.back().index;
}

void World::reserve_blocks(std::size_t count, std::size_t face_laws, std::size_t face_sets) {
  blocks_.reserve(count);
  if (face_laws > 0) face_laws_.reserve(count, face_laws);
  if (face_sets > 0) face_sets_.reserve(count, face_sets);
  a_priori_shape_.reserve(count);
  box_min_.reserve(count);
  box_max_.reserve(count);
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
  ++rules_version_;
}

int World::find_block(const std::string& name) const {
  for (const auto& b : blocks_) {
    if (b.name == name) return b.index;
  }
  return -1;
}

std::vector<int> World::find_blocks(const std::vector<std::string>& names) const {
  std::unordered_map<std::string_view, std::vector<std::size_t>> wanted;
  wanted.reserve(names.size());
  for (std::size_t k = 0; k < names.size(); ++k) wanted[names[k]].push_back(k);
  std::vector<int> found(names.size(), -1);
  for (const auto& b : blocks_) {
    const auto it = wanted.find(b.name);
    if (it == wanted.end()) continue;
    // The first block of a name, as find_block.
    for (const std::size_t k : it->second)
      if (found[k] < 0) found[k] = b.index;
  }
  return found;
}

int World::law_for(int a, int b) const {
  const std::string& ga = blocks_[a].group();
  const std::string& gb = blocks_[b].group();
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

int World::thread_count() const {
#ifdef _OPENMP
  return settings_.threads > 0 ? settings_.threads : std::max(1, omp_get_max_threads());
#else
  return 1;
#endif
}

std::vector<const Contact*> World::contacts() const {
  decomposition_.require_replica("contacts");
  std::vector<const Contact*> out;
  out.reserve(active_count_);
  for (const auto& s : slots_) {
    if (s.active) out.push_back(&contact_of(s));
  }
  return out;
}

void World::refresh_block(std::size_t i) {
  Block& b = blocks_[i];
  b.update_world_geometry(box_min_[i], box_max_[i]);
  // The water's pressure over the faces below the table and the earthquake's body force, at
  // this pose (free blocks only: the others' loads are never read).
  if (b.is_dynamic()) {
    const double g = settings_.gravity.norm();
    const WaterLoad water = block_water_load(settings_.water, settings_.water_ramp, g, b.shape,
                                             b.rotation(), b.position);
    b.set_field_loads(water.force, water.torque, b.mass * settings_.seismic.acceleration(g));
  }
  b.force = b.is_dynamic() ? Eigen::Vector3d(b.mass * settings_.gravity + b.applied_force())
                           : Eigen::Vector3d::Zero();
  b.torque = b.is_dynamic() ? b.applied_torque() : Eigen::Vector3d::Zero();
  b.contact_force.setZero();
}

void World::update_geometry(int threads) {
  const std::int64_t n = static_cast<std::int64_t>(blocks_.size());
  box_min_.resize(blocks_.size());
  box_max_.resize(blocks_.size());
  const auto refresh = [&](std::int64_t i) {
    const auto k = static_cast<std::size_t>(i);
    if (k + pass_support::kPrefetchShape < blocks_.size())
      pass_support::prefetch_shape(blocks_[k + pass_support::kPrefetchShape]);
    if (k + pass_support::kPrefetchArrays < blocks_.size())
      pass_support::prefetch_shape_arrays(blocks_[k + pass_support::kPrefetchArrays]);
    refresh_block(k);
  };
  // No parallel region for one thread: a team of one still costs a futex call at its end.
  if (threads > 1 && n > 256) {
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::int64_t i = 0; i < n; ++i) refresh(i);
  } else {
    for (std::int64_t i = 0; i < n; ++i) refresh(i);
  }
}

double World::law_stiffness_bound() const {
  double k_law = 0.0;
  for (const auto& law : laws_) {
    k_law = std::max(k_law, normal_tangent_stiffness(law.normal, 0.0));
    k_law = std::max(k_law, shear_stiffness_estimate(law.shear, 0.0));
  }
  return k_law;
}

std::array<double, 2> World::a_priori_block_steps(std::size_t i, double k_law,
                                                  bool inertial) const {
  const Block& b = blocks_[i];
  // Shapes are rigid: the largest face area and the bounding radius are kept per block from
  // add_block.
  const APrioriShape& shape = a_priori_shape_[i];
  const double area = shape.max_face_area;
  const double k = k_law * area;
  const double mass = inertial ? b.inertial_mass() : b.mass;
  const double moment = inertial ? b.inertial_moments().minCoeff() : b.inertia.minCoeff();
  return {std::sqrt(mass / k), std::sqrt(moment / (k * (shape.radius_squared + area / 12.0)))};
}

double World::a_priori_time_step() const {
  // Before contacts form: each block against one contact of its largest face, at the joint
  // laws' stiffness at zero closure (normal) and zero stress (shear). Read every step: over the
  // threads for a large world, each its share's minimum, then the least of those (a minimum is
  // exact in any order: the same bits for any thread count).
  const double k_law = law_stiffness_bound();
  if (k_law == 0.0) return std::numeric_limits<double>::infinity();
  const auto n = static_cast<std::int64_t>(blocks_.size());
  const auto least_in = [&](std::int64_t begin, std::int64_t end) {
    double dt = std::numeric_limits<double>::infinity();
    for (std::int64_t i = begin; i < end; ++i) {
      if (!blocks_[static_cast<std::size_t>(i)].is_dynamic()) continue;
      const std::array<double, 2> own =
          a_priori_block_steps(static_cast<std::size_t>(i), k_law, true);
      dt = std::min(dt, own[0]);
      dt = std::min(dt, own[1]);
    }
    return dt;
  };
  const int threads = thread_count();
  if (threads <= 1 || n < kBlocksForThreads) return settings_.safety_factor * least_in(0, n);
  const std::int64_t shares = threads;
  std::vector<double> part(static_cast<std::size_t>(shares));
  for_each_share(shares, n, threads, [&](std::int64_t k, std::int64_t begin, std::int64_t end) {
    part[static_cast<std::size_t>(k)] = least_in(begin, end);
  });
  return settings_.safety_factor * *std::min_element(part.begin(), part.end());
}

std::vector<double> World::own_critical_steps() const {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> out(blocks_.size(), inf);
  const double k_law = law_stiffness_bound();
  if (k_law == 0.0) return out;
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    if (!blocks_[i].is_dynamic()) continue;
    const std::array<double, 2> own = a_priori_block_steps(i, k_law, false);
    out[i] = std::min(own[0], own[1]);
  }
  return out;
}

double World::median_critical_step() const {
  std::vector<double> steps;
  for (const double dt : own_critical_steps()) {
    if (std::isfinite(dt)) steps.push_back(dt);
  }
  if (steps.empty()) return std::numeric_limits<double>::infinity();
  // The lower middle of an even count: the smaller target, the fewer blocks scaled.
  const auto mid = steps.begin() + static_cast<std::ptrdiff_t>((steps.size() - 1) / 2);
  std::nth_element(steps.begin(), mid, steps.end());
  return *mid;
}

void World::set_density_scaling(bool on) {
  const double k_law = law_stiffness_bound();
  const double target = on ? median_critical_step() : 0.0;
  const bool scales = on && k_law > 0.0 && std::isfinite(target);
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    Block& b = blocks_[i];
    double mass_scale = 1.0, inertia_scale = 1.0;
    if (scales && b.is_dynamic()) {
      // Raised so that the block's own steps reach the target; never lowered, so that no block
      // accelerates faster under its weight than it would unscaled.
      const std::array<double, 2> own = a_priori_block_steps(i, k_law, false);
      mass_scale = std::max(1.0, (target / own[0]) * (target / own[0]));
      inertia_scale = std::max(1.0, (target / own[1]) * (target / own[1]));
    }
    // The angular velocity is kept: the angular momentum follows the moments.
    if (inertia_scale != b.inertia_scale) b.angular_momentum *= inertia_scale / b.inertia_scale;
    b.mass_scale = mass_scale;
    b.inertia_scale = inertia_scale;
  }
  density_scaled_ = scales;
}

double World::next_time_step() const {
  if (settings_.time_step > 0.0) return settings_.time_step;
  double dt = a_priori_time_step();
  if (contact_dt_ > 0.0) dt = std::min(dt, contact_dt_);
  if (!std::isfinite(dt)) {
    const bool any_free =
        std::any_of(blocks_.begin(), blocks_.end(), [](const Block& b) { return b.is_dynamic(); });
    throw std::invalid_argument(
        any_free ? "cannot choose an automatic time step: no joint law has stiffness; set "
                   "time_step"
                 : "cannot choose an automatic time step: no block is free to move (every block "
                   "is fixed or prescribed); set time_step");
  }
  return dt;
}

double World::critical_time_step() const {
  double dt = a_priori_time_step();
  if (contact_dt_ > 0.0) dt = std::min(dt, contact_dt_);
  return dt / settings_.safety_factor;
}

void World::apply_servos(double dt, const std::vector<char>* only) {
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    // The flag first: a block another process holds needs no visit to its record.
    if (only && (*only)[i] == 0) continue;
    Block& b = blocks_[i];
    if (b.motion != Motion::servo) continue;
    const Servo& s = b.servo();
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

std::size_t World::first_diverged_block() const {
  const auto diverged = [&](const Block& b) {
    return !b.position.allFinite() || !b.velocity.allFinite() || !b.angular_velocity.allFinite() ||
           !b.orientation.coeffs().allFinite() || b.velocity.norm() > settings_.max_speed;
  };
  const std::size_t n = blocks_.size();
  const auto first_in = [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      if (diverged(blocks_[i])) return i;
    }
    return n;
  };
  // Read every step: over the threads for a large world, each share's first, then the first of
  // those (the same block for any thread count).
  const int threads = thread_count();
  if (threads <= 1 || static_cast<std::int64_t>(n) < kBlocksForThreads) return first_in(0, n);
  const std::int64_t shares = threads;
  std::vector<std::size_t> part(static_cast<std::size_t>(shares));
  for_each_share(shares, static_cast<std::int64_t>(n), threads,
                 [&](std::int64_t k, std::int64_t begin, std::int64_t end) {
                   part[static_cast<std::size_t>(k)] =
                       first_in(static_cast<std::size_t>(begin), static_cast<std::size_t>(end));
                 });
  return *std::min_element(part.begin(), part.end());
}

void World::check_divergence() {
  std::ostringstream why;
  const std::size_t first = first_diverged_block();
  if (first < blocks_.size()) {
    const Block& b = blocks_[first];
    if (!b.position.allFinite() || !b.velocity.allFinite() || !b.angular_velocity.allFinite() ||
        !b.orientation.coeffs().allFinite()) {
      why << "block '" << b.name << "' has a non-finite position or velocity";
    } else {
      why << "block '" << b.name << "' moves at " << b.velocity.norm() << " m/s (limit "
          << settings_.max_speed << " m/s)";
    }
  }
  if (why.str().empty() && overlap_violation_ >= 0) {
    // The first too-deep contact in (a, b) order, found by the load scatter.
    const Contact& c = contact_of(slots_[static_cast<std::size_t>(overlap_violation_)]);
    why << "blocks '" << blocks_[c.a].name << "' and '" << blocks_[c.b].name << "' overlap by "
        << c.geometry.overlap << " m, more than " << settings_.max_overlap_fraction
        << " of the smaller block's radius";
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

void World::fail_step(const std::string& why) {
  const std::int64_t failed_step = step_count_ + 1;
  const double failed_time = time_;
  restore_checkpoint();
  std::ostringstream msg;
  msg << "the run failed at step " << failed_step << " (t = " << failed_time
      << " s): a check inside the step refused a value: " << why
      << ". The world was reset to its last good state (step " << step_count_
      << "). A numerical breakdown the divergence checks did not catch first, or a defect of "
         "blockdem (please report it with the scenario): try a smaller safety_factor or "
         "time_step, more damping, or check the joint laws.";
  throw StepFailure(msg.str());
}

EquilibriumMeasures World::equilibrium() const {
  EquilibriumMeasures m;
  // Exact sums over the blocks and contacts this process counts, reduced over the processes of
  // a distributed world: the result does not depend on the order or the split of the terms.
  enum { kContactForce, kElastic, kKinetic, kUnbalanced };
  std::array<ExactSum, 4> sums;
  for (const auto& s : slots_) {
    if (!s.active) continue;
    const Contact& c = contact_of(s);
    if (!counts_contact(c)) continue;
    sums[kContactForce].add(c.force_on_b().norm());
    sums[kElastic].add(0.5 * c.normal_force * c.geometry.overlap);
  }
  std::array<std::int64_t, 1> free_count{0};
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    if (!counts_block(i)) continue;
    const Block& b = blocks_[i];
    sums[kKinetic].add(b.kinetic_energy());
    if (!b.is_dynamic()) continue;
    ++free_count[0];
    // A blocked degree of freedom (a roller, plane motion) carries a reaction, not an unbalance.
    Eigen::Vector3d f = b.force, t = b.torque;
    for (int k = 0; k < 3; ++k) {
      if (b.blocked_translation[k]) f[k] = 0.0;
      if (b.blocked_rotation[k]) t[k] = 0.0;
    }
    sums[kUnbalanced].add(f.norm() + t.norm() / b.shape.bounding_radius());
  }
  reduce_partials(sums, {}, free_count);
  const double contact_sum = sums[kContactForce].value(), energy = sums[kElastic].value();
  const double unbalanced = sums[kUnbalanced].value();
  const auto free_blocks = static_cast<double>(free_count[0]);
  m.kinetic_energy = sums[kKinetic].value();
  m.mean_contact_force =
      active_count_ == 0 ? 0.0 : contact_sum / static_cast<double>(active_count_);
  if (free_count[0] == 0) {
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
  decomposition_.require_replica("save_checkpoint");
  // Every slot that a fresh one would not reproduce: contacts, contacts with a history, and
  // candidate pairs whose bond is intact or broken (a pair that reappears later is unbonded).
  // Counted first and reserved exactly: near pairs with an intact bond count too, and a vector
  // grown by doubling would briefly hold three times the records.
  // A slot without a contact state keeps its bond alone, in 16 bytes (most of a rock mass's
  // pairs: intact from the start, never touching).
  std::size_t with_state = 0, bond_only = 0;
  for (const auto& s : slots_) {
    if (!checkpoint_history(s)) continue;
    (s.contact < 0 ? bond_only : with_state) += 1;
  }
  if (checkpoint_bytes(blocks_.size(), with_state, bond_only, energy_) >
      settings_.checkpoint_memory_limit) {
    // A large checkpoint (a million-block rock mass's held 0.7 GB of memory) goes to a scratch
    // file, written from the world as save_divergence_checkpoint would write it: read back only to
    // roll back or to write a restart file. The last checkpoint stays until this one is written.
    auto file = SpillFile::write(
        [&](StateWriter& w) { write_checkpoint_of_world(w, with_state + bond_only); });
    checkpoint_.release_records();
    checkpoint_.file = std::move(file);
  } else {
    checkpoint_.file.reset();
    checkpoint_.blocks.resize(blocks_.size());
    checkpoint_.motions.resize(blocks_.size());
    checkpoint_.servos.clear();
    for (std::size_t i = 0; i < blocks_.size(); ++i) {
      const Block& b = blocks_[i];
      checkpoint_.blocks[i] = {b.position, b.velocity, b.angular_velocity, b.angular_momentum,
                               b.orientation};
      checkpoint_.motions[i] = b.motion;
      if (!same_bits(b.servo(), Servo{})) checkpoint_.servos.emplace_back(i, b.servo());
    }
    std::vector<ContactHistory>().swap(checkpoint_.contacts);
    std::vector<BondHistory>().swap(checkpoint_.bonds);
    checkpoint_.contacts.reserve(with_state);
    checkpoint_.bonds.reserve(bond_only);
    for (const auto& s : slots_) keep_slot(s, checkpoint_.contacts, checkpoint_.bonds);
    checkpoint_.energy = energy_;
  }
  checkpoint_.time = time_;
  checkpoint_.step_count = step_count_;
  checkpoint_.broken_bonds = broken_bonds_;
  checkpoint_.broken_by_set = broken_by_set_;
  checkpoint_.bolts = bolts_;
  checkpoint_.valid = true;
}

std::size_t World::checkpoint_bytes(std::size_t blocks, std::size_t with_state,
                                    std::size_t bond_only, const EnergyLedger& energy) {
  return blocks * (sizeof(BlockState) + sizeof(Motion)) + with_state * sizeof(ContactHistory) +
         bond_only * sizeof(BondHistory) + energy.record_bytes();
}

void World::spill_loaded_checkpoint() {
  Checkpoint& cp = checkpoint_;
  if (cp.file || checkpoint_bytes(cp.blocks.size(), cp.contacts.size(), cp.bonds.size(),
                                  cp.energy) <= settings_.checkpoint_memory_limit)
    return;
  auto file = SpillFile::write([&](StateWriter& w) { save_divergence_checkpoint(w); });
  cp.release_records();
  cp.file = std::move(file);
}

void World::Checkpoint::release_records() {
  std::vector<BlockState>().swap(blocks);
  std::vector<Motion>().swap(motions);
  std::vector<std::pair<std::size_t, Servo>>().swap(servos);
  std::vector<ContactHistory>().swap(contacts);
  std::vector<BondHistory>().swap(bonds);
  energy = EnergyLedger{};
}

std::optional<World::ContactHistory> World::checkpoint_history(const PairSlot& s) const {
  if (s.contact < 0) {
    // No contact state: only the bond of the pair.
    if (s.bond == BondState::unbonded) return std::nullopt;
    ContactHistory h;
    h.a = s.a;
    h.b = s.b;
    h.law = s.group_law;
    h.shear.bond = s.bond;
    return h;
  }
  const Contact& c = contact_of(s);
  if (!s.active && !c.has_history && c.shear.bond == BondState::unbonded) return std::nullopt;
  return ContactHistory{c.a,
                        c.b,
                        c.law,
                        c.has_history,
                        c.shear,
                        c.twist,
                        c.previous_normal(),
                        c.force_point(),
                        c.geometry.overlap,
                        c.compressed_area()};
}

void World::keep_slot(const PairSlot& s, std::vector<ContactHistory>& contacts,
                      std::vector<BondHistory>& bonds) const {
  const auto h = checkpoint_history(s);
  if (!h) return;
  if (s.contact < 0) {
    bonds.push_back({h->a, h->b, h->law, h->shear.bond});
  } else {
    contacts.push_back(*h);
  }
}

World::ContactHistory World::BondHistory::history() const {
  ContactHistory h;
  h.a = a;
  h.b = b;
  h.law = law;
  h.shear.bond = bond;
  return h;
}

std::optional<World::BondHistory> World::BondHistory::of(const ContactHistory& h) {
  const BondHistory r{h.a, h.b, h.law, h.shear.bond};
  const ContactHistory d = r.history();
  const auto same = [](const auto& x, const auto& y) {
    static_assert(sizeof(x) == sizeof(y));
    return std::memcmp(&x, &y, sizeof(x)) == 0;
  };
  if (h.has_history || !same(h.shear.force, d.shear.force) ||
      !same(h.shear.elastic_displacement, d.shear.elastic_displacement) ||
      !same(h.shear.plastic_slip, d.shear.plastic_slip) ||
      !same(h.shear.elastic_energy, d.shear.elastic_energy) ||
      !same(h.twist.moment, d.twist.moment) || !same(h.previous_normal, d.previous_normal) ||
      !same(h.point, d.point) || !same(h.closure, d.closure) || !same(h.area, d.area))
    return std::nullopt;
  return r;
}

void World::restore_checkpoint() {
  if (!checkpoint_.valid) return;
  // A checkpoint in a file is read back for the restore (the store, replaced below, let go
  // first), then left there again.
  const std::shared_ptr<const SpillFile> file = checkpoint_.file;
  if (file) {
    std::vector<PairSlot>().swap(slots_);
    std::vector<Contact>().swap(contacts_);
    file->read([&](StateReader& r) {
      load_divergence_checkpoint(r);
      checkpoint_.energy.load_state(r, settings_.contact_damping > 0.0);
    });
  }
  std::size_t servo = 0;  // the next of checkpoint_.servos
  for (std::size_t i = 0; i < blocks_.size() && i < checkpoint_.blocks.size(); ++i) {
    Block& b = blocks_[i];
    const BlockState& s = checkpoint_.blocks[i];
    b.position = s.position;
    b.velocity = s.velocity;
    b.angular_velocity = s.angular_velocity;
    b.angular_momentum = s.angular_momentum;
    b.orientation = s.orientation;
    b.motion = checkpoint_.motions[i];
    const auto& servos = checkpoint_.servos;
    b.set_servo(servo < servos.size() && servos[servo].first == i ? servos[servo++].second
                                                                  : Servo{});
    b.update_world_geometry(box_min_[i], box_max_[i]);
  }
  // Contacts come back with their shear history; geometry and normal forces are re-derived at
  // the restored pose (the narrow-phase warm starts of the other pairs are dropped).
  slots_.clear();
  slots_.reserve(checkpoint_.kept_slots());
  contacts_.clear();
  checkpoint_.for_each_kept_slot([&](const ContactHistory& h) {
    PairSlot s;
    s.a = h.a;
    s.b = h.b;
    s.group_law = law_for(h.a, h.b);
    s.bond = h.shear.bond;
    if (h.has_history) {
      Contact c;
      c.a = h.a;
      c.b = h.b;
      c.law = h.law;
      c.shear = h.shear;
      c.twist = h.twist;
      c.has_history = true;
      c.geometry.point = h.point;
      c.geometry.overlap = h.closure;
      // The geometry is re-derived before anything reads these, but an open bond, which goes
      // on from its point and area.
      c.set_force_values(h.point, h.area, 0.0, 0.0, 0.0);
      c.set_previous_normal(h.previous_normal);
      s.contact = static_cast<std::int32_t>(contacts_.size());
      contacts_.push_back(c);
    }
    slots_.push_back(s);
  });
  slots_rules_version_ = rules_version_;
  evaluate_pairs(0.0, false, thread_count());
  active_count_ = 0;
  for (const auto& s : slots_) active_count_ += s.active ? 1 : 0;
  overlap_violation_ = -1;
  time_ = checkpoint_.time;
  step_count_ = checkpoint_.step_count;
  broken_bonds_ = checkpoint_.broken_bonds;
  broken_by_set_ = checkpoint_.broken_by_set;
  bolts_ = checkpoint_.bolts;
  if (file) {
    energy_ = std::move(checkpoint_.energy);
    checkpoint_.release_records();
    checkpoint_.file = file;
  } else {
    energy_ = checkpoint_.energy;
  }
  // The checkpoint is whole on every process: so is the world now.
  decomposition_.reset_whole();
}

World::LevelState World::level_state(int block) const {
  const Block& b = blocks_[static_cast<std::size_t>(block)];
  // Positions moved by Δt v_{n+1/2} in the last step; the orientation by the rotation Δt ω_{n+1/2}
  // (exact for prescribed motion, to O(Δt²) for a free block's two-stage update).
  LevelState s;
  s.position = b.position - last_dt_ * b.velocity;
  s.orientation =
      (rotation_quaternion(-last_dt_ * b.angular_velocity) * b.orientation).normalized();
  s.velocity = energy_.level_velocity(block, b);
  s.angular_velocity = energy_.level_angular_velocity(block, b);
  return s;
}

// The collective operations of a distributed world (world/decomposition.hpp), which on one
// process or a whole world read the world as it is.
void World::synchronize() {
  decomposition_.synchronize(*this);
}

void World::save_state_to_root(const std::function<void(std::string_view)>& emit) {
  decomposition_.save_state_to_root(*this, emit);
}

std::vector<const Contact*> World::counted_contacts() const {
  return decomposition_.counted_contacts(*this);
}

bool World::counts_contact(const Contact& contact) const {
  return decomposition_.counts_contact(*this, contact);
}

void World::reduce_partials(std::span<ExactSum> sums, std::span<double> maxima,
                            std::span<std::int64_t> counts) const {
  decomposition_.reduce_partials(*this, sums, maxima, counts);
}

std::vector<int> World::gather_indices(const std::vector<int>& mine) const {
  return decomposition_.gather_indices(*this, mine);
}

void World::merge_to_root(std::size_t count, const std::function<std::uint64_t(std::size_t)>& key,
                          const std::function<void(std::size_t, std::string&)>& record,
                          const std::function<void(std::string_view)>& emit) const {
  decomposition_.merge_to_root(*this, count, key, record, emit);
}

std::vector<std::pair<int, Eigen::Vector3d>> World::resting_contact_forces() const {
  return decomposition_.resting_contact_forces(*this);
}

}  // namespace blockdem
