// Sutherland-Hodgman clipping of a large square by half-planes, in the plane's 2D coordinates.
#include "blockdem/collision/slice_polygon.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace blockdem {

SliceVertices::SliceVertices(std::initializer_list<Eigen::Vector2d> points) {
  assign(points.begin(), points.size());
}

SliceVertices& SliceVertices::operator=(const SliceVertices& other) {
  if (this != &other) assign(other.data(), other.size_);
  return *this;
}

SliceVertices& SliceVertices::operator=(SliceVertices&& other) noexcept {
  if (this == &other) return *this;
  if (other.heap_.empty()) {
    std::copy(other.inline_.begin(), other.inline_.begin() + other.size_, inline_.begin());
    heap_.clear();
  } else {
    heap_ = std::move(other.heap_);
    other.heap_.clear();
  }
  size_ = other.size_;
  other.size_ = 0;
  return *this;
}

void SliceVertices::push_back(const Eigen::Vector2d& p) {
  if (heap_.empty() && size_ < kInline) {
    inline_[size_++] = p;
    return;
  }
  if (heap_.empty()) heap_.assign(inline_.begin(), inline_.end());
  heap_.push_back(p);
  ++size_;
}

void SliceVertices::assign(const Eigen::Vector2d* points, std::size_t n) {
  if (n <= kInline) {
    std::copy(points, points + n, inline_.begin());
    heap_.clear();
  } else {
    heap_.assign(points, points + n);
  }
  size_ = n;
}

double SlicePolygon::area() const {
  double twice = 0.0;
  const std::size_t n = vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const auto& a = vertices[i];
    const auto& b = vertices[i + 1 == n ? 0 : i + 1];
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
    const auto& b = vertices[i + 1 == n ? 0 : i + 1];
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

namespace {

constexpr std::size_t kSliceStackPlanes = 64;
// A warm-start polygon is rejected if a vertex lies outside a plane by more than this fraction
// of the extent (a cut that small changes the area by round-off only).
constexpr double kWarmTolerance = 1e-13;
// ... or if two consecutive edges are this close to parallel (sine of the angle between them).
constexpr double kWarmMinSine = 1e-9;

// Workspace of the clipping, on the stack for up to kSliceStackPlanes lines. Each cut adds at most
// one vertex, so polygons have at most m + 4 vertices.
class Workspace {
 public:
  explicit Workspace(const SliceLines& lines)
      : au(lines.a_u), av(lines.a_v), s(lines.s), m(lines.size), capacity(lines.size + 4) {
    points = stack_points_.data();
    values = stack_values_.data();
    labels = stack_labels_.data();
    if (m > kSliceStackPlanes) {
      heap_points_.resize(2 * capacity);
      heap_values_.resize(capacity);
      heap_labels_.resize(2 * capacity);
      points = heap_points_.data();
      values = heap_values_.data();
      labels = heap_labels_.data();
    }
  }

  const double* const au;
  const double* const av;
  const double* const s;
  const std::size_t m;
  const std::size_t capacity;
  Eigen::Vector2d* points = nullptr;  // two polygons of `capacity` vertices
  double* values = nullptr;           // `capacity` vertex values
  int* labels = nullptr;              // two lists of `capacity` edge labels

 private:
  std::array<Eigen::Vector2d, 2 * (kSliceStackPlanes + 4)> stack_points_;
  std::array<double, kSliceStackPlanes + 4> stack_values_;
  std::array<int, 2 * (kSliceStackPlanes + 4)> stack_labels_;
  std::vector<Eigen::Vector2d> heap_points_;
  std::vector<double> heap_values_;
  std::vector<int> heap_labels_;
};

// Sutherland-Hodgman: clips the square [-extent, extent]² by every half-plane in turn. Returns
// the number of vertices (0 if fewer than 3 remain); `cur` points at them and `label` at the
// plane of each edge (edge i joins vertex i to vertex i+1; -1 for an edge of the square).
std::size_t clip(Workspace& w, double extent, Eigen::Vector2d*& cur, int*& label) {
  cur = w.points;
  Eigen::Vector2d* next = w.points + w.capacity;
  label = w.labels;
  int* next_label = w.labels + w.capacity;
  cur[0] = {-extent, -extent};
  cur[1] = {extent, -extent};
  cur[2] = {extent, extent};
  cur[3] = {-extent, extent};
  std::fill(label, label + 4, -1);
  std::size_t n = 4;
  double radius2 = 2.0 * extent * extent;  // the largest squared distance of a vertex from 0
  double* value = w.values;
  for (std::size_t j = 0; j < w.m; ++j) {
    const double au = w.au[j], av = w.av[j], s = w.s[j];
    // A line farther from the origin than every vertex cuts nothing off (a·y <= |a| |y| < s).
    if (s > 0.0 && s * s > (1.0 + 1e-12) * (au * au + av * av) * radius2) continue;
    // Values a·y - s at the vertices; a plane that cuts nothing off is skipped.
    double largest = -std::numeric_limits<double>::infinity();
    double smallest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i) {
      value[i] = au * cur[i].x() + av * cur[i].y() - s;
      largest = std::max(largest, value[i]);
      smallest = std::min(smallest, value[i]);
    }
    if (!(largest > 0.0)) continue;
    if (smallest > 0.0) return 0;
    std::size_t k = 0;
    const int plane = static_cast<int>(j);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t i1 = i + 1 == n ? 0 : i + 1;
      const double fp = value[i];
      const double fq = value[i1];
      if (fp <= 0.0) {
        // The edge leaving a kept vertex follows the new line if it heads outside from on it.
        next_label[k] = (fp == 0.0 && fq > 0.0) ? plane : label[i];
        next[k++] = cur[i];
      }
      if ((fp < 0.0 && fq > 0.0) || (fp > 0.0 && fq < 0.0)) {
        // Leaving: the edge from the cut point follows the new line; entering: the old edge.
        next_label[k] = fp < 0.0 ? plane : label[i];
        next[k++] = cur[i] + (fp / (fp - fq)) * (cur[i1] - cur[i]);
      }
    }
    std::swap(cur, next);
    std::swap(label, next_label);
    n = k;
    if (n < 3) return 0;
    radius2 = 0.0;
    for (std::size_t i = 0; i < n; ++i) radius2 = std::max(radius2, cur[i].squaredNorm());
  }
  return n;
}

