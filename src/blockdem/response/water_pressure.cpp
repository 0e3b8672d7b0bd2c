// Hydrostatic pressure below a water table, integrated exactly over polygons and blocks.
#include "blockdem/response/water_pressure.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "blockdem/geometry/polygon_moments.hpp"

namespace blockdem {

WaterTable WaterTable::plane(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
  if (!point.allFinite() || !normal.allFinite())
    throw std::invalid_argument("the water table's point and normal must be finite");
  if (!(normal.norm() > 0.0)) throw std::invalid_argument("the water table's normal is zero");
  Eigen::Vector3d up = normal.normalized();
  if (up.z() < 0.0) up = -up;
  if (!(up.z() > 1e-9))
    throw std::invalid_argument("the water table is a vertical plane (its normal is horizontal)");
  WaterTable t;
  t.pieces_.push_back(Piece{{}, Halfspace{up, up.dot(point)}});
  // A level plane's height is its top; an inclined one rises without bound.
  if (up.x() == 0.0 && up.y() == 0.0) t.top_ = point.z();
  return t;
}

bool WaterTable::operator==(const WaterTable& other) const {
  const auto same = [](const Halfspace& a, const Halfspace& b) {
    return a.normal == b.normal && a.offset == b.offset;
  };
  if (pieces_.size() != other.pieces_.size() || !(top_ == other.top_)) return false;
  for (std::size_t i = 0; i < pieces_.size(); ++i) {
    const Piece &a = pieces_[i], &b = other.pieces_[i];
    if (!same(a.below, b.below) || a.region.size() != b.region.size()) return false;
    for (std::size_t k = 0; k < a.region.size(); ++k) {
      if (!same(a.region[k], b.region[k])) return false;
    }
  }
  return true;
}

namespace {

// The plan of a point (z dropped), and the twice signed area of the plan triangle (a, b, c).
Eigen::Vector2d plan(const Eigen::Vector3d& x) {
  return {x.x(), x.y()};
}
double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Eigen::Vector2d u = b - a, v = c - a;
  return u.x() * v.y() - u.y() * v.x();
}

// Whether d lies strictly inside the circle through a, b, c (counter-clockwise), beyond a
// relative tolerance (Guibas & Stolfi 1985, the in-circle determinant).
bool in_circle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
               const Eigen::Vector2d& d, double scale) {
  const Eigen::Vector2d p = a - d, q = b - d, r = c - d;
  const double det = (p.squaredNorm()) * (q.x() * r.y() - q.y() * r.x()) -
                     (q.squaredNorm()) * (p.x() * r.y() - p.y() * r.x()) +
                     (r.squaredNorm()) * (p.x() * q.y() - p.y() * q.x());
  return det > 1e-12 * scale * scale * scale * scale;
}

// Whether two counter-clockwise plan triangles share interior (separating axes: the six edges).
bool overlap(const std::array<Eigen::Vector2d, 3>& s, const std::array<Eigen::Vector2d, 3>& t,
             double scale) {
  const auto separated = [scale](const std::array<Eigen::Vector2d, 3>& a,
                                 const std::array<Eigen::Vector2d, 3>& b) {
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector2d& p = a[static_cast<std::size_t>(i)];
      const Eigen::Vector2d& q = a[static_cast<std::size_t>((i + 1) % 3)];
      bool all_outside = true;
      for (const Eigen::Vector2d& x : b)
        all_outside = all_outside && cross2(p, q, x) <= 1e-12 * scale * scale;
      if (all_outside) return true;
    }
    return false;
  };
  return !separated(s, t) && !separated(t, s);
}

// The half-space of the plan on the left of the directed line p -> q (vertical plane).
Halfspace left_of(const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
  const Eigen::Vector2d d = (q - p).normalized();
  const Eigen::Vector3d out(d.y(), -d.x(), 0.0);  // to the right: outside
  return Halfspace{out, out.x() * p.x() + out.y() * p.y()};
}

// The water below the plane through three points that are not on one line in plan.
Halfspace below_plane(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                      const Eigen::Vector3d& c) {
  Eigen::Vector3d n = (b - a).cross(c - a).normalized();
  if (n.z() < 0.0) n = -n;
  return Halfspace{n, n.dot(a)};
}

}  // namespace

