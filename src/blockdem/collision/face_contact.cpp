// Cells of linear closure over the projection of A∩B on the contact plane.
#include "blockdem/collision/face_contact.hpp"

#include <cmath>

#include "blockdem/collision/slice_polygon.hpp"

namespace blockdem {
namespace {

// A linear function of the plane coordinates y = (a, b): f(y) = c0 + c·y.
struct Linear {
  double c0 = 0.0;
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  double operator()(const Eigen::Vector2d& y) const { return c0 + c.dot(y); }
  Linear operator-(const Linear& o) const { return {c0 - o.c0, c - o.c}; }
};

// Keeps the part of `poly` where f(y) <= 0 (Sutherland-Hodgman, one half-plane).
void clip(std::vector<Eigen::Vector2d>& poly, const Linear& f,
          std::vector<Eigen::Vector2d>& scratch) {
  scratch.clear();
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& p = poly[i];
    const Eigen::Vector2d& q = poly[(i + 1) % n];
    const double fp = f(p), fq = f(q);
    if (fp <= 0.0) scratch.push_back(p);
    if ((fp < 0.0 && fq > 0.0) || (fp > 0.0 && fq < 0.0))
      scratch.push_back(p + (fp / (fp - fq)) * (q - p));
  }
  poly.swap(scratch);
  if (poly.size() < 3) poly.clear();
}

}  // namespace

FaceContactGeometry face_contact_geometry(std::span<const Halfspace> planes_a,
                                          std::span<const Halfspace> planes_b,
                                          const Eigen::Vector3d& origin,
                                          const Eigen::Vector3d& normal, double extent,
                                          const FaceContactSettings& settings) {
  FaceContactGeometry out;
  const double cos_face = std::cos(settings.face_angle);
  bool face = false;
  for (const auto& p : planes_a) face |= p.normal.dot(normal) > cos_face;
  for (const auto& p : planes_b) face |= p.normal.dot(normal) < -cos_face;
  if (!face) return out;
  out.face_type = true;

  Eigen::Vector3d u, v;
  plane_axes(normal, u, v);
  // Every plane in plane coordinates: slack s(y) = s0 - (n·u) a - (n·v) b.
  std::vector<Linear> top, bottom, lateral;
  auto add = [&](const Halfspace& p) {
    const double c = p.normal.dot(normal);
    const Linear slack{p.offset - p.normal.dot(origin),
                       Eigen::Vector2d(-p.normal.dot(u), -p.normal.dot(v))};
    if (std::abs(c) <= settings.lateral_tolerance) {
      lateral.push_back({-slack.c0, -slack.c});  // inside where -slack <= 0
    } else if (c > 0.0) {
      top.push_back({slack.c0 / c, slack.c / c});  // t <= s/c
    } else {
      bottom.push_back({slack.c0 / c, slack.c / c});  // t >= s/c
    }
  };
  for (const auto& p : planes_a) add(p);
  for (const auto& p : planes_b) add(p);
  if (top.empty() || bottom.empty()) return out;

  // Ties (two planes giving the same chord end) go to the lower index, so that no region is
  // counted twice.
  const Linear tie{1e-12 * extent, Eigen::Vector2d::Zero()};
  std::vector<Eigen::Vector2d> poly, scratch;
  for (std::size_t i = 0; i < top.size(); ++i) {
    for (std::size_t k = 0; k < bottom.size(); ++k) {
      poly = {{-extent, -extent}, {extent, -extent}, {extent, extent}, {-extent, extent}};
      // Closure of this pair must be non-negative: bottom_k - top_i <= 0.
      clip(poly, bottom[k] - top[i], scratch);
      for (const auto& l : lateral) {
        if (poly.empty()) break;
        clip(poly, l, scratch);
      }
      // Plane i is the lowest top, plane k the highest bottom.
      for (std::size_t j = 0; j < top.size() && !poly.empty(); ++j) {
        if (j < i) clip(poly, top[i] - top[j] - Linear{-tie.c0, tie.c}, scratch);
        if (j > i) clip(poly, top[i] - top[j], scratch);
      }
      for (std::size_t j = 0; j < bottom.size() && !poly.empty(); ++j) {
        if (j < k) clip(poly, bottom[j] - bottom[k] - Linear{-tie.c0, tie.c}, scratch);
        if (j > k) clip(poly, bottom[j] - bottom[k], scratch);
      }
      if (poly.empty()) continue;
      ClosureCell cell;
      const Linear g = top[i] - bottom[k];
      for (const auto& y : poly) {
        cell.vertices.push_back(origin + y.x() * u + y.y() * v);
        cell.closures.push_back(std::max(0.0, g(y)));
      }
      out.cells.push_back(std::move(cell));
    }
  }
  return out;
}

}  // namespace blockdem
