// Bisection searches for the collapse load and the factor of safety (docs/stability.md): the
// strength reduction method of Dawson, Roth & Drescher (1999, Geotechnique 49(6):835-840), as
// used by UDEC/3DEC, applied to joint strengths.
#include "blockdem/world/stability.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <variant>

#include "blockdem/numerics/number_text.hpp"
#include "blockdem/numerics/units.hpp"

namespace blockdem {
namespace {

// A bisection's midpoint that differs from both ends of its bracket; where it does not, the
// bracket is as narrow as doubles resolve and the search ends.
bool strictly_between(double mid, double lo, double hi) {
  return mid > lo && mid < hi;
}

TrialOutcome outcome_of(FailureKind kind) {
  switch (kind) {
    case FailureKind::collapsed:
      return TrialOutcome::collapsed;
    case FailureKind::diverged:
      return TrialOutcome::diverged;
    case FailureKind::not_converged:
      return TrialOutcome::not_converged;
  }
  return TrialOutcome::not_converged;
}

}  // namespace

const char* to_string(TrialOutcome outcome) {
  switch (outcome) {
    case TrialOutcome::stable:
      return "stable";
    case TrialOutcome::collapsed:
      return to_string(FailureKind::collapsed);
    case TrialOutcome::diverged:
      return to_string(FailureKind::diverged);
    case TrialOutcome::not_converged:
      return to_string(FailureKind::not_converged);
  }
  return "failed";
}

JointLaw divide_strength(const JointLaw& law, double factor) {
  JointLaw out = law;
  out.shear = with_reduced_strength(law.shear, factor);
  return out;
}

std::vector<int> laws_named(const World& world, const std::vector<std::string>& names) {
  std::vector<int> laws;
  for (int i = 0; i < static_cast<int>(world.joint_laws().size()); ++i) {
    if (names.empty() ||
        std::find(names.begin(), names.end(), world.joint_laws()[i].name) != names.end())
      laws.push_back(i);
  }
  return laws;
}

bool has_strength(const JointLaw& law) {
  const JointStrength& s = strength_of(law.shear);
  return s.friction_coefficient > 0.0 || s.cohesion > 0.0 || s.tensile_strength > 0.0;
}

std::optional<double> extrapolated_factor(const std::vector<StabilityTrial>& trials) {
  // The two failed trials of smallest factor (nearest the critical one, where the mechanism is
  // most likely the critical one) with a measured acceleration.
  const StabilityTrial* near[2] = {nullptr, nullptr};
  for (const auto& t : trials) {
    if (t.stable || !(t.acceleration > 0.0) || !std::isfinite(t.acceleration)) continue;
    if (near[0] && t.parameter == near[0]->parameter) continue;
    if (near[1] && t.parameter == near[1]->parameter) continue;
    if (!near[0] || t.parameter < near[0]->parameter) {
      near[1] = near[0];
      near[0] = &t;
    } else if (!near[1] || t.parameter < near[1]->parameter) {
      near[1] = &t;
    }
  }
  if (!near[0] || !near[1]) return std::nullopt;
  // a = A - B/F through (1/F1, a1) and (1/F2, a2), F1 < F2: B = (a2 - a1) / (1/F1 - 1/F2).
  const double f1 = near[0]->parameter, f2 = near[1]->parameter;
  const double a1 = near[0]->acceleration, a2 = near[1]->acceleration;
  // The weaker joints (larger F) must move the mechanism faster; else no rigid mechanism.
  if (!(a2 > a1)) return std::nullopt;
  const double b = (a2 - a1) / (1.0 / f1 - 1.0 / f2);
  const double a = a1 + b / f1;
  const double fc = b / a;
  if (!(b > 0.0 && a > 0.0) || !std::isfinite(fc)) return std::nullopt;
  return fc;
}

StabilityTrial run_trial(World& world, Stage stage, double parameter, const ProgressFn& progress,
                         const StopFn& stop) {
  stage.kind = Stage::Kind::equilibrium;
  stage.stop_on_mechanism = true;
  StabilityTrial t;
  t.parameter = parameter;
  std::optional<MotionMonitor> monitor;
  const double t0 = world.time();
  if (progress) progress(stage, 0, EquilibriumMeasures{});  // the trial begins
  try {
    AfterStepFn after_step;
    if (stop) after_step = [&stop](const StageResume&) { return stop(); };
    // Between steps the trial reads its world only through reductions (the monitor, the
    // equilibrium measures; `stop` reads no block), and its end whole: spread over processes,
    // the world is made whole there and at a failure, not after every step.
    StageSync sync;
    sync.after_step_synchronizes = true;
    sync.on_step_reads = [](const World&) { return false; };
    sync.end_synchronizes = true;
    const StageResult r =
        run_stage(world, stage, progress, &monitor, after_step, nullptr, {}, &sync);
    t.steps = r.steps;
    t.interrupted = r.interrupted;
    t.motion = r.motion;
    t.stable = r.converged && !r.motion.mechanism;
    t.outcome = t.stable ? TrialOutcome::stable : outcome_of(classify_failure(*monitor, false));
    const double elapsed = world.time() - t0;
    if (!t.stable && t.outcome != TrialOutcome::diverged && elapsed > 0.0)
      t.acceleration = 2.0 * t.motion.max_displacement / (elapsed * elapsed);
  } catch (const StepFailure&) {
    t.motion = monitor->report();
    t.outcome = TrialOutcome::diverged;  // numerical, whatever the motion said
  } catch (const DivergenceError&) {
    t.motion = monitor->report();
    t.outcome = outcome_of(classify_failure(*monitor, true));
  }
  return t;
}

StabilitySearch find_collapse_load(const World& saved, const Stage& stage, double g_stable,
                                   double g_failed, double tolerance, const TrialFn& done,
                                   const StopFn& stop, const StopFn& in_trial) {
  if (!(tolerance > 0.0)) throw std::invalid_argument("collapse_tolerance: must be positive");
  // The stage raises gravity, or else its seismic coefficient k_h (k_v in proportion).
  const bool seismic = !stage.gravity && stage.seismic && stage.seismic->horizontal > 0.0;
  if (!seismic && (!stage.gravity || stage.gravity->norm() == 0.0))
    throw std::invalid_argument(
        "find_collapse: the stage must set a gravity or a positive seismic_kh");
  const Eigen::Vector3d direction =
      seismic ? Eigen::Vector3d::Zero() : Eigen::Vector3d(stage.gravity->normalized());
  StabilitySearch s;
  s.last_stable = g_stable;
  s.first_failed = g_failed;
  while (s.first_failed - s.last_stable > tolerance) {
    const double g = 0.5 * (s.last_stable + s.first_failed);
    if (!strictly_between(g, s.last_stable, s.first_failed)) break;
    if (stop && stop()) {
      s.interrupted = true;
      break;
    }
    // From the last stable equilibrium: the load rises monotonically, in steps that halve with
    // the bracket (docs/stability.md, "Collapse load").
    World w = s.stable_world ? *s.stable_world : saved;
    Stage trial = stage;
    if (seismic) {
      trial.name = stage.name + " trial k_h = " + number_text(g, "%g");
      trial.seismic->vertical = stage.seismic->vertical * (g / stage.seismic->horizontal);
      trial.seismic->horizontal = g;
    } else {
      trial.name = stage.name + " trial " + number_text(g, "%g g");
      trial.gravity = g * kOneG * direction;
    }
    StabilityTrial t = run_trial(w, trial, g, {}, in_trial);
    if (t.interrupted) {
      s.interrupted = true;
      break;
    }
    s.trials.push_back(t);
    if (done) done(t);
    if (t.stable) {
      s.last_stable = g;
      s.stable_world = std::move(w);
    } else {
      s.first_failed = g;
      s.failed_world = std::move(w);
    }
  }
  return s;
}

StabilitySearch strength_reduction(const World& saved, const Stage& stage,
                                   const std::vector<int>& laws, double lower, double upper,
                                   double tolerance, const TrialFn& done, const StopFn& stop,
                                   const ProgressFn& progress, const StopFn& in_trial) {
  if (!(tolerance > 0.0)) throw std::invalid_argument("tolerance: must be positive");
  if (!(lower > 0.0 && upper > lower))
    throw std::invalid_argument("factor_bounds: need 0 < lo < hi");
  StabilitySearch s;
  auto trial = [&](double factor, std::optional<double> placed_by = std::nullopt) {
    // Factors only grow from the last stable one: its equilibrium, with less strength, is where
    // a single run reducing the strength step by step would stand (docs/stability.md).
    World w = stage.strength.from_last_stable && s.stable_world ? *s.stable_world : saved;
    for (int i : laws) w.replace_joint_law(i, divide_strength(saved.joint_laws()[i], factor));
    Stage st = stage;
    st.name = stage.name + " F = " + number_text(factor, "%.4g");
    StabilityTrial t = run_trial(w, st, factor, progress, in_trial);
    t.placed_by = placed_by;
    if (t.interrupted) {
      s.interrupted = true;  // the trial is dropped: the bracket is the one before it
      return t;
    }
    s.trials.push_back(t);
    if (done) done(t);
    if (t.stable) {
      s.last_stable = factor;
      s.stable_world = std::move(w);
    } else {
      s.first_failed = factor;
      s.failed_world = std::move(w);
    }
    return t;
  };
  const StabilityTrial lo = trial(lower);
  if (s.interrupted || (stop && stop())) {
    s.interrupted = true;
    return s;
  }
  const StabilityTrial hi = trial(upper);
  if (s.interrupted) return s;
  if (!lo.stable || hi.stable) {
    // What to do about it. Both failed with F <= 1 at the lower bound: the joints at their full
    // strength (or stronger) do not hold the model, and no bound can bracket a factor of safety.
    const std::string tried =
        "factor_bounds: [" + number_text(lower, "%g") + ", " + number_text(upper, "%g") +
        "] do not bracket the failure: F = " + number_text(lower, "%g") + " was " +
        to_string(lo.outcome) + " and F = " + number_text(upper, "%g") + " was " +
        to_string(hi.outcome);
    const std::string rule = " (the lower bound must be stable and the upper one fail)";
    if (lo.stable)
      throw std::invalid_argument(tried + "; both stable: raise the upper bound" + rule);
    if (hi.stable) throw std::invalid_argument(tried + rule);
    if (lower > 1.0)
      throw std::invalid_argument(tried + "; both failed: lower the lower bound" + rule);
    throw std::invalid_argument(
        tried + "; both failed, and F = " + number_text(lower, "%g") +
        " <= 1 leaves the joints their full strength or more: the model is unstable with its "
        "full strength, so no strength reduction can help and it has no factor of safety (a "
        "mechanism that friction cannot stop, such as toppling, or a model not in equilibrium "
        "before the stage)");
  }
  s.last_stable = lower;
  s.first_failed = upper;
  // Trials placed by the extrapolated critical factor F_c, while it lies inside the bracket (a
  // stable trial above it contradicts it): a quarter of the tolerance below it (stable if the
  // estimate holds: stable trials are the short ones), then, once the last stable factor lies
  // that close below F_c, 0.95 of the tolerance above it (failing there closes the bracket with
  // one more failed trial, the long ones near F_c). A trial against the expectation ends the
  // extrapolation: the mechanism is not the rigid one the estimate assumes (joints that soften,
  // bonds that break, another mechanism), and the search bisects.
  // Joints that can break (cohesion, tension, a residual angle below the peak) move a failed
  // trial's mechanism on their residual strength: its acceleration extrapolates to the residual
  // factor, not to the one at which the intact joints give way, so such a search bisects.
  s.extrapolating = stage.strength.extrapolate;
  for (const JointLaw& law : saved.joint_laws())
    if (strength_of(law.shear).can_break()) s.extrapolating = false;
  bool missed = false;
  while (s.first_failed - s.last_stable > tolerance) {
    double factor = 0.5 * (s.last_stable + s.first_failed);
    bool expect_stable = false, placed = false;
    if (s.extrapolating && !missed) {
      s.extrapolated = extrapolated_factor(s.trials);
      const double fc = s.extrapolated.value_or(0.0);
      if (s.extrapolated && strictly_between(fc, s.last_stable, s.first_failed)) {
        const double below = fc - 0.25 * tolerance;
        const double above = s.last_stable + 0.95 * tolerance;
        if (below > s.last_stable) {
          factor = below;
          expect_stable = placed = true;
        } else if (above < s.first_failed) {
          factor = above;
          placed = true;
        }
      }
    }
    if (!strictly_between(factor, s.last_stable, s.first_failed)) break;
    if (stop && stop()) {
      s.interrupted = true;
      break;
    }
    const StabilityTrial t = trial(factor, placed ? s.extrapolated : std::optional<double>{});
    if (t.interrupted) break;
    if (placed && t.stable != expect_stable) missed = true;
  }
  return s;
}

}  // namespace blockdem
