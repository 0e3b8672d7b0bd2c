// Polar and radial moments over a face contact's cells, for the twisting resistance.
#include "blockdem/collision/face_twist.hpp"

#include <array>

#include "blockdem/geometry/polygon_moments.hpp"

namespace blockdem {
namespace {

// Dunavant's 7-point rule (degree 5): barycentric points and weights (weights sum to 1).
struct QuadraturePoint {
  double l0, l1, l2, weight;
};
constexpr double kA1 = 0.059715871789770, kB1 = 0.470142064105115, kW1 = 0.132394152788506;
constexpr double kA2 = 0.797426985353087, kB2 = 0.101286507323456, kW2 = 0.125939180544827;
constexpr std::array<QuadraturePoint, 7> kRule{{{1.0 / 3, 1.0 / 3, 1.0 / 3, 0.225},
                                                {kA1, kB1, kB1, kW1},
                                                {kB1, kA1, kB1, kW1},
                                                {kB1, kB1, kA1, kW1},
                                                {kA2, kB2, kB2, kW2},
                                                {kB2, kA2, kB2, kW2},
                                                {kB2, kB2, kA2, kW2}}};

// A point of the contact with its closure (linear over each cell).
struct Node {
  Eigen::Vector3d x;
  double g;
};

Node mix(const Node& a, const Node& b, const Node& c, double la, double lb, double lc) {
  return {la * a.x + lb * b.x + lc * c.x, la * a.g + lb * b.g + lc * c.g};
}

// Calls f(y, w) at every point y of the rule (weight w, summing to 1 per sub-triangle) on the
// triangle's 16 similar sub-triangles, and returns a sub-triangle's area: ∫ f dA = area Σ w f.
template <class F>
double integrate_split(const Node& a, const Node& b, const Node& c, F&& f) {
  constexpr int kSplit = 4;      // sub-triangles along each edge
  auto at = [&](int i, int j) {  // lattice node i, j
    const double li = static_cast<double>(i) / kSplit, lj = static_cast<double>(j) / kSplit;
    return mix(a, b, c, 1.0 - li - lj, li, lj);
  };
  auto integrate = [&](const Node& p, const Node& q, const Node& r) {
    for (const auto& w : kRule) f(mix(p, q, r, w.l0, w.l1, w.l2), w.weight);
  };
  for (int i = 0; i < kSplit; ++i) {
    for (int j = 0; i + j < kSplit; ++j) {
      integrate(at(i, j), at(i + 1, j), at(i, j + 1));
      if (i + j + 1 < kSplit) integrate(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  return 0.5 * (b.x - a.x).cross(c.x - a.x).norm() / (kSplit * kSplit);
}

// ∫ σ_n(g) |x - centre| dA over a triangle, by the rule on its 16 similar sub-triangles.
double radial_stress_moment(const Node& a, const Node& b, const Node& c, const NormalLaw& law,
                            const Eigen::Vector3d& centre) {
  double sum = 0.0;
  const double area = integrate_split(a, b, c, [&](const Node& y, double weight) {
    sum += weight * normal_stress(law, y.g) * (y.x - centre).norm();
  });
  return sum * area;
}

}  // namespace

ClosurePolarMoments face_closure_polar_moments(std::span<const ClosureCell> cells,
                                               const Eigen::Vector3d& centre) {
  ClosurePolarMoments m;
  for (const ClosureCell& cell : cells) {
    const auto& v = cell.vertices;
    const auto& g = cell.closures;
    for (std::size_t k = 1; k + 1 < v.size(); ++k) {
      const double area = 0.5 * (v[k] - v[0]).cross(v[k + 1] - v[0]).norm();
      double r2 = 0.0, gr2 = 0.0;
      for (const auto& w : kRule) {
        const Node y = mix({v[0], g[0]}, {v[k], g[k]}, {v[k + 1], g[k + 1]}, w.l0, w.l1, w.l2);
        const double rr = (y.x - centre).squaredNorm();
        r2 += w.weight * rr;
        gr2 += w.weight * y.g * rr;
      }
      m.polar_moment += r2 * area;
      m.closure_polar_moment += gr2 * area;
    }
  }
  return m;
}

FaceTwistMoments face_twist_moments(std::span<const ClosureCell> cells, const NormalLaw& law,
                                    const Eigen::Vector3d& centre) {
  FaceTwistMoments m;
  for (const ClosureCell& cell : cells) {
    const std::span<const Eigen::Vector3d> vertices(cell.vertices.data(), cell.vertices.size());
    const PolygonMoments pm = polygon_moments(vertices, centre);
    m.compressed_area += pm.area;
    m.polar_moment += pm.polar_moment;
    m.radial_moment += pm.radial_moment;
    for (std::size_t k = 1; k + 1 < vertices.size(); ++k) {
      m.radial_normal_moment +=
          radial_stress_moment({vertices[0], cell.closures[0]}, {vertices[k], cell.closures[k]},
                               {vertices[k + 1], cell.closures[k + 1]}, law, centre);
    }
  }
  return m;
}

FullSlip face_full_slip(std::span<const ClosureCell> cells, const NormalLaw& law,
                        const Eigen::Vector3d& normal, const Eigen::Vector3d& force_point,
                        const SlipCentre& centre) {
  FullSlip s;
  for (const ClosureCell& cell : cells) {
    const auto& v = cell.vertices;
    const auto& g = cell.closures;
    for (std::size_t k = 1; k + 1 < v.size(); ++k) {
      FullSlip t;  // this triangle's sums Σ w f
      const double area = integrate_split(
          {v[0], g[0]}, {v[k], g[k]}, {v[k + 1], g[k + 1]}, [&](const Node& y, double weight) {
            const double sigma = normal_stress(law, y.g);
            // w = s n × (y - p): the slip of B at y; the traction on B opposes it.
            const Eigen::Vector3d w = centre.sense * normal.cross(y.x - centre.point);
            const double speed = w.norm();
            if (!(sigma > 0.0) || !(speed > 0.0)) return;
            const Eigen::Vector3d traction = (weight * sigma / speed) * w;
            t.force -= traction;
            t.moment -= (y.x - force_point).cross(traction).dot(normal);
            t.power += weight * sigma * speed;
          });
      s.force += area * t.force;
      s.moment += area * t.moment;
      s.power += area * t.power;
    }
  }
  return s;
}

}  // namespace blockdem
