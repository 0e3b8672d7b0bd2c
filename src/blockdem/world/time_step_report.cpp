// The block that sets the time step, named with its size and shape.
#include "blockdem/world/time_step_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "blockdem/numerics/number_text.hpp"

namespace blockdem {
double width_aspect_ratio(const Polyhedron& shape) {
  double widest = 0.0;
  double thinnest = std::numeric_limits<double>::infinity();
  for (const Halfspace& plane : shape.planes()) {
    // The width along a face normal: the spread of the vertices' heights along it.
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (const Eigen::Vector3d& v : shape.vertices()) {
      const double h = plane.normal.dot(v);
      lo = std::min(lo, h);
      hi = std::max(hi, h);
    }
    widest = std::max(widest, hi - lo);
    thinnest = std::min(thinnest, hi - lo);
  }
  return thinnest > 0.0 ? widest / thinnest : std::numeric_limits<double>::infinity();
}

TimeStepReport time_step_report(const World& world) {
  TimeStepReport r;
  const std::vector<double> steps = world.own_critical_steps();
  double smallest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < steps.size(); ++i) {
    if (world.blocks()[i].is_dynamic()) ++r.free_blocks;
    // The first of equal steps: the lowest index.
    if (steps[i] < smallest) {
      smallest = steps[i];
      r.block = static_cast<int>(i);
    }
  }
  if (r.block < 0) return r;
  const Block& b = world.blocks()[static_cast<std::size_t>(r.block)];
  r.name = b.name;
  r.volume = b.shape.volume();
  r.aspect_ratio = width_aspect_ratio(b.shape);
  r.critical_step = smallest;
  r.time_step = world.settings().safety_factor * smallest;
  r.median_step = world.median_critical_step();
  r.outlier = r.median_step >= TimeStepReport::kOutlierRatio * r.critical_step;
  return r;
}

std::string describe(const TimeStepReport& r) {
  if (r.block < 0) return {};
  return "time step set by block '" + r.name + "' (#" + std::to_string(r.block) + ": " +
         number_text(r.volume, "%.3g m3") + ", aspect ratio " +
         number_text(r.aspect_ratio, "%.3g") + "): it allows " +
         number_text(r.time_step, "%.3g s") + " (critical " +
         number_text(r.critical_step, "%.3g s") + "); the median of " +
         std::to_string(r.free_blocks) + " free blocks allows " +
         number_text(r.time_step / r.critical_step * r.median_step, "%.3g s");
}

std::string outlier_warning(const TimeStepReport& r) {
  if (!r.outlier) return {};
  return "block '" + r.name + "' (" + number_text(r.volume, "%.3g m3") + ", aspect ratio " +
         number_text(r.aspect_ratio, "%.3g") + ") allows a time step " +
         number_text(r.median_step / r.critical_step, "%.3g") +
         " times smaller than the median block's, and every step of a stage without density "
         "scaling is that short. Remove or merge such blocks ([rock_mass] min_block_volume, "
         "max_aspect_ratio), or keep density scaling on in the quasi-static stages (the default; "
         "duration stages run at this step)";
}

}  // namespace blockdem
