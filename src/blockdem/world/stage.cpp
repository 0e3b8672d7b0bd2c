// Quasi-static stage runner: step until the unbalanced-force ratio and the
// kinetic energy ratio fall below tolerances, or report the stage as not converged.
#include "blockdem/world/stage.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "blockdem/numerics/number_text.hpp"
#include "blockdem/world/base_drive.hpp"

namespace blockdem {

void Stage::validate() const {
  auto fail = [this](const std::string& what) {
    throw std::invalid_argument("stage '" + name + "': " + what);
  };
  if (gravity && !gravity->allFinite()) fail("gravity must be finite");
  if (damping && !(*damping >= 0.0 && *damping < 1.0)) fail("damping must be in [0, 1)");
  if (!(unbalanced_tolerance > 0.0)) fail("unbalanced_tolerance must be positive");
  if (!(kinetic_tolerance > 0.0)) fail("kinetic_tolerance must be positive");
  if (max_steps <= 0) fail("max_steps must be positive");
  if (ramp_steps < 0) fail("ramp_steps must be zero or positive");
  if (relax_steps < 0) fail("relax_steps must be zero or positive");
  if (relax_steps > 0 && remove.empty()) fail("relax_steps needs blocks to remove");
  for (const BoltSpec& b : bolts) {
    try {
      b.validate();
    } catch (const std::invalid_argument& e) {
      fail("bolt '" + b.name + "': " + e.what());
    }
  }
  if (check_interval <= 0) fail("check_interval must be positive");
  if (kind == Kind::steps && steps <= 0) fail("steps must be positive");
  if (kind == Kind::duration && !(duration > 0.0)) fail("duration must be positive");
  if (kind == Kind::duration && density_scaling.value_or(false))
    fail(
        "density_scaling: a duration stage runs in time, which density scaling distorts (it is "
        "exact only at static equilibrium)");
  if (kind == Kind::dynamic) {
    if (!base_motion) fail("a dynamic stage needs base_motion");
    if (!(duration > 0.0 && std::isfinite(duration))) fail("duration must be positive");
    if (density_scaling.value_or(false))
      fail("density_scaling: a dynamic stage runs in time, which density scaling distorts");
    try {
      base_motion->validate();
    } catch (const std::invalid_argument& e) {
      fail(std::string("base_motion.") + e.what());
    }
  } else if (base_motion) {
    fail("base_motion: only a stage of kind \"dynamic\" takes it");
  }
  if (find_collapse && !gravity && !seismic)
    fail("find_collapse needs a new gravity or seismic coefficients in this stage");
  if (seismic) {
    try {
      seismic->validate();
    } catch (const std::invalid_argument& e) {
      fail(e.what());
    }
  }
  if (water && !(water->density > 0.0 && std::isfinite(water->density)))
    fail("water_density must be positive and finite");
  if (water && dry) fail("a stage either sets a water table or makes the model dry");
  if (find_collapse && !(collapse_tolerance > 0.0)) fail("collapse_tolerance must be positive");
  if (kind == Kind::strength_reduction) {
    if (!(strength.lower > 0.0 && strength.upper > strength.lower))
      fail("factor_bounds must satisfy 0 < lo < hi");
    if (!(strength.tolerance > 0.0)) fail("tolerance must be positive");
  }
  try {
    mechanism.validate();
  } catch (const std::invalid_argument& e) {
    fail(e.what());
  }
  for (const auto& s : servos) {
    if (!(s.target_force >= 0.0) || !std::isfinite(s.target_force))
      fail("servo target_force must be >= 0");
    if (s.axis && std::abs(s.axis->norm() - 1.0) > 1e-9) fail("servo axis must be a unit vector");
  }
}

void apply_water(WorldSettings& settings, const Stage& stage) {
  if (stage.water) settings.water = stage.water;
  if (stage.dry) settings.water.reset();
}

void apply_stage_loads(WorldSettings& settings, const Stage& stage) {
  apply_water(settings, stage);
  if (stage.seismic) settings.seismic = *stage.seismic;
}

bool servos_settled(const World& world) {
  // Counted over the blocks this process counts and summed over the processes (exact).
  std::array<std::int64_t, 1> unsettled{0};
  for (std::size_t i = 0; i < world.blocks().size(); ++i) {
    const Block& b = world.blocks()[i];
    const Servo& s = b.servo();
    if (b.motion != Motion::servo || s.hold || !world.counts_block(i)) continue;
    const double reaction = -b.contact_force.dot(s.axis);
    if (std::abs(reaction - s.target_force) > s.tolerance * s.target_force) ++unsettled[0];
  }
  world.reduce_partials({}, {}, unsettled);
  return unsettled[0] == 0;
}

namespace {

/// The stage's start: new settings, servo commands, joint laws, the displacements' reference,
/// removals, the divergence checkpoint and a fresh motion monitor.
void start_stage(World& world, const Stage& stage, std::optional<MotionMonitor>& watch) {
  if (stage.gravity && stage.ramp_steps == 0) world.settings().gravity = *stage.gravity;
  apply_stage_loads(world.settings(), stage);
  if (stage.damping) world.settings().damping = *stage.damping;
  for (const auto& cmd : stage.servos) {
    const int i = world.find_block(cmd.block);
    if (i < 0)
      throw std::invalid_argument("stage '" + stage.name + "': no block named '" + cmd.block + "'");
    Block& b = world.blocks()[i];
    b.motion = Motion::servo;
    Servo& s = b.edit_servo();
    s.hold = false;
    s.target_force = cmd.target_force;
    if (cmd.axis) s.axis = *cmd.axis;
  }
  for (const auto& name : stage.hold) {
    const int i = world.find_block(name);
    if (i < 0)
      throw std::invalid_argument("stage '" + stage.name + "': no block named '" + name + "'");
    world.blocks()[i].edit_servo().hold = true;
  }
  if (!stage.set_laws.empty()) world.change_laws(stage.set_laws);
  if (stage.reset_displacements) world.reset_displacements();
  if (!stage.remove.empty()) {
    const std::vector<int> gone = world.find_blocks(stage.remove);
    for (std::size_t k = 0; k < gone.size(); ++k) {
      if (gone[k] < 0)
        throw std::invalid_argument("stage '" + stage.name + "': no block named '" +
                                    stage.remove[k] + "'");
    }
    if (stage.relax_steps > 0) {
      world.remove_blocks_gradually(gone);
    } else {
      world.remove_blocks(gone);
    }
  }
  // After the removals: the bolts, along their lines through the blocks that stay.
  for (const BoltSpec& bolt : stage.bolts) {
    try {
      world.install_bolt(bolt);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("stage '" + stage.name + "': " + e.what());
    }
  }
  // After the removals: the median block is that of the blocks that stay.
  world.set_density_scaling(stage.scales_density());
  world.save_checkpoint();
  watch.emplace(world, stage.mechanism);
}

/// What a stage ramps from (the loads before it) and, step by step, the ramped loads: gravity,
/// the seismic load and the water pressure over ramp_steps, and a gradual excavation's relaxation.
struct StageRamp {
  Eigen::Vector3d gravity_before;
  SeismicLoad seismic_before;
  std::optional<GroundWater> water_before;
  bool water_ramp = false;

