// Stability searches by bisection, each trial from a saved world (a collapse search's from its
// last stable trial): the collapse load of a rising gravity, and the factor of safety by strength
// reduction (docs/stability.md).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "blockdem/world/stage.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

/// How a trial of a search ended: stable, or why not (a failure's kind, FailureKind).
enum class TrialOutcome {
  stable,
  collapsed,      ///< a mechanism
  diverged,       ///< numerical blow-up: counted as failed and reported
  not_converged,  ///< no equilibrium and no mechanism within the step limit: counted as failed
};
/// The outcome's word in the outputs: "stable", "collapsed", "diverged", "not_converged".
const char* to_string(TrialOutcome outcome);

/// One trial of a search: the parameter tried (g level or factor) and how it ended.
struct StabilityTrial {
  double parameter = 0.0;
  bool stable = false;
  TrialOutcome outcome = TrialOutcome::not_converged;
  std::int64_t steps = 0;
  MotionReport motion;
  /// A failed trial's mean acceleration of its mechanism, 2 d / T^2 (d: the largest
  /// displacement of a free block, T: the trial's time), as if it moved from rest at constant
  /// acceleration (m/s^2); 0 for a stable trial or one that diverged.
  double acceleration = 0.0;
  /// The extrapolated critical factor that placed this trial (strength_reduction); none for a
  /// bound or a bisection's midpoint.
  std::optional<double> placed_by;
  /// Stopped part way by the caller (run_trial's `stop`): neither stable nor failed, and not
  /// among a search's trials.
  bool interrupted = false;
};

struct StabilitySearch {
  double last_stable = 0.0;
  double first_failed = 0.0;
  std::vector<StabilityTrial> trials;  ///< in the order they ran
  /// The world at the end of the first-failed trial (the mechanism), and of the last stable one.
  std::optional<World> failed_world;
  std::optional<World> stable_world;
  /// The caller stopped the search between two trials (StopFn): the bracket is the one so far.
  bool interrupted = false;
  /// A strength reduction's last estimate of the critical factor from its failed trials'
  /// accelerations (extrapolated_factor), when it had one.
  std::optional<double> extrapolated;
  /// A strength reduction placed its trials by the extrapolation (stage.strength.extrapolate,
  /// and no joint law that can break); false: it bisected.
  bool extrapolating = false;
};

/// The factor at which a rigid mechanism's acceleration vanishes, extrapolated from the failed
/// trials of a strength reduction: with the joints' strength divided by F, the mechanism's net
/// driving force is D - R/F (the resisting forces N tan(phi)/F + c A/F at fixed normal forces),
/// and under local damping its acceleration is a constant times that, a = A - B/F. The line in
/// 1/F through the two failed trials of smallest F with a measured acceleration gives F_c =
/// B/A. None when there are fewer than two, or the line does not rise with F.
std::optional<double> extrapolated_factor(const std::vector<StabilityTrial>& trials);

/// Called after each trial.
using TrialFn = std::function<void(const StabilityTrial&)>;
/// Asked between two trials of a search: true stops it there.
using StopFn = std::function<bool()>;

/// The narrowest bracket a search may be asked for, relative to the largest magnitude it
/// brackets: 1e-12 (about 4,500 times the resolution of a double there, so that every midpoint
/// differs from both ends; a search stops anyway where the midpoint equals an end).
inline constexpr double kNarrowestRelativeBracket = 1e-12;

/// Runs `stage` (Kind::equilibrium) on a copy of `saved` and says whether it reached
/// equilibrium without a mechanism. The stage stops as soon as a mechanism forms. `progress` is
/// told when the trial begins (step 0, no measures: nothing stepped yet) and then of its steps
/// as a stage's. `stop`, asked after every step, ends the trial there when it says true
/// (StabilityTrial::interrupted).
StabilityTrial run_trial(World& world, Stage stage, double parameter,
                         const ProgressFn& progress = {}, const StopFn& stop = {});

/// The collapse load of a gravity that rises to `stage.gravity`: `saved` is the world in
/// equilibrium at gravity magnitude g_stable (in g), and the stage failed at g_failed. Bisects
/// until g_failed - g_stable <= tolerance (g); each trial starts from the last stable trial's
/// equilibrium (from `saved` until one holds) and ramps gravity along the stage's direction over
/// the stage's ramp_steps, so the load only rises, by at most the bracket's width. A stage that
/// sets seismic coefficients and no gravity has its seismic coefficient k_h searched instead
/// (g_stable and g_failed are values of k_h, k_v scaled in proportion): the critical seismic
/// coefficient k_c, each trial's earthquake applied at once at its start.
StabilitySearch find_collapse_load(const World& saved, const Stage& stage, double g_stable,
                                   double g_failed, double tolerance, const TrialFn& done = {},
                                   const StopFn& stop = {}, const StopFn& in_trial = {});

/// The strength reduction of a stage: divides tan(phi), cohesion and tensile strength of the
/// joint laws `laws` (indices into saved.joint_laws()) by F and seeks equilibrium with the
/// stage's criteria. Tries the bounds first: throws std::invalid_argument (naming the factors
/// tried and what happened) when they do not bracket the failure, saying that the model is
/// unstable with its full strength when both failed and lower <= 1; then bisects until
/// first_failed - last_stable <= tolerance. With stage.strength.extrapolate (the default), a
/// trial is placed by the failed trials' extrapolated critical factor F_c where it has one (a
/// quarter of the tolerance below F_c, expected stable; then 0.95 of the tolerance above the
/// last stable factor, expected to fail and close the bracket) while F_c lies inside the bracket,
/// and at the midpoint otherwise and after a trial that went against the expectation; a world
/// with a joint law that can break (JointStrength::can_break) bisects. Every bracket is still [a
/// stable trial, a failed trial].
///
/// Both searches end whatever the tolerance: where the bracket's midpoint equals one of its ends
/// (the bracket as narrow as doubles go), or where `stop` says so between two trials
/// (StabilitySearch::interrupted), or where `in_trial`, asked after every step of a trial, says
/// so: that trial is dropped and the bracket is the one before it.
///
/// With stage.strength.from_last_stable, a trial at a larger factor starts from the equilibrium
/// of the last stable trial (the factor's strength replacing that trial's), as the strength is
/// reduced step by step in a single run; the first trial, and any with none stable before it,
/// from `saved`. `progress` is told of each trial as run_trial tells it (the trial's stage is
/// named "NAME F = f").
StabilitySearch strength_reduction(const World& saved, const Stage& stage,
                                   const std::vector<int>& laws, double lower, double upper,
                                   double tolerance, const TrialFn& done = {},
                                   const StopFn& stop = {}, const ProgressFn& progress = {},
                                   const StopFn& in_trial = {});

/// Indices into world.joint_laws() of the laws named in `names` (every law when it is empty), in
/// the world's order: the laws a strength reduction divides.
std::vector<int> laws_named(const World& world, const std::vector<std::string>& names);

/// The law with its strengths divided by `factor` (with_reduced_strength: tan(phi)/F, c/F,
/// sigma_t/F and the residual tan(phi_r)/F; stiffnesses unchanged).
JointLaw divide_strength(const JointLaw& law, double factor);
/// True when the law has a strength that strength reduction can divide (friction, cohesion or
/// tensile strength).
bool has_strength(const JointLaw& law);

}  // namespace blockdem
