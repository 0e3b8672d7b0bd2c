// Exact plane split of a convex cell (the subdivision step of rock slicing, Boon, Houlsby &
// Utili 2015, section 3) on an explicit vertex/face structure: each face polygon is clipped, the
// new face is the ordered ring of edge crossings. Mass properties by signed tetrahedra.
#include "blockdem/rockmass/convex_cell.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace blockdem {
namespace {

// Two unit vectors spanning the plane with unit normal n, right-handed (u, w, n).
std::pair<Eigen::Vector3d, Eigen::Vector3d> plane_basis(const Eigen::Vector3d& n) {
  const Eigen::Vector3d seed =
      std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d u = (seed - seed.dot(n) * n).normalized();
  return {u, n.cross(u)};
}

// Orders indices of points on a plane counter-clockwise about `normal`.
void order_indices(std::vector<int>& idx, const std::vector<Eigen::Vector3d>& pts,
                   const Eigen::Vector3d& normal) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int i : idx) c += pts[i];
  c /= static_cast<double>(idx.size());
  const auto [u, w] = plane_basis(normal);
  std::vector<std::pair<double, int>> keyed;
  keyed.reserve(idx.size());
  for (int i : idx) {
    const Eigen::Vector3d r = pts[i] - c;
    keyed.emplace_back(std::atan2(r.dot(w), r.dot(u)), i);
  }
  std::sort(keyed.begin(), keyed.end());
  for (std::size_t k = 0; k < idx.size(); ++k) idx[k] = keyed[k].second;
}

}  // namespace

void order_about(std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& normal) {
  std::vector<int> idx(points.size());
  for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = static_cast<int>(i);
  order_indices(idx, points, normal);
  std::vector<Eigen::Vector3d> out;
  out.reserve(points.size());
  for (int i : idx) out.push_back(points[i]);
  points = std::move(out);
}

ConvexCell ConvexCell::from_polyhedron(const Polyhedron& shape, std::span<const FaceTag> tags) {
  ConvexCell c;
  c.vertices_.assign(shape.vertices().begin(), shape.vertices().end());
  for (const auto& f : shape.faces()) {
    CellFace cf;
    cf.plane = shape.planes()[f.plane];
    cf.tag = tags[f.plane];
    cf.vertices.assign(f.vertices.begin(), f.vertices.end());
    c.faces_.push_back(std::move(cf));
  }
  c.update_mass_properties();
  return c;
}

