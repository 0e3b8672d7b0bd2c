// Loading stages: run the world to static equilibrium (quasi-static) or for a time or step count.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "blockdem/dynamics/base_motion.hpp"
#include "blockdem/world/motion_monitor.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

/// A change of a servo block's target at the start of a stage.
struct ServoCommand {
  std::string block;
  double target_force = 0.0;            ///< (N)
  std::optional<Eigen::Vector3d> axis;  ///< unit direction of travel; unchanged when absent
};

struct Stage {
  /// strength_reduction: equilibrium trials with the joint strengths divided by a factor F,
  /// bisected for the factor of safety (each trial from the state before the stage).
  /// dynamic: a run in time of `duration` whose base blocks follow `base_motion`.
  enum class Kind { equilibrium, steps, duration, strength_reduction, dynamic };
  std::string name = "stage";
  Kind kind = Kind::equilibrium;

  std::optional<Eigen::Vector3d> gravity;  ///< new gravity from this stage on (m/s^2)
  /// Gravity moves linearly from its previous value to `gravity` over this many steps at the
  /// start of the stage (0: at once), the seismic load from its previous value to `seismic`, and
  /// the water pressure from the one before to that of `water` (or to none, `dry`):
  /// p = (1 - f) p_before + f p_stage at step k, f = k / ramp_steps. A ramp keeps a loading step
  /// quasi-static: a sudden jump sends a transient through the joints that can make them slip
  /// (and break a cohesive bond the static load would not).
  std::int64_t ramp_steps = 0;
  std::optional<double> damping;  ///< new local damping from this stage on (-)
  /// New ground water from this stage on (a water table and its density); `dry` removes it.
  std::optional<GroundWater> water;
  bool dry = false;
  /// New pseudo-static seismic coefficients from this stage on.
  std::optional<SeismicLoad> seismic;
  std::vector<ServoCommand> servos;  ///< servo targets set at the stage start
  std::vector<std::string> hold;     ///< servo blocks stopped (held in place) at the start
  bool hold_servos_after = false;    ///< stop every servo block when the stage ends
  /// Blocks removed from the world at the stage start (an excavation stage), by name.
  std::vector<std::string> remove;
  /// Joint laws given anew at the stage start, in order (World::change_laws).
  std::vector<LawChange> set_laws;
  /// Displacement outputs count from the blocks' poses at the stage start.
  bool reset_displacements = false;
  /// A gradual excavation: the loads the removed blocks exerted on the others go linearly to
  /// zero over this many steps (0: removed at once).
  std::int64_t relax_steps = 0;
  /// Bolts installed at the stage start, after the removals (World::install_bolt): they carry
  /// only what moves from then on.
  std::vector<BoltSpec> bolts;

  // Kind::equilibrium: converged when, at a check, every measure is below its tolerance and
  // every active servo is within its force tolerance.
  double unbalanced_tolerance = 1e-4;  ///< on EquilibriumMeasures::unbalanced_force_ratio (-)
  double kinetic_tolerance = 1e-8;     ///< on EquilibriumMeasures::kinetic_energy_ratio (-)
  std::int64_t max_steps = 500000;     ///< a stage that needs more has not converged
  std::int64_t min_steps = 10;
  std::int64_t check_interval = 10;  ///< steps between convergence checks

  /// Kind::equilibrium: what counts as a mechanism, and whether the stage stops as soon as one
  /// forms (else it runs to max_steps and the mechanism only explains why it did not converge).
  MechanismCriteria mechanism;
  bool stop_on_mechanism = false;

  /// Kind::equilibrium with a new gravity: when the stage fails by a mechanism, bisect between
  /// the previous gravity and this one (each trial from the last stable equilibrium: the state
  /// before the stage, then the last stable trial's) until the bracket is narrower than
  /// collapse_tolerance.
  bool find_collapse = false;
  double collapse_tolerance = 0.5;  ///< width of the collapse bracket (g)

  /// Kind::strength_reduction.
  struct StrengthReduction {
    std::vector<std::string> laws;  ///< joint law names; empty: every law
    double lower = 0.5;             ///< factor that must be stable (-)
    double upper = 4.0;             ///< factor that must fail (-)
    double tolerance = 0.01;        ///< width of the final bracket of F (-)
    /// `trial_start = "last_stable"`: a trial starts from the equilibrium of the last stable
    /// trial (its strength divided further; the first trial from the stage's start). False
    /// (`"stage_start"`, the default): every trial from the stage's start.
    bool from_last_stable = false;
    /// `factor_search = "extrapolate"` (the default): trials placed by the critical factor
    /// extrapolated from the failed trials' accelerations (strength_reduction,
    /// world/stability.hpp); `"bisect"`: every trial at the bracket's midpoint.
    bool extrapolate = true;
  } strength;

  std::int64_t steps = 0;  ///< Kind::steps
  double duration = 0.0;   ///< Kind::duration and Kind::dynamic (s)