WaterTable WaterTable::surface(const std::vector<Eigen::Vector3d>& points) {
  const std::size_t n = points.size();
  if (n < 3)
    throw std::invalid_argument("a water table surface needs at least 3 points, got " +
                                std::to_string(n));
  if (n > kMaxSurfacePoints)
    throw std::invalid_argument("a water table surface takes at most " +
                                std::to_string(kMaxSurfacePoints) + " points, got " +
                                std::to_string(n));
  double scale = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!points[i].allFinite())
      throw std::invalid_argument("point " + std::to_string(i + 1) + " is not finite");
    for (std::size_t j = 0; j < i; ++j)
      scale = std::max(scale, (plan(points[i]) - plan(points[j])).norm());
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (!((plan(points[i]) - plan(points[j])).norm() > 1e-9 * scale))
        throw std::invalid_argument("points " + std::to_string(j + 1) + " and " +
                                    std::to_string(i + 1) + " lie at one place in plan");
    }
  }
  // The Delaunay triangles (an empty circumcircle), taken in index order without overlapping
  // those taken: four or more points on one circle give one of their triangulations.
  std::vector<std::array<std::size_t, 3>> triangles;
  std::vector<std::array<Eigen::Vector2d, 3>> shapes;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      for (std::size_t k = j + 1; k < n; ++k) {
        std::array<std::size_t, 3> t{i, j, k};
        const double twice = cross2(plan(points[i]), plan(points[j]), plan(points[k]));
        if (!(std::abs(twice) > 1e-12 * scale * scale)) continue;
        if (twice < 0.0) std::swap(t[1], t[2]);
        const std::array<Eigen::Vector2d, 3> shape{plan(points[t[0]]), plan(points[t[1]]),
                                                   plan(points[t[2]])};
        bool empty = true;
        for (std::size_t m = 0; m < n && empty; ++m) {
          if (m != i && m != j && m != k)
            empty = !in_circle(shape[0], shape[1], shape[2], plan(points[m]), scale);
        }
        for (std::size_t m = 0; m < shapes.size() && empty; ++m)
          empty = !overlap(shape, shapes[m], scale);
        if (!empty) continue;
        triangles.push_back(t);
        shapes.push_back(shape);
      }
    }
  }
  if (triangles.empty())
    throw std::invalid_argument("the points of a water table surface lie on one line in plan");
  WaterTable table;
  table.top_ = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : points) table.top_ = std::max(table.top_, p.z());
  // The triangles' pieces, and their edges that no other triangle has: the hull, counter-clockwise.
  std::map<std::pair<std::size_t, std::size_t>, int> edges;
  for (const auto& t : triangles) {
    for (int e = 0; e < 3; ++e)
      edges[{t[static_cast<std::size_t>(e)], t[static_cast<std::size_t>((e + 1) % 3)]}] += 1;
    Piece piece;
    for (int e = 0; e < 3; ++e)
      piece.region.push_back(left_of(plan(points[t[static_cast<std::size_t>(e)]]),
                                     plan(points[t[static_cast<std::size_t>((e + 1) % 3)]])));
    piece.below = below_plane(points[t[0]], points[t[1]], points[t[2]]);
    table.pieces_.push_back(std::move(piece));
  }
  std::map<std::size_t, std::size_t> next;  // hull vertex -> the next one counter-clockwise
  for (const auto& entry : edges) {
    const auto& e = entry.first;
    if (!edges.count({e.second, e.first})) next[e.first] = e.second;
  }
  for (const auto& [a, b] : next) {
    const Eigen::Vector2d pa = plan(points[a]), pb = plan(points[b]);
    const Eigen::Vector2d t = (pb - pa).normalized();
    // Beyond the edge a -> b: outside its line, between the perpendiculars at a and b.
    Piece strip;
    strip.region.push_back(left_of(pb, pa));
    strip.region.push_back(left_of(pa, pa + Eigen::Vector2d(t.y(), -t.x())));
    strip.region.push_back(left_of(pb + Eigen::Vector2d(t.y(), -t.x()), pb));
    // z = z_a + s t·(x - a): linear along the edge, level across it.
    const double s = (points[b].z() - points[a].z()) / (pb - pa).norm();
    const Eigen::Vector3d normal = Eigen::Vector3d(-s * t.x(), -s * t.y(), 1.0).normalized();
    strip.below = Halfspace{normal, normal.dot(points[a])};
    table.pieces_.push_back(std::move(strip));
    // Beyond vertex b, between the perpendiculars of its two hull edges: level at z_b.
    const std::size_t c = next.at(b);
    const Eigen::Vector2d u = (plan(points[c]) - pb).normalized();
    Piece corner;
    corner.region.push_back(left_of(pb, pb + Eigen::Vector2d(t.y(), -t.x())));
    corner.region.push_back(left_of(pb + Eigen::Vector2d(u.y(), -u.x()), pb));
    corner.below = Halfspace{Eigen::Vector3d::UnitZ(), points[b].z()};
    table.pieces_.push_back(std::move(corner));
  }
  return table;
}