// The polygon whose edges lie on the planes `edges` in counter-clockwise order, into `out`
// (vertex i = the start of edge i). False unless it is convex, counter-clockwise, with edges of
// positive length, and inside every half-plane to the tolerance: then it is the exact slice.
bool warm_polygon(const Workspace& w, const SliceWarmStart& warm, double tolerance,
                  Eigen::Vector2d* out) {
  const std::size_t n = warm.count;
  if (n < 3 || n > warm.edge_planes.size()) return false;
  for (std::size_t i = 0; i < n; ++i) {
    const int jp = warm.edge_planes[i == 0 ? n - 1 : i - 1];
    const int jq = warm.edge_planes[i];
    if (jp < 0 || jq < 0 || static_cast<std::size_t>(jp) >= w.m ||
        static_cast<std::size_t>(jq) >= w.m) {
      return false;
    }
    // Vertex i: where the line of the previous edge meets the line of edge i; a left turn.
    const double det = w.au[jp] * w.av[jq] - w.av[jp] * w.au[jq];
    const double norms2 =
        (w.au[jp] * w.au[jp] + w.av[jp] * w.av[jp]) * (w.au[jq] * w.au[jq] + w.av[jq] * w.av[jq]);
    if (!(det > 0.0 && det * det > kWarmMinSine * kWarmMinSine * norms2)) return false;
    out[i] = Eigen::Vector2d((w.s[jp] * w.av[jq] - w.s[jq] * w.av[jp]) / det,
                             (w.au[jp] * w.s[jq] - w.au[jq] * w.s[jp]) / det);
  }
  // Each edge runs from its start to its end in the line's counter-clockwise direction
  // (-a_v, a_u).
  for (std::size_t i = 0; i < n; ++i) {
    const int j = warm.edge_planes[i];
    const Eigen::Vector2d edge = out[i + 1 == n ? 0 : i + 1] - out[i];
    if (!(-w.av[j] * edge.x() + w.au[j] * edge.y() > 0.0)) return false;
  }
  // Every vertex inside every half-plane (a NaN fails the test).
  std::size_t j = 0;
  bool inside = true;
#if defined(__SSE2__)
  // Two planes at a time (SSE2 packets), each value formed as in the scalar loop below.
  __m128d all = _mm_castsi128_pd(_mm_set1_epi32(-1));
  const __m128d tol = _mm_set1_pd(tolerance);
  for (; j + 1 < w.m; j += 2) {
    const __m128d au = _mm_loadu_pd(w.au + j), av = _mm_loadu_pd(w.av + j);
    const __m128d limit = _mm_add_pd(_mm_loadu_pd(w.s + j), tol);
    for (std::size_t i = 0; i < n; ++i) {
      const __m128d value = _mm_add_pd(_mm_mul_pd(au, _mm_set1_pd(out[i].x())),
                                       _mm_mul_pd(av, _mm_set1_pd(out[i].y())));
      all = _mm_and_pd(all, _mm_cmple_pd(value, limit));
    }
  }
  inside = _mm_movemask_pd(all) == 3;
#endif
  for (; j < w.m; ++j) {
    const double au = w.au[j], av = w.av[j], limit = w.s[j] + tolerance;
    for (std::size_t i = 0; i < n; ++i) inside &= au * out[i].x() + av * out[i].y() <= limit;
  }
  return inside;
}

