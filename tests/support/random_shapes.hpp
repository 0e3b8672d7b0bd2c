// Seeded random convex shapes as half-space lists (boxes, prisms, sphere-tangent hulls) and ways to
// place pairs of them (touching, gapped, face to face), for collision tests and benchmarks.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include <Eigen/Geometry>

#include "blockdem/geometry/halfspace.hpp"
#include "support/dense_solves.hpp"

namespace blockdem::test_shapes {

using Planes = std::vector<Halfspace>;
using Rng = std::mt19937_64;

/// Uniform random double in [lo, hi).
inline double uniform(Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

/// Uniformly distributed unit vector.
inline Eigen::Vector3d random_unit_vector(Rng& rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  Eigen::Vector3d v;
  do {
    v = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
  } while (v.norm() < 1e-6);
  return v.normalized();
}

/// Uniformly distributed rotation (Haar measure), from a normalised Gaussian quaternion.
inline Eigen::Matrix3d random_rotation(Rng& rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  Eigen::Quaterniond q;
  do {
    q = Eigen::Quaterniond(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
  } while (q.norm() < 1e-6);
  return q.normalized().toRotationMatrix();
}

/// The planes of the body moved by x_world = rotation * x_body + translation.
inline Planes transformed(const Planes& body, const Eigen::Matrix3d& rotation,
                          const Eigen::Vector3d& translation) {
  Planes out;
  out.reserve(body.size());
  for (const Halfspace& h : body) {
    Halfspace w;
    w.normal = rotation * h.normal;
    w.offset = h.offset + w.normal.dot(translation);
    out.push_back(w);
  }
  return out;
}

/// The planes scaled about the origin by `factor` > 0 (a similar shape, same normals).
inline Planes scaled(const Planes& body, double factor) {
  Planes out = body;
  for (Halfspace& h : out) h.offset *= factor;
  return out;
}

/// The planes of A followed by those of B: the input of the pair overlap LP.
inline Planes concat(const Planes& a, const Planes& b) {
  Planes out = a;
  out.insert(out.end(), b.begin(), b.end());
  return out;
}

/// Box with the given half sizes (m), centred at the body origin, then moved.
inline Planes box(const Eigen::Vector3d& half_sizes,
                  const Eigen::Matrix3d& rotation = Eigen::Matrix3d::Identity(),
                  const Eigen::Vector3d& translation = Eigen::Vector3d::Zero()) {
  Planes body;
  for (int k = 0; k < 3; ++k) {
    for (const double sign : {1.0, -1.0}) {
      Halfspace h;
      h.normal = sign * Eigen::Vector3d::Unit(k);
      h.offset = half_sizes[k];
      body.push_back(h);
    }
  }
  return transformed(body, rotation, translation);
}

/// Right prism: a convex polygon (counter-clockwise, in the body x-y plane, containing the origin)
/// extruded over z in [-half_length, half_length], then moved.
inline Planes prism(const std::vector<Eigen::Vector2d>& polygon_ccw, double half_length,
                    const Eigen::Matrix3d& rotation = Eigen::Matrix3d::Identity(),
                    const Eigen::Vector3d& translation = Eigen::Vector3d::Zero()) {
  if (polygon_ccw.size() < 3) throw std::invalid_argument("prism: polygon needs 3+ vertices");
  Planes body;
  const std::size_t n = polygon_ccw.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d edge = polygon_ccw[(i + 1) % n] - polygon_ccw[i];
    const Eigen::Vector2d out2 = Eigen::Vector2d(edge.y(), -edge.x()).normalized();
    Halfspace h;
    h.normal = Eigen::Vector3d(out2.x(), out2.y(), 0.0);
    h.offset = out2.dot(polygon_ccw[i]);
    body.push_back(h);
  }
  for (const double sign : {1.0, -1.0}) {
    Halfspace h;
    h.normal = Eigen::Vector3d(0.0, 0.0, sign);
    h.offset = half_length;
    body.push_back(h);
  }
  return transformed(body, rotation, translation);
}

/// Random prism in its body frame: `sides` >= 3 vertices on a circle of `radius` at jittered,
/// increasing angles (convex, containing the origin), extruded over [-half_length, half_length].
inline Planes random_prism(Rng& rng, int sides, double radius, double half_length) {
  if (sides < 3) throw std::invalid_argument("random_prism: sides must be >= 3");
  std::vector<Eigen::Vector2d> polygon;
  const double step = 2.0 * std::numbers::pi / sides;
  const double phase = uniform(rng, 0.0, step);
  for (int i = 0; i < sides; ++i) {
    const double angle = phase + step * (i + uniform(rng, -0.3, 0.3));
    polygon.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
  }
  return prism(polygon, half_length);
}

/// Random convex hull in its body frame with `planes` >= 4 faces, all tangent to the sphere of
/// `radius` about the origin (so its inscribed ball is exactly that sphere): the first four
/// normals form a randomly rotated regular tetrahedron (guaranteeing a bounded hull), the others
/// are uniform random directions.
inline Planes random_hull(Rng& rng, int planes, double radius) {
  if (planes < 4) throw std::invalid_argument("random_hull: planes must be >= 4");
  const Eigen::Matrix3d rotation = random_rotation(rng);
  const double s = 1.0 / std::sqrt(3.0);
  const Eigen::Vector3d tetra[4] = {{s, s, s}, {s, -s, -s}, {-s, s, -s}, {-s, -s, s}};
  Planes body;
  for (int i = 0; i < planes; ++i) {
    Halfspace h;
    h.normal = i < 4 ? Eigen::Vector3d(rotation * tetra[i]) : random_unit_vector(rng);
    h.offset = radius;
    body.push_back(h);
  }
  return body;
}

/// Vertices of a bounded polytope by brute force over plane triples (fine for a few dozen
/// planes): intersections of three planes that satisfy every plane within `tol` (m), deduplicated.
inline std::vector<Eigen::Vector3d> vertices(const Planes& planes, double tol = 1e-9) {
  std::vector<Eigen::Vector3d> out;
  const std::size_t m = planes.size();
  for (std::size_t i = 0; i < m; ++i) {
    for (std::size_t j = i + 1; j < m; ++j) {
      for (std::size_t k = j + 1; k < m; ++k) {
        Eigen::Matrix3d a;
        a.row(0) = planes[i].normal.transpose();
        a.row(1) = planes[j].normal.transpose();
        a.row(2) = planes[k].normal.transpose();
        if (std::abs(a.determinant()) < 1e-9) continue;
        const Eigen::Vector3d x = test::solve_partial_lu(
            a, Eigen::Vector3d(planes[i].offset, planes[j].offset, planes[k].offset));
        const bool inside = std::all_of(planes.begin(), planes.end(), [&](const Halfspace& h) {
          return h.signed_distance(x) <= tol;
        });
        const bool seen = std::any_of(out.begin(), out.end(), [&](const Eigen::Vector3d& v) {
          return (v - x).norm() <= 10.0 * tol;
        });
        if (inside && !seen) out.push_back(x);
      }
    }
  }
  return out;
}

/// Largest distance between two points of the list (the diameter of their hull) (m).
inline double diameter(const std::vector<Eigen::Vector3d>& points) {
  double d = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (std::size_t j = i + 1; j < points.size(); ++j)
      d = std::max(d, (points[i] - points[j]).norm());
  }
  return d;
}

/// Mean of the vertices lying on plane `face` (within `tol`): a point in the face's relative
/// interior when the plane is a facet.
inline Eigen::Vector3d face_centroid(const Planes& planes,
                                     const std::vector<Eigen::Vector3d>& verts, std::size_t face,
                                     double tol = 1e-9) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int count = 0;
  for (const Eigen::Vector3d& v : verts) {
    if (std::abs(planes[face].signed_distance(v)) <= tol) {
      sum += v;
      ++count;
    }
  }
  if (count < 3) throw std::invalid_argument("face_centroid: the plane is not a facet");
  return sum / count;
}

