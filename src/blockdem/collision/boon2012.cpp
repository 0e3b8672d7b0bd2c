// Boon et al. (2012) narrow phase: steps 1-5 of DESIGN section 2.
#include "blockdem/collision/boon2012.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "blockdem/collision/analytic_centre.hpp"
#include "blockdem/collision/inscribed_ball.hpp"

namespace blockdem {

Eigen::Vector3d potential_gradient(std::span<const Halfspace> planes, const Eigen::Vector3d& x,
                                   double rounding_distance) {
  Eigen::Vector3d grad = Eigen::Vector3d::Zero();
  double nearest = -std::numeric_limits<double>::infinity();
  const Halfspace* nearest_plane = nullptr;
  bool any = false;
  for (const auto& p : planes) {
    const double h = p.normal.dot(x) - p.offset;  // negative inside
    if (h + rounding_distance > 0.0) {
      grad += 2.0 * (h + rounding_distance) * p.normal;
      any = true;
    }
    if (h > nearest) {
      nearest = h;
      nearest_plane = &p;
    }
  }
  if (!any && nearest_plane != nullptr) grad = 2.0 * rounding_distance * nearest_plane->normal;
  return grad;
}

double chord_length(std::span<const Halfspace> planes, const Eigen::Vector3d& x,
                    const Eigen::Vector3d& u) {
  double forward = std::numeric_limits<double>::infinity();
  double backward = std::numeric_limits<double>::infinity();
  for (const auto& p : planes) {
    const double c = p.normal.dot(u);
    const double s = p.offset - p.normal.dot(x);  // slack, positive inside
    if (c > 1e-14) forward = std::min(forward, s / c);
    if (c < -1e-14) backward = std::min(backward, -s / c);
  }
  return forward + backward;
}

ContactGeometry boon2012_contact(std::span<const Halfspace> planes_a,
                                 std::span<const Halfspace> planes_b, double extent,
                                 const Boon2012Settings& settings, Boon2012Cache* cache) {
  ContactGeometry out;
  // All planes of both blocks, in one buffer (on the stack for ordinary blocks).
  constexpr std::size_t kStack = 96;
  Halfspace stack_buffer[kStack];
  std::vector<Halfspace> heap_buffer;
  const std::size_t total = planes_a.size() + planes_b.size();
  Halfspace* all = stack_buffer;
  if (total > kStack) {
    heap_buffer.resize(total);
    all = heap_buffer.data();
  }
  std::copy(planes_a.begin(), planes_a.end(), all);
  std::copy(planes_b.begin(), planes_b.end(), all + planes_a.size());
  const std::span<const Halfspace> both(all, total);

  // 1. Overlap test: the largest ball inside A∩B (4-variable LP).
  const InscribedBall ball = largest_inscribed_ball(both);
  out.inscribed_radius = ball.radius;
  out.inscribed_centre = ball.center;
  if (!ball.bounded || !(ball.radius > settings.overlap_tolerance)) return out;
  out.touching = true;

  // 2. Contact point: analytic centre of all planes, from the previous step's point when it is
  //    still strictly inside, otherwise from the ball's centre.
  Eigen::Vector3d start = ball.center;
  if (cache != nullptr && cache->valid) {
    bool inside = true;
    for (const auto& p : both) inside = inside && p.offset - p.normal.dot(cache->last_point) > 0.0;
    if (inside) start = cache->last_point;
  }
  const AnalyticCentreResult centre = analytic_centre(both, start);
  out.point = centre.point;
  if (cache != nullptr) {
    cache->valid = true;
    cache->last_point = out.point;
  }

  // 3. Normal from the two inner potential particles, A to B.
  const Eigen::Vector3d ga = potential_gradient(planes_a, out.point, settings.rounding_distance);
  const Eigen::Vector3d gb = potential_gradient(planes_b, out.point, settings.rounding_distance);
  out.normal = (ga - gb).normalized();

  // 4. Overlap distance: the chord of A∩B through x_c along n.
  out.overlap = chord_length(both, out.point, out.normal);

  // 5. Contact area: the slice of A∩B by the plane through x_c normal to n.
  out.slice = slice_halfspaces(both, out.point, out.normal, extent);
  out.area = out.slice.area();
  return out;
}

}  // namespace blockdem