double WaterTable::height(double x, double y) const {
  for (const Piece& p : pieces_) {
    bool inside = true;
    for (const Halfspace& h : p.region) inside = inside && h.signed_distance({x, y, 0.0}) <= 0.0;
    if (!inside) continue;
    const Eigen::Vector3d& n = p.below.normal;
    return (p.below.offset - n.x() * x - n.y() * y) / n.z();
  }
  return -std::numeric_limits<double>::infinity();
}

WaterTable WaterTable::shifted_by(const Eigen::Vector3d& origin) const {
  WaterTable t = *this;
  t.top_ -= origin.z();
  for (Piece& p : t.pieces_) {
    for (Halfspace& h : p.region) h.offset -= h.normal.dot(origin);
    p.below.offset -= p.below.normal.dot(origin);
  }
  return t;
}

WaterLoad polygon_water_load(const GroundWater& water, double gravity,
                             std::span<const Eigen::Vector3d> vertices, const Eigen::Vector3d& n,
                             const Eigen::Vector3d& about) {
  WaterLoad load;
  const double unit_weight = water.density * gravity;  // ρ_w g (Pa/m)
  for (const WaterTable::Piece& piece : water.table.pieces()) {
    // The part of the polygon in the piece's region and below its plane.
    std::vector<Eigen::Vector3d> part(vertices.begin(), vertices.end());
    for (const Halfspace& h : piece.region) {
      if (part.empty()) break;
      part = clip_polygon(part, h);
    }
    if (part.empty()) continue;
    part = clip_polygon(part, piece.below);
    if (part.empty()) continue;
    const PolygonMoments pm = polygon_area_centroid(part);
    if (!(pm.area > 0.0)) continue;
    // p(x) = ρ_w g (z_w - z) = ρ_w g (d - m·x) / m_z for the plane m·x = d: linear in x.
    const Eigen::Vector3d& m = piece.below.normal;
    const double mean = unit_weight * piece.below.slack(pm.centroid) / m.z();  // p(x̄) (Pa)
    const Eigen::Vector3d slope = -(unit_weight / m.z()) * m;                  // ∇p (Pa/m)
    const Eigen::Vector3d first = polygon_second_moment(part, pm.centroid, n) * slope;
    // On the body: -n p over the part; about `about`, -(x̄ - about) × n A p̄ - (S ∇p) × n.
    const double push = pm.area * mean;  // ∫ p dA (N)
    load.force -= push * n;
    load.torque -= (pm.centroid - about).cross(push * n) + first.cross(n);
    load.wetted_area += pm.area;
  }
  return load;
}

WaterLoad block_water_load(const GroundWater& water, double gravity, const Polyhedron& shape,
                           const Eigen::Matrix3d& rotation, const Eigen::Vector3d& position) {
  WaterLoad load;
  // The block's vertices at its pose; none below the table: no load.
  std::vector<Eigen::Vector3d> corners;
  corners.reserve(shape.vertices().size());
  // A plane table: a vertex below it; a surface: a vertex below its top.
  const bool plane = water.table.pieces().size() == 1;
  bool wet = false;
  for (const Eigen::Vector3d& v : shape.vertices()) {
    corners.push_back(rotation * v + position);
    const Eigen::Vector3d& x = corners.back();
    wet = wet || (plane ? x.z() < water.table.height(x.x(), x.y()) : x.z() < water.table.top());
  }
  if (!wet) return load;
  std::vector<Eigen::Vector3d> polygon;
  for (const Face& f : shape.faces()) {
    polygon.clear();
    for (const int v : f.vertices) polygon.push_back(corners[static_cast<std::size_t>(v)]);
    const Eigen::Vector3d n = rotation * shape.planes()[static_cast<std::size_t>(f.plane)].normal;
    load += polygon_water_load(water, gravity, polygon, n, position);
  }
  return load;
}

WaterLoad block_water_load(const std::optional<GroundWater>& water,
                           const std::optional<WaterRamp>& ramp, double gravity,
                           const Polyhedron& shape, const Eigen::Matrix3d& rotation,
                           const Eigen::Vector3d& position) {
  WaterLoad to;
  if (water) to = block_water_load(*water, gravity, shape, rotation, position);
  if (!ramp) return to;
  // Linear in the pressure: (1 - f) L_from + f L_to.
  WaterLoad from;
  if (ramp->from) from = block_water_load(*ramp->from, gravity, shape, rotation, position);
  const double f = ramp->fraction;
  WaterLoad load;
  load.force = (1.0 - f) * from.force + f * to.force;
  load.torque = (1.0 - f) * from.torque + f * to.torque;
  load.wetted_area = (1.0 - f) * from.wetted_area + f * to.wetted_area;
  return load;
}

}  // namespace blockdem
