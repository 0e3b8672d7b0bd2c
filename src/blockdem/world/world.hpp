// The world: blocks, joint laws, persistent contacts, and the explicit time step pipeline
// (geometry -> broad phase -> narrow phase -> joint laws -> integration -> checks).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "blockdem/collision/boon2012.hpp"
#include "blockdem/collision/face_contact.hpp"
#include "blockdem/collision/shared_face.hpp"
#include "blockdem/collision/uniform_grid.hpp"
#include "blockdem/contact/normal_laws.hpp"
#include "blockdem/contact/shear_laws.hpp"
#include "blockdem/dynamics/block.hpp"
#include "blockdem/numerics/exact_sum.hpp"
#include "blockdem/response/water_pressure.hpp"
#include "blockdem/world/bolt.hpp"
#include "blockdem/world/contact.hpp"
#include "blockdem/world/contact_preload.hpp"
#include "blockdem/world/decomposition.hpp"
#include "blockdem/world/distribution.hpp"
#include "blockdem/world/energy_budget.hpp"
#include "blockdem/world/pair_slot.hpp"
#include "blockdem/world/plane_values.hpp"
#include "blockdem/world/spill_file.hpp"
#include "blockdem/world/state_stream.hpp"
#include "blockdem/world/step_scratch.hpp"

namespace blockdem {

struct StressField;
struct PairChanges;

/// How contacts are detected and turned into forces.
enum class ContactMode {
  boon2012,  ///< point contact of Boon et al. (2012): analytic centre, slice area (the paper)
  face_integrated,  ///< the joint law integrated over the contact (beyond the paper)
};

/// "boon2012" or "face_integrated".
const char* to_string(ContactMode mode);

/// A joint law: the normal and shear kernels used by one joint set.
struct JointLaw {
  std::string name;
  NormalLaw normal = LinearNormal{};
  ShearLaw shear = LinearShear{};
};

/// Which joint law acts between blocks of two groups (order-free). An empty group name matches
/// any group.
struct JointRule {
  std::string group_a;
  std::string group_b;
  int law = 0;
};

/// A joint law given anew (a stage's start): the faces of a joint set, or every face of the
/// blocks of a group, take `law`, or with `elastic` each its own law's elastic twin (the law
/// named "NAME (elastic)": the same stiffnesses, strength without limit). A contact keeps its
/// bond state, closure and shear history; a broken bond stays broken.
struct LawChange {
  int joint_set = -1;  ///< the faces of this joint set (World::set_face_sets), or -1
  std::string group;   ///< with joint_set -1: every face of this group's blocks
  int law = -1;        ///< the new law (index into joint_laws()), unless elastic
  bool elastic = false;
};

/// The suffix of an elastic twin's name (LawChange::elastic).
inline constexpr std::string_view kElasticSuffix = " (elastic)";

/// The most threads a step may be given: 64 per core of this machine, and at most 1024. Threads
/// beyond the cores only wait for each other, and each holds its own scratch buffers.
int thread_limit();

/// A pseudo-static earthquake: a constant body force k g m on every free block, g the magnitude
/// of gravity (the seismic coefficient of slope design; Wyllie & Mah, Rock Slope Engineering,
/// 4th ed., 2004, ch. 6, plane failure under a seismic coefficient).
struct SeismicLoad {
  double horizontal = 0.0;     ///< k_h (-)
  double direction_deg = 0.0;  ///< azimuth of k_h, clockwise from north (y) seen from above (deg)
  double vertical = 0.0;       ///< k_v, positive up (-)

  /// The acceleration of the body force, g (k_h (sin a, cos a, 0) + k_v e_z) (m/s^2).
  Eigen::Vector3d acceleration(double gravity) const;
  /// Throws std::invalid_argument naming the value that is not finite.
  void validate() const;
  /// The load a fraction f in [0, 1] of the way from this one to `to`, linear in the
  /// acceleration: `to` itself at f = 1 (a ramp's steps).
  SeismicLoad toward(const SeismicLoad& to, double f) const;
};

struct WorldSettings {
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();  ///< (m/s^2)
  /// Ground water: every free block's faces below the water table carry its hydrostatic
  /// pressure (joints and exposed faces alike); empty: dry.
  std::optional<GroundWater> water;
  /// While a stage's ramp brings `water` in (world/stage.hpp): the pressure is
  /// (1 - f) p_from + f p_water; empty: `water` in full.
  std::optional<WaterRamp> water_ramp;
  /// The pseudo-static earthquake's coefficients (zero: none).
  SeismicLoad seismic;
  double damping = 0.0;  ///< Cundall local damping coefficient α in [0, 1) (-)
  /// Viscous contact damping: a dashpot beside each closed contact's normal spring at this
  /// fraction ζ of critical damping, in [0, 1) (-); 0: none (response/contact_damping.hpp).
  double contact_damping = 0.0;
  double time_step = 0.0;      ///< fixed time step (s); 0 = automatic
  double safety_factor = 0.3;  ///< automatic step = factor · sqrt(m / K) (-)
  ContactMode contact_mode = ContactMode::face_integrated;
  Boon2012Settings boon2012;
  FaceContactSettings face_contact;
  /// Twisting resistance of the joints about their normals (a torsional spring k_s J with a
  /// Coulomb cap, and the stored shear force turned with the contact's spin). Empty: on in mode
  /// face_integrated, off in mode boon2012 (the paper carries no twisting moment).
  std::optional<bool> twist;
  /// A run stops as diverged when a block moves faster than this (m/s).
  double max_speed = 100.0;
  /// ... or when an overlap exceeds this fraction of the smaller block's bounding radius (-).
  double max_overlap_fraction = 0.25;
  /// A divergence checkpoint larger than this (bytes) is kept in a scratch file in $TMPDIR
  /// (else /var/tmp, else /tmp) instead of memory (World::checkpoint_file_bytes); 0: always in a
  /// file.
  std::size_t checkpoint_memory_limit = std::size_t{64} << 20;
  /// Scene origin in the user's coordinates (m): block positions inside the world are relative
  /// to it (full precision at map coordinates); outputs add it back.
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  /// Threads for the passes of a step; 0: OpenMP's default (OMP_NUM_THREADS, else every core);
  /// at most thread_limit(). Results are bit-identical for every thread count.
  int threads = 0;
  /// Processes sharing the per-pair work (an MPI run; parallel/); null: this process does all.
  /// Results are bit-identical for every number of processes.
  std::shared_ptr<PairDistribution> distribution;

