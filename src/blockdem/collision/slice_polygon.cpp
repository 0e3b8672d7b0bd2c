// Sutherland-Hodgman clipping of a large square by half-planes, in the plane's 2D coordinates.
#include "blockdem/collision/slice_polygon.hpp"

#include <cmath>

namespace blockdem {

double SlicePolygon::area() const {
  double twice = 0.0;
  const std::size_t n = vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const auto& a = vertices[i];
    const auto& b = vertices[(i + 1) % n];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * std::abs(twice);
}

Eigen::Vector2d SlicePolygon::centroid_2d() const {
  double twice = 0.0;
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  const std::size_t n = vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const auto& a = vertices[i];
    const auto& b = vertices[(i + 1) % n];
    const double cross = a.x() * b.y() - a.y() * b.x();
    twice += cross;
    c += (a + b) * cross;
  }
  if (twice == 0.0) return n > 0 ? vertices[0] : Eigen::Vector2d::Zero();
  return c / (3.0 * twice);
}

void plane_axes(const Eigen::Vector3d& normal, Eigen::Vector3d& axis_u, Eigen::Vector3d& axis_v) {
  // Cross with the world axis least aligned with the normal.
  const Eigen::Vector3d a = normal.cwiseAbs();
  Eigen::Vector3d helper = Eigen::Vector3d::UnitX();
  if (a.y() <= a.x() && a.y() <= a.z()) helper = Eigen::Vector3d::UnitY();
  if (a.z() < a.x() && a.z() < a.y()) helper = Eigen::Vector3d::UnitZ();
  axis_u = helper.cross(normal).normalized();
  axis_v = normal.cross(axis_u);
}

SlicePolygon slice_halfspaces(std::span<const Halfspace> planes, const Eigen::Vector3d& origin,
                              const Eigen::Vector3d& normal, double extent) {
  SlicePolygon poly;
  poly.origin = origin;
  poly.normal = normal;
  plane_axes(normal, poly.axis_u, poly.axis_v);
  std::vector<Eigen::Vector2d> cur = {
      {-extent, -extent}, {extent, -extent}, {extent, extent}, {-extent, extent}};
  std::vector<Eigen::Vector2d> next;
  cur.reserve(planes.size() + 4);
  next.reserve(planes.size() + 4);
  for (const auto& p : planes) {
    // In plane coordinates the half-space reads a·y <= s, a = (n·u, n·v), s = d - n·origin.
    const Eigen::Vector2d a(p.normal.dot(poly.axis_u), p.normal.dot(poly.axis_v));
    const double s = p.offset - p.normal.dot(origin);
    next.clear();
    const std::size_t n = cur.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector2d& P = cur[i];
      const Eigen::Vector2d& Q = cur[(i + 1) % n];
      const double fp = a.dot(P) - s;
      const double fq = a.dot(Q) - s;
      if (fp <= 0.0) next.push_back(P);
      if ((fp < 0.0 && fq > 0.0) || (fp > 0.0 && fq < 0.0)) {
        next.push_back(P + (fp / (fp - fq)) * (Q - P));
      }
    }
    cur.swap(next);
    if (cur.size() < 3) {
      cur.clear();
      break;
    }
  }
  poly.vertices = std::move(cur);
  return poly;
}

}  // namespace blockdem