// The lines of `planes` in the plane through `origin` with axes u, v: columns on the stack for
// up to kSliceStackPlanes planes.
class PlaneLines {
 public:
  PlaneLines(std::span<const Halfspace> planes, const Eigen::Vector3d& origin,
             const Eigen::Vector3d& axis_u, const Eigen::Vector3d& axis_v) {
    const std::size_t m = planes.size();
    double* data = stack_.data();
    if (m > kSliceStackPlanes) {
      heap_.resize(3 * m);
      data = heap_.data();
    }
    for (std::size_t j = 0; j < m; ++j) {
      const Eigen::Vector3d& n = planes[j].normal;
      data[j] = n.dot(axis_u);
      data[m + j] = n.dot(axis_v);
      data[2 * m + j] = planes[j].offset - n.dot(origin);
    }
    lines = {data, data + m, data + 2 * m, m};
  }
  SliceLines lines;

 private:
  std::array<double, 3 * kSliceStackPlanes> stack_;
  std::vector<double> heap_;
};

SlicePolygon slice(std::span<const Halfspace> planes, const Eigen::Vector3d& origin,
                   const Eigen::Vector3d& normal, double extent, SliceWarmStart* warm) {
  Eigen::Vector3d axis_u, axis_v;
  plane_axes(normal, axis_u, axis_v);
  const PlaneLines lines(planes, origin, axis_u, axis_v);
  return slice_lines(lines.lines, origin, normal, axis_u, axis_v, extent, warm);
}

}  // namespace

SlicePolygon slice_lines(const SliceLines& lines, const Eigen::Vector3d& origin,
                         const Eigen::Vector3d& normal, const Eigen::Vector3d& axis_u,
                         const Eigen::Vector3d& axis_v, double extent, SliceWarmStart* warm) {
  SlicePolygon poly;
  poly.origin = origin;
  poly.normal = normal;
  poly.axis_u = axis_u;
  poly.axis_v = axis_v;
  Workspace w(lines);
  if (warm != nullptr && warm_polygon(w, *warm, kWarmTolerance * extent, w.points)) {
    poly.vertices.assign(w.points, warm->count);
    return poly;
  }
  Eigen::Vector2d* cur = nullptr;
  int* label = nullptr;
  const std::size_t n = clip(w, extent, cur, label);
  poly.vertices.assign(cur, n);
  if (warm != nullptr) {
    const bool known = n <= warm->edge_planes.size() &&
                       std::all_of(label, label + n, [](int j) { return j >= 0; });
    warm->count = known ? n : 0;
    if (known) std::copy(label, label + n, warm->edge_planes.begin());
  }
  return poly;
}

SlicePolygon slice_halfspaces(std::span<const Halfspace> planes, const Eigen::Vector3d& origin,
                              const Eigen::Vector3d& normal, double extent) {
  return slice(planes, origin, normal, extent, nullptr);
}

SlicePolygon slice_halfspaces(std::span<const Halfspace> planes, const Eigen::Vector3d& origin,
                              const Eigen::Vector3d& normal, double extent, SliceWarmStart& warm) {
  return slice(planes, origin, normal, extent, &warm);
}

}  // namespace blockdem