  /// Whether contacts carry a twisting moment (`twist`, else the mode's default).
  bool twist_enabled() const {
    return twist.value_or(contact_mode == ContactMode::face_integrated);
  }

  /// Throws std::invalid_argument naming the setting if a value is unusable.
  void validate() const;
};

/// Thrown when the run blows up (NaN, runaway speed, excessive overlap). The world has been put
/// back to its last good state before the exception leaves step().
class DivergenceError : public std::runtime_error {
 public:
  explicit DivergenceError(const std::string& what) : std::runtime_error(what) {}
};

/// A divergence of another kind: a law or the narrow phase refused a value inside a step (a
/// stress that overflowed, a moment below zero), a numerical breakdown or a defect, never a
/// physical collapse. Thrown, as DivergenceError, after the world was reset to its last good
/// state; a stage that ends with it is `diverged` whatever the motion before it.
class StepFailure : public DivergenceError {
 public:
  explicit StepFailure(const std::string& what) : DivergenceError(what) {}
};

/// Scalar measures of how far the world is from static equilibrium.
struct EquilibriumMeasures {
  /// Mean over free blocks of |F_net| + |T_net|/R (R: bounding radius), divided by the mean
  /// contact force magnitude (-). Infinite when free blocks feel loads but no contact exists.
  double unbalanced_force_ratio = 0.0;
  double kinetic_energy = 0.0;  ///< (J)
  /// Kinetic energy over the elastic energy stored in the normal springs, Σ ½ F_n δ (-).
  double kinetic_energy_ratio = 0.0;
  double mean_contact_force = 0.0;  ///< (N)
};

class World {
 public:
  explicit World(WorldSettings settings = {});

  WorldSettings& settings() { return settings_; }
  const WorldSettings& settings() const { return settings_; }

  /// Adds a block (its index is set) and returns the index.
  int add_block(Block block);
  /// Room for `count` blocks in all, so that adding them does not reallocate (the block array of
  /// a large scene would otherwise grow to twice its size), and for as many planes' own laws
  /// and joint sets (set_face_laws, set_face_sets) as given.
  void reserve_blocks(std::size_t count, std::size_t face_laws = 0, std::size_t face_sets = 0);
  int add_joint_law(JointLaw law);
  /// Replaces joint law `index` (validated), e.g. with reduced strengths; contacts keep their
  /// history.
  void replace_joint_law(int index, JointLaw law);
  void add_joint_rule(JointRule rule);

  std::vector<Block>& blocks() { return blocks_; }
  const std::vector<Block>& blocks() const { return blocks_; }
  const std::vector<JointLaw>& joint_laws() const { return laws_; }
  /// Index of the block with this name, or -1.
  int find_block(const std::string& name) const;
  /// find_block of each name, in one walk over the blocks (an excavation lists thousands).
  std::vector<int> find_blocks(const std::vector<std::string>& names) const;
  /// Joint law index for a pair of blocks, or -1 when no rule covers their groups.
  int law_for(int a, int b) const;
  /// Gives a block's planes their own joint laws (one index per plane of its shape, -1 for a
  /// plane without one): a contact on such a face takes that law before the group rules.
  void set_face_laws(int block, std::span<const int> law_per_plane);
  /// The block's per-plane laws (empty: none).
  std::span<const int> face_laws(int block) const {
    return face_laws_.of(static_cast<std::size_t>(block));
  }
  /// Tells which joint set made each plane of a block (one index per plane of its shape, -1 for
  /// a plane of none), for law changes by joint set.
  void set_face_sets(int block, std::span<const int> set_per_plane);
  /// Gives faces their laws anew (world_laws.cpp). Throws std::invalid_argument for an unknown
  /// law or a missing elastic twin.
  void change_laws(const std::vector<LawChange>& changes);
  /// Every block's displacement outputs count from its present pose from now on.
  void reset_displacements();
  /// A gradual excavation (world_relaxation.cpp): removes the blocks and puts the forces and
  /// moments their contacts exerted on the blocks left as constant loads on those blocks, which
  /// relax() then takes down. One process only: throws std::invalid_argument on a distributed
  /// world.
  void remove_blocks_gradually(const std::vector<int>& indices);
  /// The removed blocks' loads at `remaining` (1 at the removal, 0 gone) of their value; at 0
  /// the relaxation ends.
  void relax(double remaining);
  /// Whether removed blocks' loads are still being relaxed.
  bool relaxing() const { return !relaxation_.empty(); }
  /// Removes blocks (an excavation): later blocks move down in index, their contacts are kept.
  /// A bolt tied to a removed block is removed with it (Bolt::State::removed).
  void remove_blocks(const std::vector<int>& indices);

