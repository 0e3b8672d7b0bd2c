// Compression test of the virtual laboratory: the normal law driven along a closure path, and the
// same path applied as load levels to the two-block rig (quasi-static equilibrium stages).
#include "blockdem/lab/compression_test.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "blockdem/contact/law_params.hpp"
#include "blockdem/numerics/bracketed_root.hpp"
#include "blockdem/world/stage.hpp"

namespace blockdem {
namespace {

[[noreturn]] void fail(const std::string& what) {
  throw std::invalid_argument("compression test: " + what);
}

}  // namespace

void CompressionTestDef::validate() const {
  blockdem::validate(law);
  const bool has_closure = max_closure != 0.0;
  const bool has_stress = max_stress != 0.0;
  if (has_closure == has_stress) fail("give exactly one of max_closure and max_stress");
  if (has_closure && !(max_closure > 0.0 && std::isfinite(max_closure))) {
    fail("max_closure must be positive and finite, got " + format_value(max_closure) + " m");
  }
  if (has_stress && !(max_stress > 0.0 && std::isfinite(max_stress))) {
    fail("max_stress must be positive and finite, got " + format_value(max_stress) + " Pa");
  }
  if (cycles < 1) fail("cycles must be at least 1, got " + std::to_string(cycles));
  if (steps_per_branch < 1) {
    fail("steps_per_branch must be at least 1, got " + std::to_string(steps_per_branch));
  }
}

const char* branch_name(PathBranch branch) {
  return branch == PathBranch::loading ? "loading" : "unloading";
}

double closure_at_stress(const NormalLaw& law, double stress) {
  if (!(stress > 0.0 && std::isfinite(stress))) {
    throw std::invalid_argument("closure_at_stress: stress must be positive and finite, got " +
                                format_value(stress) + " Pa");
  }
  const auto residual = [&](double u) { return normal_stress(law, u) - stress; };
  // Start from the closure the stiffness at zero closure would give; grow until bracketed.
  double hi = stress / normal_tangent_stiffness(law, 0.0);
  double r_hi = residual(hi);
  for (int i = 0; r_hi < 0.0; ++i) {
    if (i > 200) throw std::runtime_error("closure_at_stress: no closure carries the stress");
    hi *= 2.0;
    r_hi = residual(hi);
  }
  return find_root_bracketed(residual, 0.0, hi, -stress, r_hi, 1e-13, 0.0);
}

CompressionCurve run_compression_kernel(const CompressionTestDef& def) {
  def.validate();
  CompressionCurve curve;
  curve.max_closure =
      def.max_closure > 0.0 ? def.max_closure : closure_at_stress(def.law, def.max_stress);
  curve.max_stress = normal_stress(def.law, curve.max_closure);
  const int n = def.steps_per_branch;
  const auto point = [&](int cycle, PathBranch branch, int step) {
    CompressionPoint p;
    p.cycle = cycle;
    p.branch = branch;
    p.closure = curve.max_closure * static_cast<double>(step) / static_cast<double>(n);
    p.normal_stress = normal_stress(def.law, p.closure);
    p.tangent_stiffness = normal_tangent_stiffness(def.law, p.closure);
    return p;
  };
  curve.points.push_back(point(1, PathBranch::loading, 0));
  for (int cycle = 1; cycle <= def.cycles; ++cycle) {
    for (int i = 1; i <= n; ++i) curve.points.push_back(point(cycle, PathBranch::loading, i));
    for (int i = n - 1; i >= 0; --i) curve.points.push_back(point(cycle, PathBranch::unloading, i));
  }
  return curve;
}

DemCompressionRun run_compression_dem(const CompressionTestDef& def, const CompressionCurve& kernel,
                                      const TwoBlockRigDef& rig) {
  def.validate();
  rig.validate();
  if (kernel.max_closure > rig.rounding_distance) {
    fail("the DEM run needs a max closure below the rounding distance r_round = " +
         format_value(rig.rounding_distance) + " m (the contact normal may jump beyond it), got " +
         format_value(kernel.max_closure) + " m");
  }
  // Start at the first loaded level's closure, so the first stage only has to settle.
  double first_closure = 0.0;
  for (const auto& p : kernel.points) {
    if (p.normal_stress > 0.0) {
      first_closure = p.closure;
      break;
    }
  }
  World world = make_two_block_rig(rig, def.law, LinearShear{}, rig.top_size.x(), first_closure);

  DemCompressionRun run;
  run.contact_mode = rig.contact_mode;
  for (std::size_t i = 0; i < kernel.points.size(); ++i) {
    const CompressionPoint& target = kernel.points[i];
    if (!(target.normal_stress > 0.0)) continue;
    // Load level: the top block's weight carries the target stress; equilibrium under it.
    Stage stage;
    stage.name = "level " + std::to_string(i);
    stage.kind = Stage::Kind::equilibrium;
    stage.gravity =
        Eigen::Vector3d(0.0, 0.0, -rig_gravity_for_stress(world, rig, target.normal_stress));
    stage.unbalanced_tolerance = rig.unbalanced_tolerance;
    stage.kinetic_tolerance = rig.kinetic_tolerance;
    stage.max_steps = rig.max_steps_per_level;
    const StageResult result = run_stage(world, stage);

    DemCompressionPoint p;
    p.kernel_index = i;
    p.applied_stress = target.normal_stress;
    p.reading = read_rig(world, rig);
    p.steps = result.steps;
    p.converged = result.converged;
    run.total_steps += result.steps;
    if (!result.converged && run.converged) {
      run.converged = false;
      run.message = stage.name + ": " + result.message;
    }
    // Compare with the kernel: closure at the same stress, and stress at the measured closure.
    const double du = std::abs(p.reading.closure - target.closure);
    const double ds = std::abs(normal_stress(def.law, p.reading.closure) - target.normal_stress);
    run.max_closure_difference = std::max(run.max_closure_difference, du);
    run.max_stress_difference = std::max(run.max_stress_difference, ds);
    run.points.push_back(p);
  }
  run.max_relative_closure_difference = run.max_closure_difference / kernel.max_closure;
  run.max_relative_stress_difference = run.max_stress_difference / kernel.max_stress;
  return run;
}

}  // namespace blockdem
