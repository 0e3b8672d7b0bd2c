// The energy budget of a run: kinetic and elastic energy at a time level, the work of gravity,
// applied loads and moving boundaries, and the energy dissipated by joint slip and by damping.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <map>
#include <span>
#include <vector>

#include "blockdem/dynamics/block.hpp"
#include "blockdem/numerics/exact_sum.hpp"
#include "blockdem/world/contact.hpp"
#include "blockdem/world/state_stream.hpp"

namespace blockdem {

/// Energies at time level n (the positions at which the last step evaluated its forces) and the
/// works and dissipations accumulated since the world was built. The balance
///   kinetic + elastic + friction + damping + contact damping = initial + gravity + loads +
///   boundary
/// holds to the integration error; residual() is the difference.
struct EnergyBudget {
  /// Free blocks: Σ ½ m v_{n-1/2}·v_{n+1/2} + ¼ (ω_{n-1/2}·L_{n+1/2} + ω_{n+1/2}·L_{n-1/2}), the
  /// kinetic energy that central differences conserve exactly (J). It differs from ½ m v_n² with
  /// v_n = (v_{n-1/2} + v_{n+1/2})/2 by m |Δv|²/8, Δv the velocity change of one step.
  double kinetic = 0.0;
  /// Joints at level n: Σ of the normal springs' ∫ e(g) dA (face contacts) or ½ F_n δ (point
  /// contacts), the shear springs' |F_s|² / (2 k_s A) and the twist springs' M² / (2 k_s J) (J).
  /// The work the joints' forces do beyond these is in friction_dissipation
  /// (response/contact_energy.hpp).
  double elastic = 0.0;
  double gravity_work = 0.0;  ///< work of gravity on the free blocks (J)
  /// Work of the applied forces and torques on free blocks: the constant loads, the ground
  /// water's pressure and a pseudo-static earthquake's body force (Block::applied_force) (J).
  double load_work = 0.0;
  /// The parts of load_work done by the ground water's pressure and by a pseudo-static
  /// earthquake's body force (J), by the same trapezoidal rule: exact while the blocks keep
  /// their kind of motion.
  double water_work = 0.0;
  double seismic_work = 0.0;
  /// Work done on the model by prescribed and servo blocks through their contacts (J).
  double boundary_work = 0.0;
  /// The joints' dissipation (J): the work their forces do on the blocks that their springs do
  /// not hold, slip's -F_s·du_p and the twist's slip, and the work of forces without a potential
  /// (a shear stiffness that changes under a held force: negative when the area shrinks).
  double friction_dissipation = 0.0;
  double damping_dissipation = 0.0;  ///< work removed by local damping (J), positive
  /// Work removed by the contacts' viscous dashpots (settings contact_damping) (J), positive:
  /// the trapezoidal work of their forces, the rule of the other works.
  double contact_damping = 0.0;
  double initial = 0.0;  ///< kinetic + elastic when the accounting started (J)