  /// Installs a bolt (world/bolt.hpp, docs/support.md) along its line through the blocks at their
  /// present poses: from the next step it carries what moves after now. One process only.
  /// Returns its index in bolts(). Throws std::invalid_argument naming the bolt and the reason
  /// (a value, a line outside the rock or crossing no joint, a distributed world).
  int install_bolt(const BoltSpec& spec);
  /// The bolts, in installation order.
  const std::vector<Bolt>& bolts() const { return bolts_; }
  /// How many bolts are in `state`.
  std::int64_t bolt_count(Bolt::State state) const;

  /// Prestresses the joints of an in-situ stress field (world_prestress.cpp): every pair of
  /// `pairs` (the set-up's candidate pairs, sorted by (a, b)) whose blocks share a face with a
  /// joint law starts with the closure that law needs to carry the field's normal traction σ_n n
  /// over the face (exact over the polygon in mode face_integrated, at the contact point in
  /// boon2012), the field's shear force as its stored shear force and, with twist, the
  /// traction's twisting moment. Call before the first step. Returns the number of prestressed
  /// pairs. Throws std::invalid_argument naming the blocks, the point and the stress where the
  /// field is not compressive on a face.
  std::size_t prestress_joints(const StressField& field,
                               const std::vector<std::pair<int, int>>& pairs);
  /// The pairs prestressed by prestress_joints (empty: none).
  const ContactPreloads& preloads() const { return preloads_; }

  /// The narrow phase (boon2012_contact, cold) of `pairs`, sorted by (a, b), at the blocks'
  /// present poses, on every thread: `visit(k, geometry)` sees the geometry of pairs[k], from
  /// any thread and in any order. The results of the pairs that the next step evaluates are
  /// kept, and that step takes them instead of solving the same pairs again (the same bits: a
  /// pair with a block that moved or changed in between is solved again, and nothing is kept
  /// after that step). The set-up's check of the initial overlaps is such a pass. A prestressed
  /// pair (preloads()) whose second block lies beyond the first's face plane of their shared
  /// face, to a nanometre per metre, is not solved (the step solves it with that plane moved
  /// out) nor visited: it has no initial overlap.
  void prime_narrow_phase(const std::vector<std::pair<int, int>>& pairs,
                          const std::function<void(std::int64_t, const ContactGeometry&)>& visit);

  /// The current contacts, sorted by (a, b).
  std::vector<const Contact*> contacts() const;
  /// The contacts this process counts (counts_contact), sorted by (a, b): every contact of a
  /// whole world; on a distributed world that is not whole, those of the pairs it owns, exact.
  std::vector<const Contact*> counted_contacts() const;
  std::size_t contact_count() const { return active_count_; }
  /// Candidate pairs of the last step (contacts and near pairs whose narrow-phase warm start is
  /// kept), sorted by (a, b).
  std::size_t candidate_pair_count() const { return slots_.size(); }
  /// How a one-process step's broad phase gave its pairs (world_pairs.cpp), counted per step:
  /// by ranges, none changed (the store stays); by ranges, the store merged from the ranges'
  /// changes; by ranges, a list of every pair made after all (a prestressed joint without a
  /// slot that the boxes missed, a large shift); the threads' lists joined (the first step, a scene
  /// with a large box, a distributed step).
  struct PairListCounts {
    std::int64_t unchanged = 0, changed = 0, listed = 0, joined = 0;
  };
  const PairListCounts& pair_list_counts() const { return pair_list_counts_; }
  /// The number of threads a step uses (settings().threads, or OpenMP's default when 0).
  int thread_count() const;

  /// Advances one time step. Throws DivergenceError (after restoring the last good state) when
  /// the step blows up, and StepFailure when a law or the narrow phase refuses a value inside it
  /// (a std::invalid_argument of theirs; in a distributed world on every process alike, with the
  /// message of the first process that met it and the whole world reset).
  void step();

  double time() const { return time_; }  ///< (s)
  std::int64_t step_count() const { return step_count_; }
  double last_time_step() const { return last_dt_; }  ///< (s)
  /// The step the next call of step() will take (s).
  double next_time_step() const;
  /// The critical time step estimate sqrt(m/K) of the stiffest block, without the safety factor
  /// (s): from this step's contact stiffness once contacts exist, else from the joint laws.
  double critical_time_step() const;

  /// Each block's own critical step before contacts form, without the safety factor (s): the
  /// smaller of sqrt(m/K) and sqrt(I_min/K_r) for one contact over its largest face at the
  /// stiffest joint law (K = k A, K_r = k A (R² + A/12), R its bounding radius), at its true
  /// mass and inertia; infinite for a block that does not move or when no law has stiffness.
  std::vector<double> own_critical_steps() const;
  /// The median of own_critical_steps() over the free blocks (the lower middle of an even
  /// count); infinite without a free block (s).
  double median_critical_step() const;
  /// Density scaling (docs/stability.md): on, each free block's mass and moments of inertia in
  /// the equations of motion are raised (Block::mass_scale, inertia_scale; never lowered) so
  /// that its own critical step reaches median_critical_step(); the weight stays m g. Off, every
  /// scale is 1. The angular velocities are kept.
  void set_density_scaling(bool on);
  /// Whether set_density_scaling(true) scaled the blocks (the last call).
  bool density_scaled() const { return density_scaled_; }