/// Vertex of the list minimising u · v.
inline Eigen::Vector3d extreme_vertex(const std::vector<Eigen::Vector3d>& verts,
                                      const Eigen::Vector3d& u) {
  return *std::min_element(verts.begin(), verts.end(),
                           [&](const auto& a, const auto& b) { return u.dot(a) < u.dot(b); });
}

/// Moves B (world planes) so that its vertex extreme against face `face` of A sits at that face's
/// centroid, then by `gap` (m) along the face's outward normal. gap = 0: A and B touch (common
/// point, disjoint interiors, so r* = 0); gap > 0: separated by a slab of width gap (r* < 0);
/// gap < 0: B's vertex penetrates A by -gap (r* > 0).
inline Planes place_vertex_on_face(const Planes& a, std::size_t face, const Planes& b, double gap) {
  const std::vector<Eigen::Vector3d> va = vertices(a);
  const std::vector<Eigen::Vector3d> vb = vertices(b);
  const Eigen::Vector3d n = a[face].normal;
  const Eigen::Vector3d target = face_centroid(a, va, face) + gap * n;
  return transformed(b, Eigen::Matrix3d::Identity(), target - extreme_vertex(vb, n));
}

/// Rotates and moves B (world planes) so that its face `face_b` lies on face `face_a` of A with
/// opposite normals, the face centroids coinciding, B spun by `spin` (rad) about the common
/// normal, then moves B by `gap` (m) along A's face normal: an exactly aligned face-to-face
/// contact for gap = 0 (r* = 0), separated for gap > 0, overlapping for gap < 0.
inline Planes place_face_on_face(const Planes& a, std::size_t face_a, const Planes& b,
                                 std::size_t face_b, double spin, double gap) {
  const Eigen::Vector3d n = a[face_a].normal;
  const Eigen::Matrix3d align =
      (Eigen::AngleAxisd(spin, n) * test::quaternion_between(b[face_b].normal, -n))
          .toRotationMatrix();
  const Planes b_rot = transformed(b, align, Eigen::Vector3d::Zero());
  const Eigen::Vector3d ca = face_centroid(a, vertices(a), face_a);
  const Eigen::Vector3d cb = face_centroid(b_rot, vertices(b_rot), face_b);
  return transformed(b_rot, Eigen::Matrix3d::Identity(), ca - cb + gap * n);
}

}  // namespace blockdem::test_shapes
