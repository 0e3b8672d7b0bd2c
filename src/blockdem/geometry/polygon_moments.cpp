// Area, centroid, polar and radial moments of a planar convex polygon in closed form.
#include "blockdem/geometry/polygon_moments.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace blockdem {
namespace {

// Antiderivatives in ψ of sec³ψ and sec⁴ψ:
//   ∫ sec³ = (sec ψ tan ψ + ln|sec ψ + tan ψ|) / 2,   ∫ sec⁴ = tan ψ + tan³ψ / 3.
double integral_sec3(double t) {  // t = tan ψ, sec ψ = sqrt(1 + t²) > 0 for |ψ| < π/2
  const double s = std::sqrt(1.0 + t * t);
  return 0.5 * (s * t + std::asinh(t));  // ln(sec + tan) = asinh(tan)
}
double integral_sec4(double t) {
  return t + t * t * t / 3.0;
}

// The moments about `pole`; with `second` false only the area and the centroid (the same
// arithmetic for those two, so the same bits).
PolygonMoments moments(std::span<const Eigen::Vector3d> vertices, const Eigen::Vector3d& pole,
                       bool second) {
  PolygonMoments m;
  const std::size_t n = vertices.size();
  if (n < 3) return m;
  // Unit normal of the polygon's plane from its vector area, summed about a vertex: about the
  // origin, the terms of a sliver far from it cancel to round-off and may turn the normal over.
  Eigen::Vector3d vector_area = Eigen::Vector3d::Zero();
  for (std::size_t i = 1; i + 1 < n; ++i)
    vector_area += (vertices[i] - vertices[0]).cross(vertices[i + 1] - vertices[0]);
  if (!(vector_area.norm() > 0.0)) return m;
  const Eigen::Vector3d normal = vector_area.normalized();

  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p = vertices[i] - pole;
    const Eigen::Vector3d q = vertices[(i + 1) % n] - pole;
    // Signed area of the triangle (pole, p, q): positive when it turns like the polygon.
    const double area = 0.5 * normal.dot(p.cross(q));
    m.area += area;
    first += area * (p + q) / 3.0;
    if (!second) continue;
    const Eigen::Vector3d edge = q - p;
    const double length = edge.norm();
    // A sliver (pole on or within round-off of the edge's line) adds at most |area| r_max², below
    // round-off of the sum; skipping it keeps tan ψ = along·p / h finite.
    if (length == 0.0 || std::abs(area) <= 1e-14 * length * length) continue;
    // Distance h from the pole to the edge's line and the tangents of the edge ends' angles
    // measured from the foot of the perpendicular.
    const Eigen::Vector3d along = edge / length;
    const double h = 2.0 * std::abs(area) / length;
    const double t1 = along.dot(p) / h, t2 = along.dot(q) / h;
    const double sign = area > 0.0 ? 1.0 : -1.0;
    m.radial_moment += sign * h * h * h / 3.0 * (integral_sec3(t2) - integral_sec3(t1));
    m.polar_moment += sign * h * h * h * h / 4.0 * (integral_sec4(t2) - integral_sec4(t1));
  }
  // A polygon of no area within round-off (a sliver of a contact touching along an edge) has no
  // moments: the signed fan may sum to a few ulps below zero, never a physical value.
  if (!(m.area > 0.0)) return PolygonMoments{};
  m.centroid = pole + first / m.area;
  // Both integrands are non-negative; round-off in the signed fan must not make them negative.
  m.polar_moment = std::max(0.0, m.polar_moment);
  m.radial_moment = std::max(0.0, m.radial_moment);
  return m;
}

// Moments about the centroid found in a first pass about the first vertex.
PolygonMoments about_centroid(std::span<const Eigen::Vector3d> vertices, bool second) {
  const PolygonMoments about_first =
      vertices.size() < 3 ? PolygonMoments{} : moments(vertices, vertices[0], false);
  if (about_first.area == 0.0) return about_first;
  return moments(vertices, about_first.centroid, second);
}

}  // namespace

PolygonMoments polygon_moments(std::span<const Eigen::Vector3d> vertices,
                               const Eigen::Vector3d& pole) {
  return moments(vertices, pole, true);
}

PolygonMoments polygon_moments_about_centroid(std::span<const Eigen::Vector3d> vertices) {
  return about_centroid(vertices, true);
}

PolygonMoments polygon_area_centroid(std::span<const Eigen::Vector3d> vertices) {
  return about_centroid(vertices, false);
}

Eigen::Matrix3d polygon_second_moment(std::span<const Eigen::Vector3d> vertices,
                                      const Eigen::Vector3d& c, const Eigen::Vector3d& n) {
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const Eigen::Vector3d p = vertices[i] - c;
    const Eigen::Vector3d q = vertices[(i + 1) % vertices.size()] - c;
    const double area = 0.5 * p.cross(q).dot(n);  // signed by the order about n
    const Eigen::Vector3d s = p + q;
    second += (area / 12.0) * (p * p.transpose() + q * q.transpose() + s * s.transpose());
  }
  // Vertices clockwise about n: every signed triangle negative.
  if (second.trace() < 0.0) second = -second;
  return second;
}

std::vector<Eigen::Vector3d> clip_polygon(std::span<const Eigen::Vector3d> vertices,
                                          const Halfspace& h) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(vertices.size() + 1);
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const Eigen::Vector3d& p = vertices[i];
    const Eigen::Vector3d& q = vertices[(i + 1) % vertices.size()];
    const double dp = h.signed_distance(p);
    const double dq = h.signed_distance(q);
    if (dp <= 0.0) out.push_back(p);
    // The edge crosses the plane: its point on the plane, interpolated from the inside end.
    if ((dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0))
      out.push_back(p + (dp / (dp - dq)) * (q - p));
  }
  if (out.size() < 3) out.clear();
  return out;
}

}  // namespace blockdem