  /// Sums exact (ExactSum): the same bits for any number of threads or processes. Collective
  /// on a distributed world that is not whole (reduce_partials).
  EquilibriumMeasures equilibrium() const;

  /// A block's state at time level n, where the last step evaluated forces and contacts (t_n =
  /// time() - last_time_step()): position and orientation stepped back by that step, velocities
  /// the mean of the half-step velocities around t_n. Outputs written from these, with the
  /// contacts and energy_budget(), describe one instant.
  struct LevelState {
    Eigen::Vector3d position;          ///< centroid (m)
    Eigen::Quaterniond orientation;    ///< body to world
    Eigen::Vector3d velocity;          ///< (m/s)
    Eigen::Vector3d angular_velocity;  ///< world frame (rad/s)
  };
  LevelState level_state(int block) const;
  /// t_n (s); see level_state.
  double level_time() const { return time_ - last_dt_; }
  /// The energy budget at level n since the world was built (world/energy_budget.hpp).
  const EnergyBudget& energy_budget() const { return energy_.budget(); }
  /// Block i's velocity was set after the step (a dynamic stage's base): the energy ledger pairs
  /// the block's next work term with it, the velocity that moved it over the step.
  void note_boundary_velocity(int i) {
    energy_.set_boundary_velocity(static_cast<std::size_t>(i),
                                  blocks_[static_cast<std::size_t>(i)].velocity);
  }

  /// The ground water's force on the free blocks at level n, summed (N): with a level water
  /// table and every block below it, ρ_w g times their volume, upward. Collective like
  /// reduce_partials on a distributed world that is not whole.
  Eigen::Vector3d total_water_force() const;

  /// Bonds (cohesion, tensile strength) broken since the world was built, counted in the step
  /// they break (a bond that breaks and then separates still counts).
  std::int64_t broken_bond_count() const { return broken_bonds_; }
  /// The same per joint set and cause: entry k + 1 holds joint set k's (World::set_face_sets),
  /// entry 0 those of faces of no set; [0] broke in tension, [1] in shear. A bond's set is that
  /// of the face it joins (the most nearly coincident pair of opposite planes of its blocks).
  const std::vector<std::array<std::int64_t, 2>>& broken_bonds_by_set() const {
    return broken_by_set_;
  }

  /// Saves / restores the block states and contact histories (the "last good state"). The
  /// snapshot is compact: block states and, per contact, its pair and shear history; a restore
  /// re-derives the contacts' geometry and normal forces at the restored pose.
  /// One larger than settings().checkpoint_memory_limit goes to a scratch file (SpillFile) and
  /// is read back from it to restore or to write a restart file; throws
  /// std::filesystem::filesystem_error (the folder and the reason) if that file cannot be
  /// written, the last checkpoint kept.
  void save_checkpoint();
  void restore_checkpoint();
  /// Whether the last checkpoint is kept in a scratch file, and its size there (bytes; 0: in
  /// memory).
  std::size_t checkpoint_file_bytes() const {
    return checkpoint_.file ? checkpoint_.file->size() : 0;
  }

  /// The complete dynamic state (block states, every pair slot with its history and warm
  /// start, counters, the divergence checkpoint) as bytes, for restart files (world_state.cpp).
  void save_state(StateWriter& out) const;
  /// Loads save_state's bytes into a world built from the same scenario (blocks removed since
  /// are removed again, matched by name); the run then continues bit-identically. Throws
  /// StateError when the state does not fit this world.
  void load_state(StateReader& in);
  /// Collective with settings().distribution (every process at the same step): save_state's
  /// bytes, in order and in pieces, to `emit` on process 0 (the others call nothing), as a whole
  /// world would write them, without making the world whole on any process: each process sends
  /// the blocks and pairs it keeps exact, merged to process 0 in bounded chunks (merge_to_root;
  /// docs/restart.md). Without a distribution, or on a whole world: save_state's bytes at once.
  void save_state_to_root(const std::function<void(std::string_view)>& emit);
  /// With settings().distribution: the owner process of each block (empty before the first
  /// step) and this process's figures of the distributed work.
  const std::vector<int>& block_owners() const { return decomposition_.block_owners(); }
  const DistributionStats& distribution_stats() const { return decomposition_.stats(); }

  /// With settings().distribution, a step leaves exact only this process's blocks and pairs and
  /// its ghosts (docs/scaling.md). Collective: gathers every block's state and every pair slot to
  /// every process, bit for bit those of one process. Nothing to do when already complete.
  void synchronize();
  /// Whether every block and pair slot here is exact (always without a distribution).
  bool replica_complete() const { return decomposition_.replica_complete(); }
  /// Off (the default): a distributed step ends with synchronize(). On: the caller calls
  /// synchronize() on every process before it reads more than the time and step counters.
  void set_deferred_replica(bool on) { decomposition_.set_deferred_replica(on); }

