// Overlap of a convex section with a joint's extent: exact for polygons (Sutherland-Hodgman
// clipping of convex polygons) and for discs (centre inside, or distance to an edge below R).
#include "blockdem/rockmass/planar_extent.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace blockdem {
namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Distance from p to the segment [a, b] (m).
double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                        const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

}  // namespace

double signed_area(const std::vector<Eigen::Vector2d>& polygon) {
  double a = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i)
    a += cross2(polygon[i], polygon[(i + 1) % polygon.size()]);
  return 0.5 * a;
}

double clipped_area(std::vector<Eigen::Vector2d> subject,
                    const std::vector<Eigen::Vector2d>& clip) {
  const std::size_t m = clip.size();
  for (std::size_t e = 0; e < m && !subject.empty(); ++e) {
    const Eigen::Vector2d a = clip[e], b = clip[(e + 1) % m];
    auto inside = [&](const Eigen::Vector2d& p) { return cross2(b - a, p - a); };
    std::vector<Eigen::Vector2d> out;
    for (std::size_t i = 0; i < subject.size(); ++i) {
      const Eigen::Vector2d p = subject[i], q = subject[(i + 1) % subject.size()];
      const double sp = inside(p), sq = inside(q);
      if (sp >= 0.0) out.push_back(p);
      if ((sp >= 0.0) != (sq >= 0.0)) out.push_back(p + sp / (sp - sq) * (q - p));
    }
    subject = std::move(out);
  }
  return subject.size() < 3 ? 0.0 : std::abs(signed_area(subject));
}

Overlap overlap(const std::vector<Eigen::Vector3d>& section, const PlanarExtent& ext, double tol) {
  if (section.size() < 3) return Overlap::none;
  std::vector<Eigen::Vector2d> p;
  p.reserve(section.size());
  for (const auto& x : section) {
    const Eigen::Vector3d r = x - ext.centre;
    p.emplace_back(r.dot(ext.axis1), r.dot(ext.axis2));
  }
  if (signed_area(p) < 0.0) std::reverse(p.begin(), p.end());

  if (ext.disc) {
    double far = 0.0;
    for (const auto& q : p) far = std::max(far, q.norm());
    if (far <= ext.radius + tol) return Overlap::inside;
    // The centre inside the section, or an edge within R - tol of it.
    bool centre_inside = true;
    double near = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Eigen::Vector2d a = p[i], b = p[(i + 1) % p.size()];
      if (cross2(b - a, -a) < 0.0) centre_inside = false;
      near = std::min(near, segment_distance(Eigen::Vector2d::Zero(), a, b));
    }
    return centre_inside || near < ext.radius - tol ? Overlap::partial : Overlap::none;
  }

  std::vector<Eigen::Vector2d> clip = ext.polygon;
  if (signed_area(clip) < 0.0) std::reverse(clip.begin(), clip.end());
  bool all_inside = true;
  for (const auto& q : p) {
    for (std::size_t e = 0; e < clip.size() && all_inside; ++e) {
      const Eigen::Vector2d a = clip[e], b = clip[(e + 1) % clip.size()];
      if (cross2(b - a, q - a) / (b - a).norm() < -tol) all_inside = false;
    }
  }
  if (all_inside) return Overlap::inside;
  // Shared area thinner than tol over the section's size counts as none.
  const double area = clipped_area(p, clip);
  double size = 0.0;
  for (const auto& q : p) size = std::max(size, (q - p.front()).norm());
  return area > tol * size ? Overlap::partial : Overlap::none;
}

}  // namespace blockdem
