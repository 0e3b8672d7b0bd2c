// Watches a stage for a mechanism (blocks that keep accelerating or move past a limit) and keeps
// the energy balance that tells a physical collapse from a numerical blow-up.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "blockdem/world/world.hpp"

namespace blockdem {

/// When a stage counts as failed by a mechanism. Defaults in docs/stability.md.
struct MechanismCriteria {
  /// A free block that moves farther than this from where it was at the stage start is part of a
  /// mechanism (m); 0: half the bounding radius of the smallest free block.
  double displacement_limit = 0.0;
  /// A mechanism also forms when the largest block speed has grown at this many successive
  /// convergence checks (outside a ramp) while some block has moved by half the limit (-).
  std::int64_t growth_checks = 100;

  void validate() const;  ///< throws std::invalid_argument naming the field
};

/// What the monitor saw (the last observation).
struct MotionReport {
  double max_displacement = 0.0;    ///< largest displacement of a free block since the start (m)
  double displacement_limit = 0.0;  ///< the limit in force (m)
  double max_speed = 0.0;           ///< (m/s)
  double kinetic_energy = 0.0;      ///< (J)
  /// Work done by gravity and external forces on the free blocks since the stage start (J).
  double load_work = 0.0;
  /// Elastic energy in the normal springs at the stage start, ½ Σ F_n δ (J): an upper bound of
  /// what the joints can release for the stiffening laws (linear, exponential). For a stage that
  /// starts the world's first step, whose joints take their forces in that step (an in-situ
  /// prestress, blocks placed overlapping), the energy the world's ledger starts from instead:
  /// the joints' elastic energy and the blocks' kinetic energy after that step
  /// (EnergyBudget::initial). NaN until the monitor has observed a stepped world.
  double elastic_energy_start = 0.0;
  /// Time step over the critical estimate sqrt(m/K) of the stiffest block (-).
  double time_step_ratio = 0.0;
  int growing_checks = 0;          ///< successive checks at which the largest speed grew
  std::vector<int> moving_blocks;  ///< free blocks past a tenth of the limit
  bool mechanism = false;          ///< the criteria say: a mechanism has formed
};

/// Observes a world during one stage.
class MotionMonitor {
 public:
  MotionMonitor(const World& world, const MechanismCriteria& criteria);
  /// A monitor read back from save_state's bytes (restart files).
  explicit MotionMonitor(StateReader& in);
  void save_state(StateWriter& out) const;

  /// Updates the report from the world's state; `ramping` while a load is still being raised
  /// (speeds then grow for a stable model too).
  void observe(const World& world, bool ramping);
  const MotionReport& report() const { return report_; }
  /// True when the kinetic energy exceeds what the loads and the joints could have supplied
  /// (by more than 10% and 1e-12 J): energy created by the integrator.
  bool energy_created() const;

 private:
  MechanismCriteria criteria_;
  std::vector<Eigen::Vector3d> start_;
  MotionReport report_;
  double previous_speed_ = 0.0;
};

/// How a failed stage ended, in the words of summary.json's status.
enum class FailureKind { collapsed, diverged, not_converged };

/// Classifies a stage that did not reach equilibrium. `blew_up`: the world's divergence check
/// stopped it. A numerical blow-up: time step above the critical estimate, or kinetic energy
/// the loads cannot have supplied. A physical collapse: a mechanism (or a divergence check
/// tripped by blocks moving) under a stable step, with the energy accounted for by the loads.
FailureKind classify_failure(const MotionMonitor& monitor, bool blew_up);
/// True when the monitor shows a physical collapse beyond doubt: a block past the displacement
/// limit, the largest speed grown at `criteria.growth_checks` successive checks, a stable time
/// step and no kinetic energy the loads cannot have supplied.
bool collapse_is_certain(const MotionMonitor& monitor, const MechanismCriteria& criteria);
const char* to_string(FailureKind kind);
/// A plain-words explanation with advice that fits the kind.
std::string explain_failure(FailureKind kind, const MotionReport& report, const World& world);

}  // namespace blockdem