  // Global measures without the whole world: each process takes its part (the blocks and the
  // contacts it counts) and the parts are reduced exactly (docs/scaling.md), so the result is
  // the same bits as on one process. On a whole world (one process, or after synchronize())
  // every block and contact counts and the reductions do nothing.
  /// Whether block i is this process's to count: every block of a whole world, else its own.
  bool counts_block(std::size_t i) const { return decomposition_.counts_block(i); }
  /// Whether a contact is this process's to count: every contact of a whole world, else its own.
  bool counts_contact(const Contact& contact) const;
  /// Collective when the world is distributed and not whole (every process at the same point,
  /// with the same sizes); nothing to do otherwise. Each sum becomes the sum over the processes
  /// (exact), each maximum the maximum and each count the total.
  void reduce_partials(std::span<ExactSum> sums, std::span<double> maxima,
                       std::span<std::int64_t> counts) const;
  /// Collective like reduce_partials: every process's indices, merged in increasing order.
  std::vector<int> gather_indices(const std::vector<int>& mine) const;
  /// Collective like reduce_partials: process 0 receives every process's records (`count` of
  /// them here: `record(k, text)` appends record k, whose key `key(k)` increases with k) in
  /// chunks of about kMergeChunkBytes, and calls `emit` for each record of every process in
  /// increasing key order (a K-way merge), ties in rank order; the other processes call nothing.
  /// Outputs written from rows keyed by block index or by (a, b) come out in one process's order
  /// without the whole world on any process. On a whole world: this process's records, in order.
  void merge_to_root(std::size_t count, const std::function<std::uint64_t(std::size_t)>& key,
                     const std::function<void(std::size_t, std::string&)>& record,
                     const std::function<void(std::string_view)>& emit) const;
  /// Collective like reduce_partials. On a distributed world that is not whole: each resting
  /// block's contact force (N) as one process sums it (World::sum_resting_loads' order), on
  /// every process, by block index (no process keeps it between refreshes). Empty otherwise:
  /// every block's Block::contact_force is exact.
  std::vector<std::pair<int, Eigen::Vector3d>> resting_contact_forces() const;
  /// The bound on a process's part of one round of merge_to_root (B).
  static constexpr std::size_t kMergeChunkBytes = std::size_t{1} << 20;

 private:
  // The pair store's records (world/pair_slot.hpp).
  using NarrowWarmStart = blockdem::NarrowWarmStart;
  using PairSlot = blockdem::PairSlot;
  /// An index beyond 16 bits (a pair of blocks with more than 32 767 planes) leaves the warm
  /// start empty: the next call starts cold.
  static NarrowWarmStart pack_warm_start(const Boon2012Cache& cache);
  static Boon2012Cache unpack_warm_start(const NarrowWarmStart& warm);
  /// A contact state formed during the per-pair pass, waiting for settle_contacts().
  struct PendingContact {
    std::size_t slot = 0;
    Contact contact;
  };

  // The step's passes (world/step.cpp), in order.
  void refresh_blocks(StepScratch& s);
  void contact_passes(StepScratch& s);
  void find_step_pairs(StepScratch& s);
  /// One process's broad phase in ranges of blocks, each range's pairs compared with its
  /// slots where they are found (world_pairs.cpp). Returns false, having done nothing, where
  /// there are no slots yet or the grid has a large box. Else `changes` holds each range's
  /// change of the store (a slot holding an open bond keeps its pair, as keep_open_bonds, and
  /// so does a prestressed joint's slot), and `missed` the prestressed joints that neither a
  /// pair nor a slot covers, sorted.
  bool find_pairs_by_range(int threads, const std::vector<char>& breakable, PairChanges& changes,
                           std::vector<std::pair<int, int>>& missed);
  /// pairs_: every pair of the store changed by `changes`, in order.
  void list_changed_pairs(const PairChanges& changes);
  /// The store rearranged by `changes` (merge_changes, else the list merged serially).
  void merge_pair_changes(const PairChanges& changes);
  /// pairs_ with the prestressed joints' pairs that it misses (sorted) merged in.
  void merge_joints(const std::vector<std::pair<int, int>>& missed);
  /// A new candidate pair's slot.
  PairSlot fresh_slot(int a, int b) const;
  /// The slots' group rules' laws looked up again where the rules changed since.
  void refresh_group_laws();
  void evaluate_step_pairs(StepScratch& s);
  void scatter_step_loads(StepScratch& s);
  void integrate_blocks(StepScratch& s);
  void check_step(StepScratch& s);
  void keep_divergence_checkpoint();
  /// After the contacts' loads: the bolts' (world_support.cpp), and their stiffness in the
  /// automatic time step. The bolts are solved on s.threads threads, their loads added in order.
  void apply_bolts(const StepScratch& s);
  /// After a removal: the bolts' blocks by their new indices (-1: removed).
  void renumber_bolts(const std::vector<int>& new_index);
  /// A block whose pairs this process finds and keeps: its own, not resting.
  bool keeps_pairs_of(int i) const { return decomposition_.keeps_pairs_of(i); }

