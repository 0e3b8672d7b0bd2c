// Convex polyhedron construction: vertex enumeration from planes, face ordering, hull of points,
// and exact mass properties by signed tetrahedra.
#include "blockdem/geometry/polyhedron.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <new>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "blockdem/geometry/geometry_error.hpp"
#include "blockdem/numerics/number_text.hpp"

namespace blockdem {
namespace {

// Relative tolerance for "on the plane" tests, scaled by the shape's size.
constexpr double kRelTol = 1e-9;

std::string fmt_vec(const Eigen::Vector3d& v) {
  std::ostringstream s;
  s << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return s.str();
}

// Vertices of {n_i·x <= d_i}: every point where three planes meet and that satisfies all planes.
std::vector<Eigen::Vector3d> enumerate_vertices(const std::vector<Halfspace>& planes, double tol) {
  std::vector<Eigen::Vector3d> out;
  const int m = static_cast<int>(planes.size());
  for (int i = 0; i < m; ++i) {
    for (int j = i + 1; j < m; ++j) {
      const Eigen::Vector3d nij = planes[i].normal.cross(planes[j].normal);
      if (nij.squaredNorm() < 1e-20) continue;
      for (int k = j + 1; k < m; ++k) {
        const double det = nij.dot(planes[k].normal);
        if (std::abs(det) < 1e-10) continue;
        Eigen::Matrix3d a;
        a.row(0) = planes[i].normal.transpose();
        a.row(1) = planes[j].normal.transpose();
        a.row(2) = planes[k].normal.transpose();
        const Eigen::Vector3d x = a.partialPivLu().solve(
            Eigen::Vector3d(planes[i].offset, planes[j].offset, planes[k].offset));
        bool inside = true;
        for (const auto& p : planes) {
          if (p.signed_distance(x) > tol) {
            inside = false;
            break;
          }
        }
        if (!inside) continue;
        const bool duplicate = std::any_of(out.begin(), out.end(), [&](const Eigen::Vector3d& v) {
          return (v - x).norm() <= 10 * tol;
        });
        if (!duplicate) out.push_back(x);
      }
    }
  }
  return out;
}

}  // namespace

double polygon_area(std::span<const Eigen::Vector3d> points, const Eigen::Vector3d& normal) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  const std::size_t n = points.size();
  for (std::size_t i = 0; i < n; ++i) sum += points[i].cross(points[(i + 1) % n]);
  return 0.5 * std::abs(sum.dot(normal));
}

Polyhedron Polyhedron::from_planes(std::span<const Halfspace> planes) {
  return Polyhedron(build(std::vector<Halfspace>(planes.begin(), planes.end()), false));
}

Polyhedron Polyhedron::from_closed_planes(std::span<const Halfspace> planes) {
  return Polyhedron(build(std::vector<Halfspace>(planes.begin(), planes.end()), true));
}

Polyhedron Polyhedron::box(const Eigen::Vector3d& size) {
  for (int i = 0; i < 3; ++i) {
    if (!(size[i] > 0.0) || !std::isfinite(size[i])) {
      throw GeometryError("box size must be three positive finite lengths, got " + fmt_vec(size));
    }
  }
  std::vector<Halfspace> planes;
  for (int axis = 0; axis < 3; ++axis) {
    for (double sign : {1.0, -1.0}) {
      Halfspace h;
      h.normal = sign * Eigen::Vector3d::Unit(axis);
      h.offset = 0.5 * size[axis];
      planes.push_back(h);
    }
  }
  return from_planes(planes);
}

Polyhedron Polyhedron::from_vertices(std::span<const Eigen::Vector3d> points) {
  const int n = static_cast<int>(points.size());
  if (n < 4) throw GeometryError("a vertex list needs at least 4 points, got " + std::to_string(n));
  double scale = 0.0;
  for (const auto& q : points) {
    if (!q.allFinite()) throw GeometryError("vertex " + fmt_vec(q) + " is not finite");
    scale = std::max(scale, q.cwiseAbs().maxCoeff());
  }
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& q : points) mean += q;
  mean /= n;
  double extent = 0.0;
  for (const auto& q : points) extent = std::max(extent, (q - mean).norm());
  const double tol = kRelTol * std::max(scale, extent) * 10;

  // Hull planes: every plane through three points with all points on one side.
  std::vector<Halfspace> planes;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      for (int k = j + 1; k < n; ++k) {
        Eigen::Vector3d nrm = (points[j] - points[i]).cross(points[k] - points[i]);
        const double len = nrm.norm();
        if (len <= 1e-12 * extent * extent) continue;
        nrm /= len;
        double d = nrm.dot(points[i]);
        bool pos = false, neg = false;
        for (const auto& q : points) {
          const double s = nrm.dot(q) - d;
          pos |= s > tol;
          neg |= s < -tol;
        }
        if (pos && neg) continue;
        if (!pos && !neg) {
          throw GeometryError("the vertex list is flat (all points on one plane): zero volume");
        }
        if (pos) {
          nrm = -nrm;
          d = -d;
        }
        const bool duplicate = std::any_of(planes.begin(), planes.end(), [&](const Halfspace& h) {
          return (h.normal - nrm).norm() < 1e-9 && std::abs(h.offset - d) <= tol;
        });
        if (!duplicate) planes.push_back(Halfspace{nrm, d});
      }
    }
  }
  // Every input point must lie on the hull's boundary: an interior point means the list is not
  // the vertex set of a convex polyhedron.
  for (const auto& q : points) {
    double worst = -std::numeric_limits<double>::infinity();
    for (const auto& h : planes) worst = std::max(worst, h.signed_distance(q));
    if (worst < -tol) {
      throw GeometryError(
          "vertex " + fmt_vec(q) +
          " lies inside the convex hull of the others: the vertex list is not convex");
    }
  }
  return from_planes(planes);
}

