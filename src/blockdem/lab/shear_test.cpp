// Direct shear test of the virtual laboratory: the shear law driven along a displacement path at
// constant normal stress, and the same path imposed on the two-block rig.
#include "blockdem/lab/shear_test.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "blockdem/contact/law_params.hpp"
#include "blockdem/lab/compression_test.hpp"
#include "blockdem/world/stage.hpp"

namespace blockdem {
namespace {

[[noreturn]] void fail_shear_test(const std::string& what) {
  throw std::invalid_argument("shear test: " + what);
}

}  // namespace

void ShearTestDef::validate() const {
  blockdem::validate(law);
  if (!(normal_stress > 0.0 && std::isfinite(normal_stress))) {
    fail_shear_test("normal_stress must be positive and finite, got " +
                    format_value(normal_stress) + " Pa");
  }
  if (!(max_displacement > 0.0 && std::isfinite(max_displacement))) {
    fail_shear_test("max_displacement must be positive and finite, got " +
                    format_value(max_displacement) + " m");
  }
  if (steps < 1) fail_shear_test("steps must be at least 1, got " + std::to_string(steps));
  if (cycles < 0)
    fail_shear_test("cycles must be >= 0 (0: monotonic), got " + std::to_string(cycles));
}

std::vector<double> shear_path_increments(const ShearTestDef& def) {
  def.validate();
  const double du = def.max_displacement / def.steps;
  std::vector<double> out;
  if (def.cycles == 0) {
    out.assign(static_cast<std::size_t>(def.steps), du);
    return out;
  }
  // A cycle: +max (steps), back through zero to -max (2 steps), back to zero (steps).
  for (int c = 0; c < def.cycles; ++c) {
    out.insert(out.end(), static_cast<std::size_t>(def.steps), du);
    out.insert(out.end(), static_cast<std::size_t>(2 * def.steps), -du);
    out.insert(out.end(), static_cast<std::size_t>(def.steps), du);
  }
  return out;
}

ShearCurve run_shear_kernel(const ShearTestDef& def) {
  const std::vector<double> increments = shear_path_increments(def);
  // A joint of unit area: forces (N) equal stresses (Pa).
  ShearIncrement inc;
  inc.normal = Eigen::Vector3d::UnitZ();
  inc.contact_area = 1.0;
  inc.normal_force = def.normal_stress;
  inc.normal_stress = def.normal_stress;
  ShearState state;

  ShearCurve curve;
  ShearPoint p;
  p.cycle = def.cycles == 0 ? 0 : 1;
  p.step_stiffness = std::numeric_limits<double>::quiet_NaN();
  curve.points.push_back(p);
  const std::size_t per_cycle = 4 * static_cast<std::size_t>(def.steps);
  for (std::size_t k = 0; k < increments.size(); ++k) {
    // B (top) moves by du along +x relative to A (bottom).
    inc.displacement = Eigen::Vector3d(increments[k], 0.0, 0.0);
    const ShearResult result = update_shear(def.law, state, inc);
    ShearPoint next;
    next.cycle = def.cycles == 0 ? 0 : static_cast<int>(k / per_cycle) + 1;
    next.shear_displacement = p.shear_displacement + increments[k];
    next.shear_stress = -state.force.x() / inc.contact_area;
    next.mobilised_friction = next.shear_stress / def.normal_stress;
    next.plastic_slip = state.plastic_slip;
    next.step_stiffness = (next.shear_stress - p.shear_stress) / increments[k];
    next.sliding = result.sliding;
    curve.points.push_back(next);
    curve.peak_shear_stress = std::max(curve.peak_shear_stress, std::abs(next.shear_stress));
    p = next;
  }
  return curve;
}

DemShearRun run_shear_dem(const ShearTestDef& def, const NormalLaw& normal,
                          const ShearCurve& kernel, const TwoBlockRigDef& rig) {
  const std::vector<double> increments = shear_path_increments(def);
  rig.validate();
  validate(normal);
  if (kernel.points.size() != increments.size() + 1) {
    throw std::invalid_argument("run_shear_dem: the kernel curve is not this test's path");
  }
  if (!(def.max_displacement <= 0.25 * rig.top_size.x())) {
    fail_shear_test("the DEM run needs max_displacement <= a quarter of the block length (" +
                    format_value(0.25 * rig.top_size.x()) + " m), got " +
                    format_value(def.max_displacement) + " m");
  }
  const double closure = closure_at_stress(normal, def.normal_stress);
  if (closure > rig.rounding_distance) {
    fail_shear_test(
        "the DEM run needs the closure at sigma_n below the rounding distance r_round = " +
        format_value(rig.rounding_distance) + " m, got " + format_value(closure) + " m");
  }
  // The bottom block is longer than the top by the travel both ways, so the joint keeps the top
  // block's full face as its area.
  const double bottom_length =
      rig.top_size.x() + 2.0 * def.max_displacement + 0.1 * rig.top_size.x();
  // The top block starts at half the closure that carries sigma_n and settles under its weight:
  // the engine, not this function, finds the equilibrium closure.
  World world = make_two_block_rig(rig, normal, def.law, bottom_length, 0.5 * closure);

  // Settle the top block under the weight that carries sigma_n.
  Stage settle;
  settle.name = "settle";
  settle.kind = Stage::Kind::equilibrium;
  settle.gravity =
      Eigen::Vector3d(0.0, 0.0, -rig_gravity_for_stress(world, rig, def.normal_stress));
  settle.unbalanced_tolerance = rig.unbalanced_tolerance;
  settle.kinetic_tolerance = rig.kinetic_tolerance;
  settle.max_steps = rig.max_steps_per_level;
  const StageResult settled = run_stage(world, settle);

  DemShearRun run;
  run.contact_mode = rig.contact_mode;
  run.settle_steps = settled.steps;
  run.settled = settled.converged;
  if (!settled.converged) run.message = "settling under the normal load: " + settled.message;

  // Shear: a fixed time step, and one path increment per step through the bottom block's velocity.
  run.time_step = world.next_time_step();
  world.settings().time_step = run.time_step;
  run.shear_speed = def.max_displacement / def.steps / run.time_step;
  Block& bottom = world.blocks()[rig_bottom];
  const auto compare = [&](std::size_t k) {
    const RigReading& r = run.readings.back();
    const ShearPoint& q = kernel.points[k];
    run.max_shear_stress_difference =
        std::max(run.max_shear_stress_difference, std::abs(r.shear_stress - q.shear_stress));
    run.max_displacement_difference = std::max(
        run.max_displacement_difference, std::abs(r.shear_displacement - q.shear_displacement));
    run.max_relative_normal_stress_deviation =
        std::max(run.max_relative_normal_stress_deviation,
                 std::abs(r.normal_stress - def.normal_stress) / def.normal_stress);
  };
  run.readings.push_back(read_rig(world, rig));
  compare(0);
  for (std::size_t k = 0; k < increments.size(); ++k) {
    // The top block moves +du relative to the bottom: the bottom moves -du.
    bottom.velocity = Eigen::Vector3d(-increments[k] / run.time_step, 0.0, 0.0);
    world.step();
    run.readings.push_back(read_rig(world, rig));
    compare(k + 1);
  }
  bottom.velocity.setZero();
  run.max_relative_shear_stress_difference =
      kernel.peak_shear_stress > 0.0 ? run.max_shear_stress_difference / kernel.peak_shear_stress
                                     : 0.0;
  return run;
}

}  // namespace blockdem