  void update_geometry(int threads);
  /// One block's refresh at the start of a step: its world planes and box, and the loads that
  /// do not come from contacts.
  void refresh_block(std::size_t i);
  /// The blocks' boxes for the broad phase: compact arrays (48 bytes per block) that the grid
  /// reads many times per box; read in place from the blocks (576-byte records then) the step
  /// at 1e5 blocks was about 4 % slower (cache misses). A block keeps no box of its own.
  BoxView block_boxes() const { return BoxView(box_min_, box_max_); }
  /// A pair the step evaluates: at least one block can move (boxes of fixed blocks alone meet
  /// no contact that matters).
  bool steps_pair(int a, int b) const {
    return (blocks_[a].motion != Motion::fixed || blocks_[b].motion != Motion::fixed) &&
           (blocks_[a].is_dynamic() || blocks_[b].is_dynamic());
  }
  // world_primed.cpp: the results of prime_narrow_phase, taken by the first step.
  void take_primed_slots();
  void drop_primed();
  /// The pair's narrow phase with its warm start, or its primed result.
  /// `planes_a`: A's world planes, or a prestressed pair's with its face plane moved out.
  ContactGeometry narrow_phase(PairSlot& slot, std::span<const Halfspace> planes_a, const Block& a,
                               const Block& b, double extent) const;
  /// `breakable`: per joint law, whether its strength can break (keeps_bond_pair).
  void keep_open_bonds(const std::vector<char>& breakable);
  /// Per joint law, whether its strength can break.
  std::vector<char> breakable_laws() const;
  /// The face blocks a and b share at their present poses (collision/shared_face.hpp), with
  /// the joint law it takes: A's face's, else B's, else `group_law` (-1: none). `gap` (m): how
  /// far the faces may be pressed into each other. A polygon of area below 1e-6 of the smaller
  /// block's bounding radius squared (two blocks meeting along an edge) is no face.
  std::optional<SharedFace> shared_face_of(const Block& a, const Block& b, double gap = 0.0) const;
  /// Whether any joint law's strength can break (a bond can matter).
  bool any_breakable_law() const;
  int shared_face_law(int a, int b, const SharedFace& face, int group_law) const;
  /// Whether a slot's pair stays a candidate after its boxes part: an open bond, or a closed
  /// one that can open into tension (`breakable`: per law, whether its strength can break).
  bool keeps_bond_pair(const PairSlot& s, const std::vector<char>& breakable) const;
  void merge_pairs();
  /// The contact a slot starts a step with when it has no state: no history, its bond.
  Contact fresh_contact(const PairSlot& slot) const;
  /// The slot's contact state (the slot must have one).
  Contact& contact_of(const PairSlot& slot) {
    return contacts_[static_cast<std::size_t>(slot.contact)];
  }
  const Contact& contact_of(const PairSlot& slot) const {
    return contacts_[static_cast<std::size_t>(slot.contact)];
  }
  void evaluate_pair(PairSlot& slot, Contact& ct, double dt, bool advance_shear) const;
  /// Last step's force point, normal and compressed area of a contact, which an open bond starts
  /// from: taken before this step's geometry replaces them, or (null) the contact's own.
  struct OpenBondStart {
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    double area = 0.0;
  };
  bool evaluate_open_bond(PairSlot& slot, Contact& ct, const OpenBondStart* start, double dt,
                          bool advance_shear) const;
  /// The per-pair pass over every slot (or those with nonzero `only`), in parallel; new contact
  /// states go to pending_. Returns the exception of the first failing slot in order, if any.
  std::exception_ptr evaluate_slots(double dt, bool advance_shear, int threads,
                                    const std::vector<char>* only = nullptr);
  /// evaluate_slots, then settle_contacts; throws the first failure.
  void evaluate_pairs(double dt, bool advance_shear, int threads);
  /// After a per-pair pass: contacts_ holds the states of the active slots, in slot order (a
  /// sorted merge of the kept states and pending_, in place).
  void settle_contacts();
  bool settle_contacts_parallel(int threads);
  void settle_contacts_serial();
  /// Drops the states of slots that no longer exist (after slots were removed), keeping order.
  void compact_contacts();
  /// `counted`: the contacts' energy terms, contact and broken-bond counts and the first too-deep
  /// overlap of these slots only (per slot, nonzero: count; a distributed step's own pairs), and
  /// loads summed only on the blocks of keeps_loads_ (the others' are not read), without the
  /// time-step minimum (the step takes it over its own blocks); null: every slot and block.
  void scatter_loads(const std::vector<char>* counted = nullptr);
  /// `only`: servos of these blocks only (per block, nonzero: apply); null: every block.
  void apply_servos(double dt, const std::vector<char>* only = nullptr);
  void check_divergence();
  /// Resets the world to the divergence checkpoint and throws StepFailure for a step whose
  /// contact pass refused a value (`why`, the check's message).
  [[noreturn]] void fail_step(const std::string& why);
  double a_priori_time_step() const;
  /// The stiffest joint law's stiffness at zero closure and zero stress (Pa/m).
  double law_stiffness_bound() const;
  /// Block i's own critical steps before contacts form, translation and rotation (s), for a
  /// contact stiffness k_law per unit area; `inertial`: with the density-scaled mass and moments.
  std::array<double, 2> a_priori_block_steps(std::size_t i, double k_law, bool inertial) const;
  /// The first block (index order) with a non-finite state or a speed above max_speed, or the
  /// block count when none.
  std::size_t first_diverged_block() const;
  bool density_scaled_ = false;

