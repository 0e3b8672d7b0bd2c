// Shared faces of two blocks: A's face polygon clipped (Sutherland-Hodgman, one half-space at a
// time) by B's planes other than the coincident one.
#include "blockdem/collision/shared_face.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "blockdem/collision/small_vector.hpp"
#include "blockdem/geometry/polygon_moments.hpp"

namespace blockdem {
namespace {

// A face polygon of the usual size stays on the stack.
using ClipPolygon = SmallVector<Eigen::Vector3d, 16>;

/// Keeps the part of the convex polygon `poly` with n·x <= d + tolerance, into `out`; returns the
/// least n·x - d over `poly`'s vertices (each vertex's distance found once).
double clip(const ClipPolygon& poly, const Halfspace& h, double tolerance, ClipPolygon& out) {
  out.clear();
  const std::size_t n = poly.size();
  if (n == 0) return std::numeric_limits<double>::infinity();
  const double s0 = h.signed_distance(poly[0]);
  double least = s0;
  double sp = s0 - tolerance;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d& p = poly[i];
    const Eigen::Vector3d& q = poly[(i + 1) % n];
    double sq = s0 - tolerance;
    if (i + 1 < n) {
      const double s = h.signed_distance(q);
      least = std::min(least, s);
      sq = s - tolerance;
    }
    if (sp <= 0.0) out.push_back(p);
    if ((sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0))
      out.push_back(p + (sp / (sp - sq)) * (q - p));
    sp = sq;
  }
  return least;
}

template <class VertexAt>
std::optional<SharedFace> shared_face_of_faces(const Polyhedron& shape_a, const VertexAt& vertex_a,
                                               std::span<const Halfspace> planes_a,
                                               std::span<const Halfspace> planes_b,
                                               double tolerance, double min_area) {
  std::optional<SharedFace> best;
  for (const Face& face : shape_a.faces()) {
    const Halfspace& pa = planes_a[static_cast<std::size_t>(face.plane)];
    for (std::size_t j = 0; j < planes_b.size(); ++j) {
      const Halfspace& pb = planes_b[j];
      // Opposite normals and the same plane: n_b = -n_a and d_b = -d_a.
      if (pa.normal.dot(pb.normal) > -1.0 + 1e-9) continue;
      if (std::abs(pa.offset + pb.offset) > tolerance) continue;
      ClipPolygon buffers[2];
      ClipPolygon* poly = &buffers[0];
      ClipPolygon* clipped = &buffers[1];
      for (int v : face.vertices) poly->push_back(vertex_a(static_cast<std::size_t>(v)));
      // A sliver found early: after the clip by B's plane k, the polygon lies within a slab of
      // that plane, between the least distance of the polygon clipped (`least`) and the
      // tolerance; across the face's plane the slab is (tolerance - least) / s wide (s the sine
      // of the planes' angle), so the polygon's area is at most that width times the face's
      // diameter D (at most twice its largest distance from its first vertex). Below a quarter
      // of min_area the polygon is refused below in any case (its vector area, twice its area,
      // against min_area), so it is refused here without the clips that remain; only where
      // min_area is far above the round-off of the area of a polygon of that size.
      // (Squares compared, without a square root per vertex and plane.)
      double reach2 = 0.0;
      for (std::size_t v = 1; v < poly->size(); ++v)
        reach2 = std::max(reach2, ((*poly)[v] - (*poly)[0]).squaredNorm());
      const double diameter2 = 4.0 * reach2;
      const double quarter2 = 0.0625 * min_area * min_area;
      const bool early = min_area > 1e-12 * diameter2;
      const Eigen::Vector3d face_normal = pa.normal.normalized();
      bool sliver = false;
      for (std::size_t k = 0; k < planes_b.size() && poly->size() >= 3; ++k) {
        if (k == j) continue;
        const double least = clip(*poly, planes_b[k], tolerance, *clipped);
        std::swap(poly, clipped);
        if (early && poly->size() >= 3) {
          const Eigen::Vector3d& nk = planes_b[k].normal;
          const double sine2 = (nk - nk.dot(face_normal) * face_normal).squaredNorm();
          const double width = tolerance - least;  // >= 0: the polygon clipped is not empty
          if (width * width * diameter2 < quarter2 * sine2) {
            sliver = true;
            break;
          }
        }
      }
      if (sliver || poly->size() < 3) continue;
      // Half the vector area's length: the polygon's area to round-off, which the moments'
      // own sum (the area kept) differs from by far less than the factor 2 allowed here.
      Eigen::Vector3d vector_area = Eigen::Vector3d::Zero();
      for (std::size_t i = 1; i + 1 < poly->size(); ++i)
        vector_area += ((*poly)[i] - (*poly)[0]).cross((*poly)[i + 1] - (*poly)[0]);
      if (vector_area.norm() < min_area) continue;
      const PolygonMoments m =
          polygon_area_centroid(std::span<const Eigen::Vector3d>(poly->data(), poly->size()));
      if (!(m.area > tolerance * tolerance) || !(m.area > min_area) ||
          (best && m.area <= best->area))
        continue;
      best = SharedFace{face.plane, static_cast<int>(j),
                        pa.normal,  m.centroid,
                        m.area,     std::vector<Eigen::Vector3d>(poly->begin(), poly->end())};
    }
  }
  return best;
}

}  // namespace

std::optional<SharedFace> shared_face(const Polyhedron& shape_a,
                                      std::span<const Eigen::Vector3d> vertices_a,
                                      std::span<const Halfspace> planes_a,
                                      std::span<const Halfspace> planes_b, double tolerance,
                                      double min_area) {
  return shared_face_of_faces(
      shape_a, [&](std::size_t v) -> const Eigen::Vector3d& { return vertices_a[v]; }, planes_a,
      planes_b, tolerance, min_area);
}

std::optional<SharedFace> shared_face(const Polyhedron& shape_a,
                                      const Eigen::Quaterniond& orientation_a,
                                      const Eigen::Vector3d& position_a,
                                      std::span<const Halfspace> planes_a,
                                      std::span<const Halfspace> planes_b, double tolerance,
                                      double min_area) {
  const std::span<const Eigen::Vector3d> body = shape_a.vertices();
  return shared_face_of_faces(
      shape_a,
      [&](std::size_t v) -> Eigen::Vector3d { return position_a + orientation_a * body[v]; },
      planes_a, planes_b, tolerance, min_area);
}

}  // namespace blockdem
