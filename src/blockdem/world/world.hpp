// The world: blocks, joint laws, persistent contacts, and the explicit time step pipeline
// (geometry -> broad phase -> narrow phase -> joint laws -> integration -> checks).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "blockdem/collision/boon2012.hpp"
#include "blockdem/collision/broad_phase.hpp"
#include "blockdem/collision/face_contact.hpp"
#include "blockdem/contact/normal_laws.hpp"
#include "blockdem/contact/shear_laws.hpp"
#include "blockdem/dynamics/block.hpp"
#include "blockdem/world/contact.hpp"

namespace blockdem {

/// How contacts are detected and turned into forces.
enum class ContactMode {
  boon2012,  ///< point contact of Boon et al. (2012): analytic centre, slice area (the paper)
  face_integrated,  ///< the joint law integrated over the contact (DESIGN section 3)
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

struct WorldSettings {
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();  ///< (m/s^2)
  double damping = 0.0;        ///< Cundall local damping coefficient α in [0, 1) (-)
  double time_step = 0.0;      ///< fixed time step (s); 0 = automatic
  double safety_factor = 0.3;  ///< automatic step = factor · sqrt(m / K) (-)
  ContactMode contact_mode = ContactMode::face_integrated;
  Boon2012Settings boon2012;
  FaceContactSettings face_contact;
  /// A run stops as diverged when a block moves faster than this (m/s).
  double max_speed = 100.0;
  /// ... or when an overlap exceeds this fraction of the smaller block's bounding radius (-).
  double max_overlap_fraction = 0.25;

  /// Throws std::invalid_argument naming the setting if a value is unusable.
  void validate() const;
};

/// Thrown when the run blows up (NaN, runaway speed, excessive overlap). The world has been put
/// back to its last good state before the exception leaves step().
class DivergenceError : public std::runtime_error {
 public:
  explicit DivergenceError(const std::string& what) : std::runtime_error(what) {}
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
  /// Joint law index for a pair of blocks, or -1 when no rule covers their groups.
  int law_for(int a, int b) const;

  /// The current contacts (order unspecified).
  std::vector<const Contact*> contacts() const;
  std::size_t contact_count() const { return contacts_.size(); }

  /// Advances one time step. Throws DivergenceError (after restoring the last good state).
  void step();

  double time() const { return time_; }  ///< (s)
  std::int64_t step_count() const { return step_count_; }
  double last_time_step() const { return last_dt_; }  ///< (s)
  /// The step the next call of step() will take (s).
  double next_time_step() const;
  /// The critical time step estimate sqrt(m/K) of the stiffest block, without the safety factor
  /// (s): from this step's contact stiffness once contacts exist, else from the joint laws.
  double critical_time_step() const;

  EquilibriumMeasures equilibrium() const;

  /// Saves / restores the block states and contact histories (the "last good state").
  void save_checkpoint();
  void restore_checkpoint();

 private:
  void update_geometry();
  void compute_contacts(double dt);
  void apply_servos(double dt);
  void check_divergence();
  double a_priori_time_step() const;

  WorldSettings settings_;
  std::vector<Block> blocks_;
  std::vector<JointLaw> laws_;
  std::vector<JointRule> rules_;
  std::unordered_map<std::uint64_t, Contact> contacts_;
  SweepAndPrune broad_phase_;
  std::vector<std::pair<int, int>> pairs_;
  std::vector<Eigen::Vector3d> box_min_, box_max_;

  // Per-block stiffness sums of this step, for the automatic time step.
  std::vector<double> stiffness_, rotational_stiffness_;
  double contact_dt_ = 0.0;

  double time_ = 0.0;
  std::int64_t step_count_ = 0;
  double last_dt_ = 0.0;

  struct BlockState {
    Eigen::Vector3d position, velocity, angular_velocity, angular_momentum;
    Eigen::Quaterniond orientation;
    Motion motion;
    Servo servo;
  };
  struct Checkpoint {
    std::vector<BlockState> blocks;
    std::unordered_map<std::uint64_t, Contact> contacts;
    double time = 0.0;
    std::int64_t step_count = 0;
    bool valid = false;
  } checkpoint_;
};

}  // namespace blockdem