  /// Sets the loads of step k; true while a load is still being raised or relaxed.
  bool apply(World& world, const Stage& stage, std::int64_t k) const {
    const bool relaxing = world.relaxing();
    const bool in_ramp = k <= stage.ramp_steps;
    const bool ramping = ((stage.gravity || stage.seismic || water_ramp) && in_ramp) || relaxing;
    const double f = in_ramp ? static_cast<double>(k) / static_cast<double>(stage.ramp_steps) : 1.0;
    if (stage.gravity && in_ramp)
      world.settings().gravity = gravity_before + f * (*stage.gravity - gravity_before);
    // The seismic load moves from the one before the stage to the stage's over the ramp.
    if (stage.seismic && in_ramp)
      world.settings().seismic = seismic_before.toward(*stage.seismic, f);
    // The water pressure p = (1 - f) p_before + f p_stage; the stage's alone from f = 1.
    if (water_ramp && in_ramp) {
      if (k < stage.ramp_steps) {
        world.settings().water_ramp = WaterRamp{water_before, f};
      } else {
        world.settings().water_ramp.reset();
      }
    }
    // A gradual excavation: the removed blocks' loads down to zero at step relax_steps.
    if (relaxing) {
      const double done = static_cast<double>(std::min(k, stage.relax_steps)) /
                          static_cast<double>(stage.relax_steps);
      world.relax(1.0 - done);
    }
    return ramping;
  }
};

}  // namespace

StageResult run_stage(World& world, const Stage& stage, const ProgressFn& progress,
                      std::optional<MotionMonitor>* monitor, const AfterStepFn& after_step,
                      const StageResume* resume, const StepFn& on_step, const StageSync* sync) {
  stage.validate();
  // A distributed world is made whole only where the stage or its callbacks read it.
  world.synchronize();
  const bool deferred =
      sync != nullptr && world.settings().distribution != nullptr && sync->after_step_synchronizes;
  struct Deferral {
    World& world;
    ~Deferral() { world.set_deferred_replica(false); }
  } deferral{world};
  world.set_deferred_replica(deferred);
  if (resume && !(monitor && monitor->has_value()))
    throw std::logic_error("run_stage: resuming a stage needs its motion monitor");
  StageRamp ramp;
  ramp.gravity_before = resume ? resume->gravity_before : world.settings().gravity;
  const Eigen::Vector3d& gravity_before = ramp.gravity_before;
  // The seismic load before the stage (a restart applies the stages' loads up to the one before
  // this, and this stage's at the end of its ramp).
  ramp.seismic_before = world.settings().seismic;
  if (resume && stage.seismic && resume->steps_done >= stage.ramp_steps)
    world.settings().seismic = *stage.seismic;
  // Likewise the water: a ramp moves its pressure from the one before the stage to the stage's
  // (none when the two are the same water, as in a collapse search's later trials).
  ramp.water_before = world.settings().water;
  const bool sets_water = stage.water || stage.dry;
  ramp.water_ramp = sets_water && stage.ramp_steps > 0 &&
                    !(ramp.water_before == (stage.dry ? std::nullopt : stage.water));
  if (resume && sets_water) apply_water(world.settings(), stage);
  std::optional<MotionMonitor> own_monitor;
  std::optional<MotionMonitor>& watch = monitor ? *monitor : own_monitor;
  if (!resume) start_stage(world, stage, watch);
  StageResult r;
  r.name = stage.name;
  const double t0 = resume ? resume->start_time : world.time();
  // A dynamic stage's base follows its history (nothing for another stage).
  BaseDrive base(world, stage, t0, resume != nullptr);
  auto last_report = std::chrono::steady_clock::now();
  bool reported = false;
  for (std::int64_t k = resume ? resume->steps_done + 1 : 1;; ++k) {
    const bool ramping = ramp.apply(world, stage, k);
    base.before_step(world);
    world.step();
    base.after_step(world);
    r.steps = k;
    const bool check = k % stage.check_interval == 0;
    if (deferred && on_step && (!sync->on_step_reads || sync->on_step_reads(world)))
      world.synchronize();
    if (on_step) on_step(world, stage, k);
    // The checks read the world through reductions (collective on every process alike when it
    // is distributed and not whole), not through a whole-world refresh.
    EquilibriumMeasures measures;
    if (check) {
      watch->observe(world, ramping);
      measures = world.equilibrium();
    }
    if (progress && check) {
      const auto now = std::chrono::steady_clock::now();
      // The first check's line at once (a short run, such as a search's trial, has one too),
      // then at most every 250 ms.
      if (!reported || now - last_report > std::chrono::milliseconds(250)) {
        progress(stage, k, measures);
        last_report = now;
        reported = true;
      }
    }
    if (stage.kind == Stage::Kind::steps && k >= stage.steps) {
      r.converged = true;
      break;
    }
    const bool timed = stage.kind == Stage::Kind::duration || stage.kind == Stage::Kind::dynamic;
    if (timed && world.time() - t0 >= stage.duration * (1 - 1e-12)) {
      r.converged = true;
      break;
    }
    if (stage.kind == Stage::Kind::equilibrium && check && k >= stage.min_steps && !ramping) {
      // servos_settled is collective too: evaluated on every process, not short-circuited.
      const bool settled = servos_settled(world);
      if (measures.unbalanced_force_ratio <= stage.unbalanced_tolerance &&
          measures.kinetic_energy_ratio <= stage.kinetic_tolerance && settled) {
        r.converged = true;
        break;
      }
    }
    if (stage.kind == Stage::Kind::equilibrium && stage.stop_on_mechanism &&
        watch->report().mechanism) {
      r.mechanism = true;
      r.message = "a mechanism formed after " + std::to_string(k) + " steps";
      break;
    }
    // A mechanism beyond doubt ends an equilibrium stage at once (waiting for max_steps would
    // only carry the blocks farther): blocks past the displacement limit whose largest speed has
    // grown at every one of the last growth_checks checks, under a stable time step and with
    // the kinetic energy accounted for by the loads. The stage fails as it would at max_steps.
    if (stage.kind == Stage::Kind::equilibrium && check && !ramping &&
        collapse_is_certain(*watch, stage.mechanism)) {
      r.mechanism = true;
      r.message = "a mechanism formed after " + std::to_string(k) +
                  " steps: blocks past the displacement limit kept accelerating";
      break;
    }
    if (k >= stage.max_steps) {
      world.synchronize();
      const EquilibriumMeasures m = world.equilibrium();
      // A stage that runs to a count or a time has no equilibrium to miss: it was cut short
      // (blockdem run --max-steps, or a max_steps below its steps).
      const std::string cut =
          "stopped by its step limit (max_steps = " + std::to_string(stage.max_steps) + ") after " +
          std::to_string(k);
      r.message = (stage.kind == Stage::Kind::steps
                       ? cut + " of its " + std::to_string(stage.steps) + " steps"
                   : timed ? cut + " steps, at " + number_text(world.time() - t0, "%.4g") +
                                 " s of its " + number_text(stage.duration, "%.4g") + " s"
                           : "no equilibrium after " + std::to_string(k) + " steps") +
                  ": unbalanced force ratio " + number_text(m.unbalanced_force_ratio) +
                  " (tolerance " + number_text(stage.unbalanced_tolerance) +
                  "), kinetic energy ratio " + number_text(m.kinetic_energy_ratio) +
                  " (tolerance " + number_text(stage.kinetic_tolerance) + ")" +
                  (servos_settled(world) ? "" : ", a servo has not reached its target force");
      break;
    }
    if (after_step && after_step(StageResume{k, gravity_before, t0})) {
      r.interrupted = true;
      r.message = "interrupted after " + std::to_string(k) + " steps of the stage";
      break;
    }
  }
  if (!deferred || sync->end_synchronizes) world.synchronize();
  if (!r.interrupted) base.finish(world);
  // A stage that ends (or is stopped) inside its ramp leaves its water in full, as a restart
  // after it sets it (a checkpoint of a stopped stage was written before this).
  world.settings().water_ramp.reset();
  if (stage.hold_servos_after && !r.interrupted) {
    for (auto& b : world.blocks()) {
      if (b.motion == Motion::servo) b.edit_servo().hold = true;
    }
  }
  r.time = world.time();
  r.measures = world.equilibrium();
  watch->observe(world, false);
  r.motion = watch->report();
  return r;
}

}  // namespace blockdem
