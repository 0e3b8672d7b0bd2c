// The block that sets the explicit time step: each free block's own critical step before
// contacts form (World::own_critical_steps), the smallest against the median block's, and a
// warning when one block holds the whole model back.
#pragma once

#include <cstddef>
#include <string>

#include "blockdem/world/world.hpp"

namespace blockdem {

struct TimeStepReport {
  /// An outlier's own step is this many times below the median block's, or more.
  static constexpr double kOutlierRatio = 10.0;

  int block = -1;  ///< the block with the smallest own critical step (-1: no free block)
  std::string name;
  double volume = 0.0;         ///< (m^3)
  double aspect_ratio = 0.0;   ///< largest over smallest width along its face normals (-)
  double critical_step = 0.0;  ///< its own critical step sqrt(m/K) (s)
  double time_step = 0.0;      ///< the automatic step it allows: safety_factor · critical_step (s)
  double median_step = 0.0;    ///< the median free block's own critical step (s)
  std::size_t free_blocks = 0;  ///< blocks that move
  /// median_step >= kOutlierRatio · critical_step.
  bool outlier = false;
};

/// Largest over smallest width of a shape, the widths measured along its face normals (1 for a
/// cube; the measure of `[rock_mass] max_aspect_ratio`).
double width_aspect_ratio(const Polyhedron& shape);

/// The report for the world as it stands (its blocks' true masses, before any contact).
TimeStepReport time_step_report(const World& world);

/// One line naming the block, its volume, aspect ratio and the step it allows, and the median
/// block's; empty without a free block or a joint law with stiffness.
std::string describe(const TimeStepReport& report);

/// For an outlier: what it costs and what to do (`min_block_volume`, `max_aspect_ratio`, density
/// scaling); empty otherwise.
std::string outlier_warning(const TimeStepReport& report);

}  // namespace blockdem
