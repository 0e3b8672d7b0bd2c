// Parametric clipping of a segment by half-spaces (Cyrus & Beck 1978).
#include "blockdem/geometry/segment_clip.hpp"

#include <algorithm>

namespace blockdem {

std::optional<std::pair<double, double>> clip_segment(std::span<const Halfspace> planes,
                                                      const Eigen::Vector3d& p0,
                                                      const Eigen::Vector3d& p1) {
  const Eigen::Vector3d d = p1 - p0;
  double t_in = 0.0, t_out = 1.0;
  for (const Halfspace& h : planes) {
    // n·(p0 + t d) <= offset: slack(p0) >= t n·d.
    const double slack = h.slack(p0);
    const double rate = h.normal.dot(d);
    if (rate == 0.0) {
      if (slack < 0.0) return std::nullopt;  // parallel and outside
      continue;
    }
    const double t = slack / rate;
    if (rate > 0.0) {
      t_out = std::min(t_out, t);  // leaving through this plane
    } else {
      t_in = std::max(t_in, t);  // entering through it
    }
    if (!(t_in < t_out)) return std::nullopt;
  }
  return std::make_pair(t_in, t_out);
}

}  // namespace blockdem