  WorldSettings settings_;
  std::vector<Block> blocks_;
  /// Per block, what the a-priori time step reads of its rigid shape: kept beside the block
  /// records so that the step's pass over every block does not visit the shapes.
  struct APrioriShape {
    double max_face_area = 0.0;   ///< the largest face's area (m^2)
    double radius_squared = 0.0;  ///< the shape's bounding radius, squared (m^2)
  };
  std::vector<APrioriShape> a_priori_shape_;
  std::vector<JointLaw> laws_;
  std::vector<JointRule> rules_;
  int rules_version_ = 0;          ///< counts add_joint_rule calls
  int slots_rules_version_ = 0;    ///< rules_version_ when the slots' laws were looked up
  std::vector<PairSlot> slots_;    ///< candidate pairs, sorted by (a, b)
  std::vector<Contact> contacts_;  ///< the states of the slots that have one, in slot order
  /// New contact states of the last per-pair pass, per run of pending_run_ slots, in slot order.
  std::vector<std::vector<PendingContact>> pending_;
  std::size_t pending_run_ = 1;
  std::size_t active_count_ = 0;
  std::int64_t broken_bonds_ = 0;                           ///< see broken_bond_count()
  std::vector<std::array<std::int64_t, 2>> broken_by_set_;  ///< see broken_bonds_by_set()
  /// This step's broken bonds per set and cause, of this process's pairs (scatter_loads).
  std::vector<std::array<std::int64_t, 2>> step_breaks_;
  /// Counts this step's broken bonds (slots with `broke`, of `counted` pairs) into step_breaks_.
  void tally_step_breaks(const std::vector<char>* counted);
  /// Adds a table of broken bonds per set and cause (rows as broken_by_set_'s) to it.
  void add_step_breaks(const std::vector<std::array<std::int64_t, 2>>& breaks);
  /// The joint set of the face blocks a and b are bonded across (-1: none).
  int bonded_face_set(int a, int b) const;
  /// Rows of broken_bonds_by_set: one per joint set any block's face has, plus one.
  std::size_t break_table_rows() const;
  std::int64_t overlap_violation_ = -1;  ///< first slot whose overlap is too deep, or -1
  UniformGrid broad_phase_;   ///< chosen over sweep and prune by bench/bench_broad_phase.cpp
  PlaneValues face_laws_;     ///< per block, one law per plane (empty: none)
  PlaneValues face_sets_;     ///< per block, one joint set per plane (empty: none)
  ContactPreloads preloads_;  ///< joints prestressed at set-up
  /// A gradual excavation's loads on a block: its applied loads before, and the removed blocks'.
  struct Relaxation {
    int block = -1;
    Eigen::Vector3d base_force, base_torque;  ///< (N), (N m)
    Eigen::Vector3d force, torque;            ///< (N), (N m)
  };
  std::vector<Relaxation> relaxation_;
  std::vector<Bolt> bolts_;  ///< installed bolts (world_support.cpp)
  /// Each bolt's loads of this step, kept between steps for their room (world_support.cpp).
  std::vector<std::vector<BoltLoad>> bolt_loads_;
  std::vector<std::pair<int, int>> pairs_;
  PairListCounts pair_list_counts_;

  // Per-block stiffness sums of this step, for the automatic time step.
  std::vector<double> stiffness_, rotational_stiffness_;
  double contact_dt_ = 0.0;
  // scatter_loads: its runs of slots (first block and first slot of each, and an end), the slots
  // of each run whose block b lies in a later run, and this step's contact energy sums.
  std::vector<std::size_t> scatter_first_, scatter_begin_;
  std::vector<std::vector<std::size_t>> scatter_cross_;
  EnergyStepSums contact_energy_;
  // Contact damping: whether the last step's contacts had dashpots, and the second halves of
  // their trapezoidal work this step's velocities give (evaluate_slots, for scatter_loads).
  // After a restart, the halves its checkpoint kept, for the first step.
  bool dashpots_last_step_ = false;
  ExactSum dashpot_carried_, dashpot_restored_;
  /// The energy (J) a contact's dashpot of the last step dissipates with the velocities now: the
  /// second half of its trapezoidal work (response/contact_damping.hpp); and its sum over the
  /// contacts, which a checkpoint keeps.
  double dashpot_carried(const Contact& ct) const;
  ExactSum dashpot_pending() const;

  /// The world's spread over processes (settings_.distribution); empty on one process.
  Decomposition decomposition_;
  friend class Decomposition;

  double time_ = 0.0;
  std::int64_t step_count_ = 0;
  double last_dt_ = 0.0;
  EnergyLedger energy_;

  // prime_narrow_phase's results until the next step takes them: the slots that step would
  // open, with their warm starts after the cold solve, and per slot the contact's slice area, 0
  // where the narrow phase found no contact, or kNotPrimed (a contact's point is its warm
  // start's last point; normal and overlap follow from it). The blocks' poses and shapes at the
  // time, to see that none changed.
  struct PrimedPose {
    Eigen::Vector3d position;
    Eigen::Quaterniond orientation;
    Polyhedron shape;
  };
  static constexpr double kNotPrimed = -1.0;
  std::vector<PairSlot> primed_slots_;
  std::vector<double> primed_area_;  ///< per slot, while the step may take them
  std::vector<PrimedPose> primed_poses_;
  Boon2012Settings primed_settings_;
  std::int64_t primed_step_ = 0;  ///< step_count_ when primed