  /// kinetic + elastic + friction + damping + contact damping − (initial + gravity + loads +
  /// boundary) (J).
  double residual() const;
  /// The largest magnitude among the terms, the scale for a relative residual (J).
  double scale() const;
};

/// Elastic energy of one joint's normal and shear springs (J): Contact::normal_energy() and the
/// shear spring's ShearState::elastic_energy.
double joint_elastic_energy(const Contact& contact);

/// One block's part of a step's budget sums (J).
struct BlockEnergyTerms {
  double gravity = 0.0;   ///< to gravity_work (free blocks)
  double load = 0.0;      ///< to load_work (free blocks)
  double damping = 0.0;   ///< to damping_dissipation (free blocks)
  double kinetic = 0.0;   ///< to kinetic (free blocks)
  double boundary = 0.0;  ///< subtracted from boundary_work (other blocks)
  /// To water_work and seismic_work: ½ v_{n-1/2} · (Δt F) of this step's water and seismic
  /// impulses, and (`_next`) ½ v_{n+1/2} · (Δt F), the half the next step adds (free blocks).
  double water = 0.0, water_next = 0.0, seismic = 0.0, seismic_next = 0.0;
  double dynamic = 0.0;  ///< 1: a free block (-)
};

/// A step's sums for the budget over blocks and contacts (J). Each is exact (ExactSum), so the
/// sums do not depend on the order of the terms: a world spread over processes adds each
/// process's part and reduces the parts (limbs()) to the bits of one process.
struct EnergyStepSums {
  ExactSum gravity, load, damping, kinetic;           ///< over free blocks
  ExactSum boundary;                                  ///< over the other blocks
  ExactSum elastic, slip_work;                        ///< over active contacts
  ExactSum contact_damping;                           ///< over contacts with a dashpot
  ExactSum water, water_next, seismic, seismic_next;  ///< over free blocks
  void add_block(const BlockEnergyTerms& terms);
  /// A contact's springs (normal, shear and, with `twist_stiffness` k_s J > 0, the twist spring),
  /// the work its slip dissipated in the step and its dashpot's half of this step (J).
  void add_contact(const Contact& contact, double twist_stiffness, double slip_work);
  /// Adds another part's sums (exact: the same bits for any split of the terms).
  EnergyStepSums& operator+=(const EnergyStepSums& other);
  static constexpr std::size_t kLimbs = 12 * ExactSum::kLimbs;
  /// Every sum's limbs (ExactSum::limbs), for an integer-sum reduction over processes.
  std::vector<std::int64_t> limbs() const;
  static EnergyStepSums from_limbs(std::span<const std::int64_t> limbs);
};

/// Keeps an EnergyBudget up to date, one world step at a time. Works use the trapezoidal rule of
/// central differences: in the step that evaluates forces at level n,
///   W += ½ v_{n-1/2} · (Δt_n F_n + Δt_{n-1} F_{n-1}),
/// for which the change of `kinetic` equals the work of every force to round-off (a discrete
/// form of the work-energy theorem; Hairer, Lubich & Wanner, Geometric Numerical Integration,
/// 2nd ed., 2006, ch. I.1.4, the Störmer-Verlet energy).
class EnergyLedger {
 public:
  /// Before the blocks are integrated in a step (after the servos set their velocities).
  void before_integration(const std::vector<Block>& blocks);
  /// before_integration for the blocks `only` (index order) of a world spread over processes,
  /// once the accounting has started: the other blocks' records are kept by the processes that
  /// own them (block_record, set_block_record move them). Before the start, as above, over all.
  void before_integration(const std::vector<Block>& blocks, std::span<const int> only);
  /// After integration: `dt` the step just taken, `gravity` and `damping` those it used,
  /// `contacts` the joints' energy at level n and the energy dissipated by slip in the step
  /// (EnergyStepSums::add_contact for every active contact).
  void after_integration(const std::vector<Block>& blocks, const Eigen::Vector3d& gravity,
                         double damping, double dt, EnergyStepSums contacts);
  /// after_integration in parts, for a world whose blocks are spread over processes: `prepare`
  /// once (sizes the per-block records), `block_terms` for each of its blocks (updates their
  /// records), then `add_step` with the sums over every block and contact (reduced over the
  /// processes), as after_integration adds them.
  void prepare(std::size_t blocks);
  BlockEnergyTerms block_terms(std::size_t i, const Block& b, const Eigen::Vector3d& gravity,
                               double damping, double dt);
  void add_step(const EnergyStepSums& sums);
  /// The budget computed by another process, for a step whose add_step ran there.
  void set_budget(const EnergyBudget& budget) {
    budget_ = budget;
    started_ = true;
  }
  /// A block's records (previous step, level velocities) as doubles, to move between processes.
  static constexpr std::size_t kBlockRecordDoubles = 36;
  void block_record(std::size_t i, double* out) const;
  void set_block_record(std::size_t i, const double* in);

  /// Blocks were removed: the next step starts the accounting again, carrying the residual.
  void restart() { started_ = false; }
  /// Whether a step has been accounted (save_state's last byte), and the number of per-block
  /// records (its count), for a writer of save_state's bytes in parts.
  bool started() const { return started_; }
  /// The last values save_state writes after the flag: the water and seismic works and the
  /// halves of them the next step adds (J).
  std::array<double, 4> field_terms() const {
    return {budget_.water_work, budget_.seismic_work, water_pending_, seismic_pending_};
  }
  std::size_t records() const { return previous_.size(); }
  /// The bytes its per-block records take (what a copy of the ledger holds).
  std::size_t record_bytes() const {
    return previous_.size() * sizeof(Previous) + loads_.size() * sizeof(loads_[0]) + free_.size() +
           dormant_.size() * sizeof(Impulses) +
           (level_velocity_.size() + level_angular_velocity_.size()) * sizeof(Eigen::Vector3d);
  }

