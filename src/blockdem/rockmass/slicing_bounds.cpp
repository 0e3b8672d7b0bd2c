// Estimates of a rock mass's joints and blocks before it is cut, against the settings' limits.
#include "blockdem/rockmass/slicing_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "blockdem/numerics/number_text.hpp"

namespace blockdem {
namespace {

[[noreturn]] void refuse(const std::string& key, const std::string& why) {
  throw std::invalid_argument(key + ": " + why);
}

}  // namespace

void check_slicing_work(const RockMassSpec& spec, const ConvexCell& region) {
  const SlicingSettings& s = spec.settings;
  double diameter = 0.0;
  for (const auto& v : region.vertices()) {
    for (const auto& w : region.vertices()) diameter = std::max(diameter, (v - w).norm());
  }
  // Elementary symmetric sums of the sets' plane counts so far (e_1, e_2, e_3).
  double e1 = 0.0, e2 = 0.0, e3 = 0.0;
  for (std::size_t i = 0; i < spec.joint_sets.size(); ++i) {
    const JointSet& set = spec.joint_sets[i];
    const std::string key = "joint_sets[" + std::to_string(i + 1) + "]";
    const std::string who = "joint set \"" + set.name + "\"";
    double planes = static_cast<double>(set.centres.size());
    JointPlaneEstimate estimate;
    if (set.centres.empty()) {
      const auto [lo, hi] = region.extent_along(set.normal());
      estimate = estimate_joint_planes(set, lo, hi);
      planes = estimate.planes;
    }
    e3 += e2 * planes;
    e2 += e1 * planes;
    e1 += planes;
    const double blocks = 1.0 + e1 + e2 + e3;
    if (!(blocks <= static_cast<double>(s.max_blocks))) {
      refuse(key + (set.centres.empty() ? ".spacing" : ".extent.centres"),
             who + " brings the joint sets up to about " + number_text(blocks, "%.3g") +
                 " blocks in the region (" + number_text(planes, "%.3g") +
                 " joint planes of this set cross it), more than max_blocks = " +
                 std::to_string(s.max_blocks) +
                 ": widen the spacing or shrink the region, or raise [rock_mass] max_blocks "
                 "(about 3.5 kB of memory per block)");
    }
    if (set.extent && set.centres.empty()) {
      const double section = std::numbers::pi * diameter * diameter / 4.0;
      const double per_plane =
          std::max(1.0, std::round(set.persistence * section / set.extent->area()));
      const double joints = planes * per_plane;
      if (!(joints <= static_cast<double>(s.max_joints))) {
        refuse(key + ".extent",
               who + " would place up to about " + number_text(joints, "%.3g") + " joints (" +
                   number_text(planes, "%.3g") + " planes, up to " +
                   number_text(per_plane, "%.3g") + " joints on each at persistence " +
                   number_text(set.persistence, "%.3g") +
                   "), more than max_joints = " + std::to_string(s.max_joints) +
                   ": enlarge the joints or lower the persistence, or raise [rock_mass] "
                   "max_joints");
      }
    }
    if (!(estimate.draws <= kMaxSpacingDraws)) {
      refuse(key + ".origin",
             who + ": placing its joints would draw about " + number_text(estimate.draws, "%.3g") +
                 " random spacings from the origin's joint across the region, more than " +
                 number_text(kMaxSpacingDraws, "%.3g") +
                 ": put the origin in or near the region, or widen the spacing");
    }
  }
}

}  // namespace blockdem