Polyhedron::Polyhedron() {
  // One empty shape for every default-constructed polyhedron; its own reference is never
  // released, so it is never freed.
  static const Data empty;
  data_ = &empty;
  data_->share();
}

void Polyhedron::Data::release() const {
  if (references.fetch_sub(1, std::memory_order_acq_rel) != 1) return;
  this->~Data();  // the arrays after it hold nothing to destroy (static_assert below)
  ::operator delete(const_cast<Data*>(this));
}

namespace {

// The arrays are never destroyed element by element: nothing in them owns a resource.
static_assert(std::is_trivially_destructible_v<Halfspace> &&
              std::is_trivially_destructible_v<Eigen::Vector3d> &&
              std::is_trivially_destructible_v<Face>);
static_assert(alignof(Halfspace) <= 8 && alignof(Face) <= 8 && alignof(Eigen::Vector3d) <= 8 &&
              sizeof(Halfspace) % 8 == 0 && sizeof(Face) % 8 == 0);

}  // namespace

const Polyhedron::Data* Polyhedron::build(std::vector<Halfspace> planes, bool known_closed) {
  Data header;
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Halfspace> kept_planes;
  std::vector<std::vector<int>> faces;  // each face's plane is its place in kept_planes
  if (planes.size() < 4) {
    throw GeometryError("a bounded polyhedron needs at least 4 planes, got " +
                        std::to_string(planes.size()));
  }
  double scale = 0.0;
  for (std::size_t i = 0; i < planes.size(); ++i) {
    const auto& h = planes[i];
    if (!h.normal.allFinite() || !std::isfinite(h.offset)) {
      throw GeometryError("plane " + std::to_string(i) + " has a NaN or infinite coefficient");
    }
    if (std::abs(h.normal.norm() - 1.0) > 1e-9) {
      throw GeometryError("plane " + std::to_string(i) + " normal " + fmt_vec(h.normal) +
                          " is not a unit vector (length " + number_text(h.normal.norm()) + ")");
    }
    scale = std::max(scale, std::abs(h.offset));
  }
  if (scale == 0.0)
    throw GeometryError("all planes pass through the origin: the shape is unbounded or empty");

  // Unbounded sets: close them with a box far outside and see whether the box is touched.
  if (!known_closed) {
    const double far = 1e6 * scale;
    std::vector<Halfspace> closed = planes;
    for (int axis = 0; axis < 3; ++axis) {
      for (double sign : {1.0, -1.0})
        closed.push_back(Halfspace{sign * Eigen::Vector3d::Unit(axis), far});
    }
    const auto closed_vertices = enumerate_vertices(closed, kRelTol * far);
    if (closed_vertices.empty())
      throw GeometryError("the planes enclose no point: the shape is empty");
    for (const auto& v : closed_vertices) {
      if (v.cwiseAbs().maxCoeff() > 0.5 * far) {
        throw GeometryError("the planes do not enclose a bounded region: the shape is unbounded");
      }
    }
  }
  const double tol = kRelTol * scale;

  vertices = enumerate_vertices(planes, tol);
  if (vertices.size() < 4) throw GeometryError("the planes enclose no solid: zero volume");

  // Faces: the vertices on each plane, ordered counter-clockwise about its outward normal.
  // Planes that touch fewer than three vertices (redundant) or repeat another face are dropped.
  kept_planes.clear();
  faces.clear();
  std::vector<std::vector<int>> seen;
  for (const auto& h : planes) {
    std::vector<int> on;
    for (int v = 0; v < static_cast<int>(vertices.size()); ++v) {
      if (std::abs(h.signed_distance(vertices[v])) <= 10 * tol) on.push_back(v);
    }
    if (on.size() < 3) continue;
    if (std::find(seen.begin(), seen.end(), on) != seen.end()) continue;
    seen.push_back(on);
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int v : on) centre += vertices[v];
    centre /= static_cast<double>(on.size());
    const Eigen::Vector3d u = (vertices[on[0]] - centre).normalized();
    const Eigen::Vector3d w = h.normal.cross(u);
    std::vector<double> angle(vertices.size());
    for (int v : on) {
      const Eigen::Vector3d r = vertices[v] - centre;
      angle[v] = std::atan2(r.dot(w), r.dot(u));
    }
    std::sort(on.begin(), on.end(), [&](int a, int b) { return angle[a] < angle[b]; });
    faces.push_back(std::move(on));
    kept_planes.push_back(h);
  }
  if (faces.size() < 4) throw GeometryError("the planes enclose no solid: zero volume");

  // Mass properties: fan each face into triangles and form tetrahedra with an interior point c.
  // For a tetrahedron p0..p3: V = (p1-p0)·((p2-p0)×(p3-p0))/6 and
  // ∫ x xᵀ dV = V/20 (Σ p_i p_iᵀ + s sᵀ), s = Σ p_i (about the origin, here c).
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& v : vertices) c += v;
  c /= static_cast<double>(vertices.size());
  double vol = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (const auto& f : faces) {
    const Eigen::Vector3d a = vertices[f[0]] - c;
    for (std::size_t i = 1; i + 1 < f.size(); ++i) {
      const Eigen::Vector3d b = vertices[f[i]] - c;
      const Eigen::Vector3d d = vertices[f[i + 1]] - c;
      const double v6 = a.dot(b.cross(d));
      const double v = v6 / 6.0;
      const Eigen::Vector3d s = a + b + d;
      vol += v;
      first += v * s / 4.0;
      second += v / 20.0 *
                (a * a.transpose() + b * b.transpose() + d * d.transpose() + s * s.transpose());
    }
  }
  if (!(vol > std::pow(1e-6 * scale, 3))) throw GeometryError("the shape has zero volume");
  header.volume = vol;
  const Eigen::Vector3d g = first / vol;
  header.centroid = c + g;
  const Eigen::Matrix3d cov = second - vol * g * g.transpose();
  header.unit_inertia = cov.trace() * Eigen::Matrix3d::Identity() - cov;
  header.bounding_radius = 0.0;
  for (const auto& v : vertices)
    header.bounding_radius = std::max(header.bounding_radius, (v - header.centroid).norm());

  // The record: the header, then the planes, vertices, faces and their indices (Data's
  // accessors find each array after the one before).
  std::size_t n_indices = 0;
  for (const auto& f : faces) n_indices += f.size();
  header.n_planes = static_cast<std::uint32_t>(kept_planes.size());
  header.n_vertices = static_cast<std::uint32_t>(vertices.size());
  header.n_faces = static_cast<std::uint32_t>(faces.size());
  header.n_indices = static_cast<std::uint32_t>(n_indices);
  static_assert(sizeof(Data) % 8 == 0 && alignof(Data) <= alignof(std::max_align_t));
  const std::size_t bytes = sizeof(Data) + kept_planes.size() * sizeof(Halfspace) +
                            vertices.size() * sizeof(Eigen::Vector3d) +
                            faces.size() * sizeof(Face) + n_indices * sizeof(int);
  void* memory = ::operator new(bytes);
  Data* data = new (memory) Data;
  data->n_planes = header.n_planes;
  data->n_vertices = header.n_vertices;
  data->n_faces = header.n_faces;
  data->n_indices = header.n_indices;
  data->volume = header.volume;
  data->centroid = header.centroid;
  data->unit_inertia = header.unit_inertia;
  data->bounding_radius = header.bounding_radius;
  std::uninitialized_copy(kept_planes.begin(), kept_planes.end(),
                          const_cast<Halfspace*>(data->planes()));
  std::uninitialized_copy(vertices.begin(), vertices.end(),
                          const_cast<Eigen::Vector3d*>(data->vertices()));
  int* index = const_cast<int*>(data->indices());
  Face* face = const_cast<Face*>(data->faces());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    std::copy(faces[f].begin(), faces[f].end(), index);
    new (face + f) Face{static_cast<int>(f), std::span<const int>(index, faces[f].size())};
    index += faces[f].size();
  }
  return data;
}

double Polyhedron::face_area(int f) const {
  if (f < 0 || static_cast<std::uint32_t>(f) >= data_->n_faces)
    throw std::out_of_range("Polyhedron::face_area: no face " + std::to_string(f));
  const Face& face = data_->faces()[f];
  std::vector<Eigen::Vector3d> pts;
  pts.reserve(face.vertices.size());
  for (int v : face.vertices) pts.push_back(data_->vertices()[v]);
  return polygon_area(pts, data_->planes()[face.plane].normal);
}

Polyhedron Polyhedron::transformed(const Eigen::Matrix3d& rotation,
                                   const Eigen::Vector3d& translation) const {
  std::vector<Halfspace> moved;
  moved.reserve(data_->n_planes);
  for (const auto& h : planes()) {
    Halfspace m;
    m.normal = (rotation * h.normal).normalized();
    m.offset = h.offset + m.normal.dot(translation);
    moved.push_back(m);
  }
  // A rigid motion of a closed solid is closed.
  return from_closed_planes(moved);
}

}  // namespace blockdem