  /// Kind::dynamic: the base group's acceleration history (docs/water-and-earthquakes.md). Its
  /// blocks, fixed before the stage, move with it during the stage (translation only) and are
  /// fixed again where it leaves them at the end. Without `damping` the stage runs with no local
  /// damping.
  std::optional<BaseMotion> base_motion;
  /// Kind::dynamic: the local damping the world takes back after the stage (the scenario reader
  /// sets the one before the stage). Empty: the one the stage found at its start (a resumed
  /// stage keeps its own).
  std::optional<double> damping_after;

  /// Density scaling during the stage (World::set_density_scaling; docs/stability.md): each
  /// block's inertia raised so that the time step follows the median block, not the smallest.
  /// Exact at static equilibrium, wrong for motion in time. Empty: on in equilibrium (and
  /// excavation) and strength-reduction stages, off in steps and duration stages and in a
  /// collapse search (find_collapse: its trials follow a ramp, whose overshoot inertia shapes);
  /// a duration stage refuses it.
  std::optional<bool> density_scaling;
  /// Whether the stage runs with density scaling (`density_scaling`, else the kind's default).
  bool scales_density() const {
    if (kind == Kind::dynamic) return false;
    return density_scaling.value_or((kind == Kind::equilibrium && !find_collapse) ||
                                    kind == Kind::strength_reduction);
  }

  /// Throws std::invalid_argument naming the field if a value is unusable.
  void validate() const;
};

struct StageResult {
  std::string name;
  bool converged = false;  ///< equilibrium reached (always true for steps/duration stages)
  std::int64_t steps = 0;  ///< steps taken in the stage
  double time = 0.0;       ///< world time at the end (s)
  EquilibriumMeasures measures;
  std::string message;       ///< why the stage did not converge, empty otherwise
  bool mechanism = false;    ///< stopped because a mechanism formed (Kind::equilibrium)
  MotionReport motion;       ///< the motion monitor's last observation
  bool interrupted = false;  ///< stopped by the caller's after-step hook (the run was stopped)
};

/// Where a stage stands between two steps: what run_stage needs to continue it later (a restart
/// file holds it, with the world and the motion monitor).
struct StageResume {
  std::int64_t steps_done = 0;                               ///< steps taken in the stage
  Eigen::Vector3d gravity_before = Eigen::Vector3d::Zero();  ///< gravity before the ramp (m/s^2)
  double start_time = 0.0;                                   ///< world time at the start (s)
};

/// Called after every step that does not end the stage; returning true stops the stage there
/// (StageResult::interrupted).
using AfterStepFn = std::function<bool(const StageResume&)>;

/// Progress reports: called at a stage's first check and then at most every 250 ms of wall time
/// (at checks) with (stage, steps taken, measures).
using ProgressFn = std::function<void(const Stage&, std::int64_t, const EquilibriumMeasures&)>;

/// Called after every step of a stage with (stage, steps taken in it); e.g. a time-history writer.
using StepFn = std::function<void(const World&, const Stage&, std::int64_t)>;

/// For a world spread over processes (WorldSettings::distribution): when the callbacks read the
/// whole world, so that run_stage completes it (World::synchronize) only then. Without it a
/// distributed world is completed after every step.
struct StageSync {
  /// Whether on_step reads more than the world's time and step counters after this step (the
  /// same answer on every process).
  std::function<bool(const World&)> on_step_reads;
  /// after_step calls World::synchronize itself, on every process alike, before it reads the world.
  bool after_step_synchronizes = false;
  /// Whether the stage's caller reads the whole world after the stage (off: the stage ends with
  /// the world as its last step left it, its results taken through reductions; the caller
  /// calls World::synchronize on every process alike where it needs the whole world).
  bool end_synchronizes = true;
};

/// Applies the stage's settings and steps the world. Throws DivergenceError from World::step.
/// `monitor`, when given, is created at the stage start and observed at every check, so that
/// after a DivergenceError it still holds the last observation before the blow-up.
/// With `resume`, the stage continues from that point instead: its start (settings, servo
/// commands, removals) is already in the world and `*monitor` must hold the monitor of then.
StageResult run_stage(World& world, const Stage& stage, const ProgressFn& progress = {},
                      std::optional<MotionMonitor>* monitor = nullptr,
                      const AfterStepFn& after_step = {}, const StageResume* resume = nullptr,
                      const StepFn& on_step = {}, const StageSync* sync = nullptr);

/// The loads a stage sets for itself and the stages after it besides gravity: ground water and
/// seismic coefficients (a restart, whose saved world holds the gravity but not these, applies
/// those of the stages it has run).
void apply_stage_loads(WorldSettings& settings, const Stage& stage);
/// The ground water alone of those: the stage's water table, or none for `dry`.
void apply_water(WorldSettings& settings, const Stage& stage);

/// True when every active (not held) servo block's reaction is within its tolerance of target.
bool servos_settled(const World& world);

}  // namespace blockdem
