// Mechanism detection and the energy balance of a stage (docs/stability.md).
#include "blockdem/world/motion_monitor.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "blockdem/numerics/number_text.hpp"

namespace blockdem {
namespace {
/// MotionReport::elastic_energy_start before the world's first step (saved as is, restored).
constexpr double kPending = std::numeric_limits<double>::quiet_NaN();
}  // namespace

void MechanismCriteria::validate() const {
  if (!(displacement_limit >= 0.0) || !std::isfinite(displacement_limit))
    throw std::invalid_argument("displacement_limit: must be >= 0 (0: automatic)");
  if (growth_checks < 2) throw std::invalid_argument("growth_checks: must be at least 2");
}

MotionMonitor::MotionMonitor(const World& world, const MechanismCriteria& criteria)
    : criteria_(criteria) {
  criteria_.validate();
  double limit = std::numeric_limits<double>::infinity();
  for (const auto& b : world.blocks()) {
    start_.push_back(b.position);
    if (b.is_dynamic()) limit = std::min(limit, 0.5 * b.shape.bounding_radius());
  }
  report_.displacement_limit =
      criteria_.displacement_limit > 0.0 ? criteria_.displacement_limit : limit;
  // A world not yet stepped has no joint forces: its joints' energy (an in-situ prestress
  // above all, which can be most of what a stage releases) is taken after the first step.
  if (world.step_count() == 0) report_.elastic_energy_start = kPending;
  for (const Contact* c : world.contacts())
    report_.elastic_energy_start += 0.5 * std::max(c->normal_force, 0.0) * c->geometry.overlap;
  observe(world, true);
}

void MotionMonitor::observe(const World& world, bool ramping) {
  MotionReport& r = report_;
  if (std::isnan(r.elastic_energy_start) && world.step_count() > 0)
    r.elastic_energy_start = world.energy_budget().initial;
  // Maxima, exact sums and the list of moving blocks over the blocks this process counts,
  // reduced over the processes of a distributed world (World::reduce_partials): the bits of one
  // process whatever the split.
  std::array<double, 2> maxima{0.0, 0.0};  // displacement, speed
  std::array<ExactSum, 2> sums;            // kinetic energy, load work
  std::vector<int> moving;
  const Eigen::Vector3d g = world.settings().gravity;
  for (std::size_t i = 0; i < world.blocks().size(); ++i) {
    const Block& b = world.blocks()[i];
    if (!b.is_dynamic() || !world.counts_block(i)) continue;
    const Eigen::Vector3d d = b.position - start_[i];
    maxima[0] = std::max(maxima[0], d.norm());
    maxima[1] = std::max(maxima[1], b.velocity.norm());
    sums[0].add(b.kinetic_energy());
    // Gravity and the applied loads are constant over a stage (outside a ramp; the water's
    // pressure nearly so as a block moves), so their work is the load times the displacement;
    // during a ramp the current gravity overstates it.
    sums[1].add((b.mass * g + b.applied_force()).dot(d));
    if (d.norm() > 0.1 * r.displacement_limit) moving.push_back(b.index);
  }
  world.reduce_partials(sums, maxima, {});
  r.max_displacement = maxima[0];
  r.max_speed = maxima[1];
  r.kinetic_energy = sums[0].value();
  r.load_work = sums[1].value();
  r.moving_blocks = world.gather_indices(moving);
  const double critical = world.critical_time_step();
  r.time_step_ratio =
      critical > 0.0 && std::isfinite(critical) ? world.next_time_step() / critical : 0.0;
  r.growing_checks = (!ramping && r.max_speed > previous_speed_) ? r.growing_checks + 1 : 0;
  previous_speed_ = r.max_speed;
  const bool past_limit = r.max_displacement > r.displacement_limit;
  const bool accelerating = r.growing_checks >= criteria_.growth_checks &&
                            r.max_displacement > 0.5 * r.displacement_limit;
  if (past_limit || accelerating) r.mechanism = true;
}

MotionMonitor::MotionMonitor(StateReader& in) {
  in.pod(criteria_.displacement_limit);
  in.pod(criteria_.growth_checks);
  start_.resize(in.size());
  for (auto& p : start_) p = in.vec();
  MotionReport& r = report_;
  for (double* x : {&r.max_displacement, &r.displacement_limit, &r.max_speed, &r.kinetic_energy,
                    &r.load_work, &r.elastic_energy_start, &r.time_step_ratio})
    in.pod(*x);
  r.growing_checks = in.pod<std::int32_t>();
  r.moving_blocks.resize(in.size());
  for (int& b : r.moving_blocks) b = in.pod<std::int32_t>();
  r.mechanism = in.pod<std::uint8_t>() != 0;
  in.pod(previous_speed_);
}

void MotionMonitor::save_state(StateWriter& out) const {
  out.pod(criteria_.displacement_limit);
  out.pod(criteria_.growth_checks);
  out.size(start_.size());
  for (const auto& p : start_) out.vec(p);
  const MotionReport& r = report_;
  for (double x : {r.max_displacement, r.displacement_limit, r.max_speed, r.kinetic_energy,
                   r.load_work, r.elastic_energy_start, r.time_step_ratio})
    out.pod(x);
  out.pod(static_cast<std::int32_t>(r.growing_checks));
  out.size(r.moving_blocks.size());
  for (int b : r.moving_blocks) out.pod(static_cast<std::int32_t>(b));
  out.pod(static_cast<std::uint8_t>(r.mechanism));
  out.pod(previous_speed_);
}

bool MotionMonitor::energy_created() const {
  const double stored =
      std::isnan(report_.elastic_energy_start) ? 0.0 : report_.elastic_energy_start;
  const double available = std::max(report_.load_work, 0.0) + stored;
  return report_.kinetic_energy > 1.1 * available + 1e-12;
}

FailureKind classify_failure(const MotionMonitor& monitor, bool blew_up) {
  const MotionReport& r = monitor.report();
  if (r.time_step_ratio > 1.0 || monitor.energy_created()) return FailureKind::diverged;
  if (!std::isfinite(r.kinetic_energy)) return FailureKind::diverged;
  if (r.mechanism) return FailureKind::collapsed;
  // A divergence check tripped under a stable step with the energy accounted for: the blocks
  // were set moving by the loads (e.g. falling after a snap-through).
  if (blew_up) return FailureKind::collapsed;
  return FailureKind::not_converged;
}

bool collapse_is_certain(const MotionMonitor& monitor, const MechanismCriteria& criteria) {
  const MotionReport& r = monitor.report();
  return r.max_displacement > r.displacement_limit && r.growing_checks >= criteria.growth_checks &&
         r.time_step_ratio <= 1.0 && std::isfinite(r.kinetic_energy) && !monitor.energy_created();
}

const char* to_string(FailureKind kind) {
  switch (kind) {
    case FailureKind::collapsed:
      return "collapsed";
    case FailureKind::diverged:
      return "diverged";
    case FailureKind::not_converged:
      return "not_converged";
  }
  return "failed";
}

std::string explain_failure(FailureKind kind, const MotionReport& r, const World& world) {
  std::string blocks;
  for (std::size_t i = 0; i < r.moving_blocks.size() && i < 8; ++i)
    blocks += (i ? ", " : "") + world.blocks()[static_cast<std::size_t>(r.moving_blocks[i])].name;
  if (r.moving_blocks.size() > 8) blocks += ", ...";
  const std::string energy =
      "kinetic energy " + number_text(r.kinetic_energy, "%.3g J") + " against " +
      number_text(r.load_work, "%.3g J") + " of work by the loads and " +
      number_text(r.elastic_energy_start, "%.3g J") + " stored in the joints";
  switch (kind) {
    case FailureKind::collapsed:
      return "physical collapse: a mechanism formed under a stable time step (step " +
             number_text(r.time_step_ratio, "%.2f") + " of the critical one); blocks moving: " +
             (blocks.empty() ? "none past a tenth of the limit" : blocks) +
             "; largest displacement " + number_text(r.max_displacement, "%.3g m") + " (limit " +
             number_text(r.displacement_limit, "%.3g m") + "), speed " +
             number_text(r.max_speed, "%.3g m/s") + "; " + energy +
             ". The model cannot carry this load: this is a result, not a numerical problem. "
             "Use find_collapse = true to bracket the collapse load, or a strength_reduction "
             "stage for a factor of safety";
    case FailureKind::diverged:
      return std::string("numerical blow-up: ") +
             (r.time_step_ratio > 1.0
                  ? "the time step is " + number_text(r.time_step_ratio, "%.3g") +
                        " times the critical estimate sqrt(m/K)"
                  : "energy was created by the integrator") +
             "; " + energy +
             ". Use the automatic time step (time_step = 0) or a smaller safety_factor; check "
             "the joint stiffness against the block masses";
    case FailureKind::not_converged:
      return "no equilibrium within the step limit, but no mechanism either (largest "
             "displacement " +
             number_text(r.max_displacement, "%.3g m") + ", limit " +
             number_text(r.displacement_limit, "%.3g m") +
             "): raise max_steps, add damping, or loosen the tolerances";
  }
  return {};
}

}  // namespace blockdem