  /// A block's state in the checkpoint; its motion is kept apart (Checkpoint::motions): here it
  /// would take 16 bytes of a 144-byte record, the quaternion's alignment padding the rest.
  struct BlockState {
    Eigen::Vector3d position, velocity, angular_velocity, angular_momentum;
    Eigen::Quaterniond orientation;
  };
  /// Every block's world-frame box (see block_boxes), refreshed with its world planes: one
  /// entry per block from add_block on (restart files write them with the block).
  std::vector<Eigen::Vector3d> box_min_, box_max_;
  /// What a contact needs to go on after a restore (its geometry is re-derived).
  struct ContactHistory {
    int a = -1, b = -1;
    int law = -1;
    bool has_history = false;
    ShearState shear;
    TwistState twist;
    Eigen::Vector3d previous_normal = Eigen::Vector3d::UnitZ();
    // An open bond's state, which no geometry re-derives: its point, closure and area.
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    double closure = 0.0;
    double area = 0.0;
  };
  /// What a checkpoint keeps of a slot: its contact's history, or the bond of a pair without a
  /// contact state; nothing for a pair that a fresh slot reproduces (no force, no history, no
  /// bond).
  std::optional<ContactHistory> checkpoint_history(const PairSlot& s) const;
  /// A kept slot without a contact state: its pair, law and bond (16 bytes where its
  /// ContactHistory takes 152). Its ContactHistory is `history()`: every other field default.
  struct BondHistory {
    std::int32_t a = -1, b = -1;
    std::int32_t law = -1;
    BondState bond = BondState::intact;
    ContactHistory history() const;
    /// The record of `h` when `h` is such a ContactHistory bit for bit (no contact state's
    /// fields set), else nothing.
    static std::optional<BondHistory> of(const ContactHistory& h);
  };
  struct Checkpoint {
    std::vector<BlockState> blocks;
    std::vector<Motion> motions;  ///< per block, as blocks
    /// The servos that are not Servo{} bit for bit, by block index in increasing order; every
    /// other block's is Servo{} (a servo in each BlockState would add 64 bytes per block).
    std::vector<std::pair<std::size_t, Servo>> servos;
    /// The kept slots, each in one of the two lists, each list sorted by (a, b): those with a
    /// contact state, and the bonds of candidate pairs without one (most of a rock mass's
    /// pairs, whose bonds are intact from the start). for_each_kept_slot walks both in order.
    std::vector<ContactHistory> contacts;
    std::vector<BondHistory> bonds;
    template <class F>
    void for_each_kept_slot(F&& f) const;
    std::size_t kept_slots() const { return contacts.size() + bonds.size(); }
    double time = 0.0;
    std::int64_t step_count = 0;
    std::int64_t broken_bonds = 0;
    std::vector<std::array<std::int64_t, 2>> broken_by_set;
    std::vector<Bolt> bolts;
    EnergyLedger energy;
    bool valid = false;
    /// A distributed part (world/decomposition_replica.cpp): `blocks` and `motions` hold this
    /// process's blocks (indices in `part_blocks`), `servos` and `contacts` its own; synchronize()
    /// gathers.
    std::vector<int> part_blocks;
    std::vector<double> part_resting;  ///< the resting blocks' loads' terms (gather_checkpoint)
    bool partial = false;
    /// Set: the blocks, kept slots and energy are not in the vectors above (left empty) but in
    /// this file, in save_divergence_checkpoint's layout (a checkpoint larger than
    /// settings().checkpoint_memory_limit). The header fields, bolts and broken_by_set stay here.
    std::shared_ptr<const SpillFile> file;
    /// Empties the vectors that a checkpoint in a file leaves empty, giving back their memory.
    void release_records();
  } checkpoint_;
  /// Appends checkpoint_history(s), if any, to the list it belongs in.
  void keep_slot(const PairSlot& s, std::vector<ContactHistory>& contacts,
                 std::vector<BondHistory>& bonds) const;
  // save_state's parts (world_state.cpp), shared with save_state_to_root: block i's record with
  // its loads (force, torque, contact force), a slot's record with its contact state (null: the
  // fresh contact it restarts from), the counters after the stiffness sums, and the divergence
  // checkpoint.
  void save_block(StateWriter& w, std::size_t i, const Eigen::Vector3d* loads) const;
  void save_slot(StateWriter& w, const PairSlot& s, const Contact* contact) const;
  void save_counters(StateWriter& w, std::int64_t overlap_violation) const;
  void save_divergence_checkpoint(StateWriter& w) const;
  /// What a checkpoint of these records takes in memory (bytes), to weigh against
  /// settings_.checkpoint_memory_limit.
  static std::size_t checkpoint_bytes(std::size_t blocks, std::size_t with_state,
                                      std::size_t bond_only, const EnergyLedger& energy);
  /// A checkpoint read into memory (a restart file's) larger than the limit: to its file, as
  /// save_checkpoint would have kept it.
  void spill_loaded_checkpoint();
  /// What save_divergence_checkpoint writes for a checkpoint save_checkpoint would take now, from
  /// the world itself (`kept`: the slots checkpoint_history keeps), for a checkpoint in a file.
  void write_checkpoint_of_world(StateWriter& w, std::size_t kept) const;
  // load_state's sections, in the order save_state writes them (world_state.cpp).
  void load_blocks(StateReader& r);
  void load_counters(StateReader& r);
  void load_slots(StateReader& r);
  void load_divergence_checkpoint(StateReader& r);
};

template <class F>
void World::Checkpoint::for_each_kept_slot(F&& f) const {
  std::size_t c = 0, k = 0;
  while (c < contacts.size() || k < bonds.size()) {
    const bool take_contact =
        k == bonds.size() ||
        (c < contacts.size() && (contacts[c].a < bonds[k].a ||
                                 (contacts[c].a == bonds[k].a && contacts[c].b < bonds[k].b)));
    if (take_contact) {
      f(contacts[c++]);
    } else {
      f(bonds[k++].history());
    }
  }
}

}  // namespace blockdem
