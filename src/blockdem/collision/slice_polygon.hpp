// The polygon in which a plane cuts an intersection of half-spaces (exact half-plane clipping).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <initializer_list>
#include <span>
#include <utility>
#include <vector>

#include "blockdem/geometry/halfspace.hpp"

namespace blockdem {

/// The vertices of a slice polygon: a small vector of 2D points that holds up to `kInline`
/// points in place (no heap allocation, the common case: two boxes give at most 8) and moves
/// them all to the heap beyond that. Copies and moves copy only the points in use.
class SliceVertices {
 public:
  static constexpr std::size_t kInline = 16;

  SliceVertices() = default;
  SliceVertices(std::initializer_list<Eigen::Vector2d> points);
  SliceVertices(const SliceVertices& other) { *this = other; }
  SliceVertices(SliceVertices&& other) noexcept { *this = std::move(other); }
  SliceVertices& operator=(const SliceVertices& other);
  SliceVertices& operator=(SliceVertices&& other) noexcept;

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const Eigen::Vector2d* data() const { return heap_.empty() ? inline_.data() : heap_.data(); }
  Eigen::Vector2d* data() { return heap_.empty() ? inline_.data() : heap_.data(); }
  const Eigen::Vector2d& operator[](std::size_t i) const { return data()[i]; }
  Eigen::Vector2d& operator[](std::size_t i) { return data()[i]; }
  const Eigen::Vector2d* begin() const { return data(); }
  const Eigen::Vector2d* end() const { return data() + size_; }

  void clear() {
    heap_.clear();
    size_ = 0;
  }
  void push_back(const Eigen::Vector2d& p);
  /// Replaces the contents by the n points at `points`.
  void assign(const Eigen::Vector2d* points, std::size_t n);

 private:
  std::array<Eigen::Vector2d, kInline> inline_;  // uninitialised beyond size_ (Eigen)
  std::vector<Eigen::Vector2d> heap_;            // all points when size_ > kInline, else empty
  std::size_t size_ = 0;
};

/// A convex polygon in a plane through `origin` with orthonormal in-plane axes `axis_u`, `axis_v`
/// (right-handed with the plane normal: axis_u × axis_v = normal). Vertices are 2D plane
/// coordinates (m), counter-clockwise about the normal.
struct SlicePolygon {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d axis_u = Eigen::Vector3d::UnitX();
  Eigen::Vector3d axis_v = Eigen::Vector3d::UnitY();
  SliceVertices vertices;

  double area() const;                  ///< (m^2)
  Eigen::Vector2d centroid_2d() const;  ///< area centroid in plane coordinates (m)
  Eigen::Vector3d to_world(const Eigen::Vector2d& p) const {
    return origin + p.x() * axis_u + p.y() * axis_v;
  }
};

/// Orthonormal in-plane axes for a unit normal (a fixed, continuous-almost-everywhere choice).
void plane_axes(const Eigen::Vector3d& normal, Eigen::Vector3d& axis_u, Eigen::Vector3d& axis_v);

/// Which plane each edge of a slice polygon lies on (edge i joins vertex i to vertex i+1), kept
/// between time steps so that the next slice of the same pair can be rebuilt from the same planes.
struct SliceWarmStart {
  std::array<int, SliceVertices::kInline> edge_planes{};  ///< indices into the plane list
  std::size_t count = 0;                                  ///< number of edges; 0: none known
};

/// The polygon {x in plane(origin, normal) : n_j·x <= d_j for all j}. `extent` (m) must exceed the
/// polygon's radius about `origin` (e.g. the sum of the two blocks' bounding diameters). Planes
/// parallel to the slice keep or remove the whole polygon, exactly. No heap allocation for up to
/// 64 planes and a result of up to SliceVertices::kInline vertices.
SlicePolygon slice_halfspaces(std::span<const Halfspace> planes, const Eigen::Vector3d& origin,
                              const Eigen::Vector3d& normal, double extent);

/// The same polygon, first tried as the cycle of the planes in `warm` (the previous slice of the
/// same plane list): its vertices are the intersections of consecutive edge lines, and it is
/// accepted if it is convex and counter-clockwise with every vertex inside every plane (to
/// 1e-13 of `extent`), which makes it the exact slice. Otherwise it is clipped as above.
/// On return `warm` holds the new polygon's edge planes (count 0 if an edge is not a plane's).
SlicePolygon slice_halfspaces(std::span<const Halfspace> planes, const Eigen::Vector3d& origin,
                              const Eigen::Vector3d& normal, double extent, SliceWarmStart& warm);

/// A slice's half-spaces already in plane coordinates: a_j·y <= s_j with a_j = (n_j·axis_u,
/// n_j·axis_v) (-) and s_j = d_j - n_j·origin (m), as columns of `size` entries.
struct SliceLines {
  const double* a_u = nullptr;
  const double* a_v = nullptr;
  const double* s = nullptr;
  std::size_t size = 0;
};

/// slice_halfspaces for callers that have the lines already (the narrow phase computes them
/// with other per-plane quantities). `axis_u`, `axis_v` must be plane_axes(normal); `warm` may
/// be null.
SlicePolygon slice_lines(const SliceLines& lines, const Eigen::Vector3d& origin,
                         const Eigen::Vector3d& normal, const Eigen::Vector3d& axis_u,
                         const Eigen::Vector3d& axis_v, double extent, SliceWarmStart* warm);

}  // namespace blockdem