std::pair<double, double> ConvexCell::extent_along(const Eigen::Vector3d& n) const {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (const auto& v : vertices_) {
    const double s = n.dot(v);
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
  return {lo, hi};
}

double ConvexCell::aspect_ratio() const {
  double wmin = std::numeric_limits<double>::infinity();
  double wmax = 0.0;
  for (const auto& f : faces_) {
    const auto [lo, hi] = extent_along(f.plane.normal);
    wmin = std::min(wmin, hi - lo);
    wmax = std::max(wmax, hi - lo);
  }
  return wmax / wmin;
}

std::vector<Eigen::Vector3d> ConvexCell::face_polygon(int f) const {
  std::vector<Eigen::Vector3d> out;
  for (int v : faces_[f].vertices) out.push_back(vertices_[v]);
  return out;
}

std::vector<Eigen::Vector3d> ConvexCell::section(const Halfspace& plane, double snap) const {
  std::vector<double> s(vertices_.size());
  bool below = false, above = false;
  for (std::size_t i = 0; i < vertices_.size(); ++i) {
    s[i] = plane.signed_distance(vertices_[i]);
    below |= s[i] < -snap;
    above |= s[i] > snap;
  }
  std::vector<Eigen::Vector3d> pts;
  if (!below || !above) return pts;
  // Vertices on the plane, and crossings of edges from one side to the other (each edge is met
  // twice, once per face; the face order keeps the one with a < b).
  for (std::size_t i = 0; i < vertices_.size(); ++i) {
    if (std::abs(s[i]) <= snap) pts.push_back(vertices_[i]);
  }
  for (const auto& f : faces_) {
    const std::size_t m = f.vertices.size();
    for (std::size_t k = 0; k < m; ++k) {
      const int a = f.vertices[k], b = f.vertices[(k + 1) % m];
      if (a > b) continue;
      if ((s[a] < -snap && s[b] > snap) || (s[a] > snap && s[b] < -snap)) {
        const double t = s[a] / (s[a] - s[b]);
        pts.push_back(vertices_[a] + t * (vertices_[b] - vertices_[a]));
      }
    }
  }
  order_about(pts, plane.normal);
  return pts;
}

std::optional<CellParts> ConvexCell::split(const Halfspace& plane, const FaceTag& tag,
                                           double snap) const {
  const int nv = static_cast<int>(vertices_.size());
  std::vector<int> side(nv);
  std::vector<double> s(nv);
  bool has_below = false, has_above = false;
  for (int i = 0; i < nv; ++i) {
    s[i] = plane.signed_distance(vertices_[i]);
    side[i] = s[i] > snap ? 1 : (s[i] < -snap ? -1 : 0);
    has_below |= side[i] < 0;
    has_above |= side[i] > 0;
  }
  if (!has_below || !has_above) return std::nullopt;

  CellParts p;
  std::vector<int> map_below(nv, -1), map_above(nv, -1);
  auto vb = [&](int i) {
    if (map_below[i] < 0) {
      map_below[i] = static_cast<int>(p.below.vertices_.size());
      p.below.vertices_.push_back(vertices_[i]);
    }
    return map_below[i];
  };
  auto va = [&](int i) {
    if (map_above[i] < 0) {
      map_above[i] = static_cast<int>(p.above.vertices_.size());
      p.above.vertices_.push_back(vertices_[i]);
    }
    return map_above[i];
  };
  // Edge crossings, made once per edge and shared by the two faces that hold the edge.
  struct Crossing {
    int a, b, below, above;
  };
  std::vector<Crossing> crossings;
  std::vector<int> cap_below, cap_above;
  auto crossing = [&](int a, int b) -> const Crossing& {
    const int lo = std::min(a, b), hi = std::max(a, b);
    for (const auto& c : crossings) {
      if (c.a == lo && c.b == hi) return c;
    }
    // Interpolate from the lower index so both faces get bit-identical points.
    const double t = s[lo] / (s[lo] - s[hi]);
    const Eigen::Vector3d x = vertices_[lo] + t * (vertices_[hi] - vertices_[lo]);
    const int ib = static_cast<int>(p.below.vertices_.size());
    const int ia = static_cast<int>(p.above.vertices_.size());
    p.below.vertices_.push_back(x);
    p.above.vertices_.push_back(x);
    cap_below.push_back(ib);
    cap_above.push_back(ia);
    crossings.push_back(Crossing{lo, hi, ib, ia});
    return crossings.back();
  };

  for (const auto& f : faces_) {
    CellFace fb{f.plane, f.tag, {}}, fa{f.plane, f.tag, {}};
    bool any_below = false, any_above = false;
    const std::size_t m = f.vertices.size();
    for (std::size_t k = 0; k < m; ++k) {
      const int a = f.vertices[k], b = f.vertices[(k + 1) % m];
      any_below |= side[a] < 0;
      any_above |= side[a] > 0;
      if (side[a] <= 0) fb.vertices.push_back(vb(a));
      if (side[a] >= 0) fa.vertices.push_back(va(a));
      if (side[a] * side[b] < 0) {
        const Crossing c = crossing(a, b);
        fb.vertices.push_back(c.below);
        fa.vertices.push_back(c.above);
      }
    }
    if (any_below && fb.vertices.size() >= 3) p.below.faces_.push_back(std::move(fb));
    if (any_above && fa.vertices.size() >= 3) p.above.faces_.push_back(std::move(fa));
  }
  // Vertices on the plane belong to both caps.
  for (int i = 0; i < nv; ++i) {
    if (side[i] == 0) {
      cap_below.push_back(vb(i));
      cap_above.push_back(va(i));
    }
  }
  // The caps: outward normal +n for the part below, -n for the part above.
  order_indices(cap_below, p.below.vertices_, plane.normal);
  order_indices(cap_above, p.above.vertices_, -plane.normal);
  p.below.faces_.push_back(CellFace{plane, tag, std::move(cap_below)});
  p.above.faces_.push_back(
      CellFace{Halfspace{-plane.normal, -plane.offset}, tag, std::move(cap_above)});
  p.below.update_mass_properties();
  p.above.update_mass_properties();
  return p;
}

void ConvexCell::shrink_to_fit() {
  vertices_.shrink_to_fit();
  faces_.shrink_to_fit();
  for (auto& f : faces_) f.vertices.shrink_to_fit();
}

void ConvexCell::update_mass_properties() {
  // Signed tetrahedra from a reference vertex r over a fan of every face:
  // V = Σ (p0-r)·((p1-r)×(p2-r))/6, centroid = Σ V_t (r+p0+p1+p2)/4 / V.
  const Eigen::Vector3d r = vertices_.front();
  double vol = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  for (const auto& f : faces_) {
    const Eigen::Vector3d a = vertices_[f.vertices[0]] - r;
    for (std::size_t i = 1; i + 1 < f.vertices.size(); ++i) {
      const Eigen::Vector3d b = vertices_[f.vertices[i]] - r;
      const Eigen::Vector3d c = vertices_[f.vertices[i + 1]] - r;
      const double v = a.dot(b.cross(c)) / 6.0;
      vol += v;
      first += v * (a + b + c) / 4.0;
    }
  }
  volume_ = vol;
  centroid_ = vol > 0.0 ? Eigen::Vector3d(r + first / vol) : r;
}

}  // namespace blockdem
