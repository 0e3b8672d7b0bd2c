// Law of a contact from the faces in contact (per-face provenance of cut rock blocks).
#include "blockdem/response/face_laws.hpp"

#include <limits>

namespace blockdem {

std::pair<int, double> contact_face(const Block& block, const Eigen::Vector3d& outward,
                                    const Eigen::Vector3d& point, double reach) {
  int best = -1, any = -1;
  double best_dot = -std::numeric_limits<double>::infinity(), any_dot = best_dot;
  const auto& planes = block.world_planes;
  for (int i = 0; i < static_cast<int>(planes.size()); ++i) {
    const double dot = planes[i].normal.dot(outward);
    if (dot > any_dot) {
      any_dot = dot;
      any = i;
    }
    if (std::abs(planes[i].signed_distance(point)) <= reach && dot > best_dot) {
      best_dot = dot;
      best = i;
    }
  }
  return best >= 0 ? std::make_pair(best, best_dot) : std::make_pair(any, any_dot);
}

int face_law_for_contact(const Block& a, std::span<const int> laws_a, const Block& b,
                         std::span<const int> laws_b, const ContactGeometry& g, int group_law) {
  if (laws_a.empty() && laws_b.empty()) return group_law;
  // The contact point lies inside the overlap, within its depth of both contact faces.
  // The blocks' copies of their shapes' radii (refreshed with the world planes read below).
  const double reach = 2.0 * g.overlap + 1e-9 * (a.bounding_radius + b.bounding_radius);
  int law_a = -1, law_b = -1;
  double dot_a = -2.0, dot_b = -2.0;
  if (!laws_a.empty()) {
    const auto [face, dot] = contact_face(a, g.normal, g.point, reach);
    law_a = laws_a[face];
    dot_a = dot;
  }
  if (!laws_b.empty()) {
    const auto [face, dot] = contact_face(b, -g.normal, g.point, reach);
    law_b = laws_b[face];
    dot_b = dot;
  }
  if (law_a >= 0 && law_b >= 0) return dot_b > dot_a ? law_b : law_a;
  if (law_a >= 0) return law_a;
  if (law_b >= 0) return law_b;
  return group_law;
}

}  // namespace blockdem