  const EnergyBudget& budget() const { return budget_; }
  /// The whole ledger (budget, previous step, level velocities), for a bit-identical restart;
  /// with `dashpots` (the scenario has contact damping), the contact damping term last.
  void save_state(StateWriter& w, bool dashpots) const;
  /// Throws StateError for bytes that are not a ledger.
  void load_state(StateReader& r, bool dashpots);
  /// A boundary block's velocity over the next step, set after the step (a dynamic stage's
  /// base): the velocity its next work term pairs with its contact impulses (m/s).
  void set_boundary_velocity(std::size_t i, const Eigen::Vector3d& v) {
    if (started_ && i < previous_.size()) previous_[i].velocity = v;
  }
  /// Velocity of block i at level n, (v_{n-1/2} + v_{n+1/2}) / 2 (m/s); before the first step,
  /// the block's own.
  Eigen::Vector3d level_velocity(int i, const Block& b) const;
  /// Angular velocity of block i at level n (rad/s), likewise.
  Eigen::Vector3d level_angular_velocity(int i, const Block& b) const;

 private:
  /// A block's impulses of the previous step: a free block's Δt m g, Δt F_ext, Δt T_ext and
  /// the damping's Δt F_d, Δt T_d (N s, N m s); any other block's contact Δt F, Δt T in the
  /// first two, the rest zero. A block reads only the impulses of its own kind of motion.
  using Impulses = std::array<Eigen::Vector3d, 5>;
  static constexpr std::size_t kGravity = 0, kLoad = 1, kLoadTorque = 2, kDamping = 3,
                               kDampingTorque = 4, kContact = 0, kContactTorque = 1;
  static Impulses zero_impulses() {
    const Eigen::Vector3d z = Eigen::Vector3d::Zero();
    return {z, z, z, z, z};
  }
  /// What a block brings from the previous step: its velocities and the impulses of its kind
  /// that most blocks have, 144 bytes. A free block's load impulses Δt F_ext, Δt T_ext live
  /// apart (loads_), as in most scenes no block carries a load.
  struct Previous {
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero();          ///< v_{n-1/2} (m/s)
    Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  ///< ω_{n-1/2} (rad/s)
    Eigen::Vector3d angular_momentum = Eigen::Vector3d::Zero();  ///< L_{n-1/2} (kg m²/s)
    /// A free block's Δt m g, Δt F_d, Δt T_d; any other block's Δt F, Δt T, then zero.
    std::array<Eigen::Vector3d, 3> impulse = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                              Eigen::Vector3d::Zero()};
  };
  static constexpr std::size_t kKeptGravity = 0, kKeptDamping = 1, kKeptDampingTorque = 2;
  /// Block i's impulses of the kind in free_[i], whole (the compact record and loads_).
  Impulses own_impulses(std::size_t i) const;
  /// Stores block i's impulses of the kind in free_[i] in the compact record (and loads_).
  void set_own_impulses(std::size_t i, const Impulses& q);
  /// Makes loads_ one zero entry per block, if it is empty.
  void keep_loads();
  /// The ten vectors of block i's record in the order of block_record (velocity, angular
  /// velocity and momentum, then the free kind's five impulses and the other kind's two).
  void full_record(std::size_t i, Eigen::Vector3d* out) const;
  void set_full_record(std::size_t i, const Eigen::Vector3d* in);
  /// Block i changed its kind of motion: its impulses and those kept for the other kind trade
  /// places.
  void swap_kind(std::size_t i);
  /// Whether every impulse is +0.0 (the bits of an absent dormant_ entry).
  static bool zero_bits(const Impulses& v);
  static bool zero_bits(const Eigen::Vector3d& x);

  EnergyBudget budget_;
  std::vector<Previous> previous_;
  /// Per block, the free kind's Δt F_ext, Δt T_ext of the previous step (N s, N m s); empty
  /// while every block's are +0.0 (no block has had a load or a -0.0 in one since the
  /// accounting started): 48 bytes per block saved in the common scene.
  std::vector<std::array<Eigen::Vector3d, 2>> loads_;
  /// Per block: 1 when previous_[i].impulse holds a free block's impulses, 0 another block's.
  std::vector<std::uint8_t> free_;
  /// The impulses of the other kind for the few blocks whose motion changed while they were not
  /// all zero bits (a block read only its own kind's before: absent means zero).
  std::map<std::size_t, Impulses> dormant_;
  std::vector<Eigen::Vector3d> level_velocity_, level_angular_velocity_;
  bool started_ = false;
  /// The halves of the last step's water and seismic works that this step adds (J): the sums
  /// of ½ v_{n+1/2} · (Δt F) over the blocks, so that no block keeps its impulses for them.
  double water_pending_ = 0.0, seismic_pending_ = 0.0;
};

}  // namespace blockdem
