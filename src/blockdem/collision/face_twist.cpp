// Polar and radial moments over a face contact's cells, for the twisting resistance.
#include "blockdem/collision/face_twist.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <variant>

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
// triangle's kSplit² similar sub-triangles, and returns a sub-triangle's area: ∫ f dA = area Σ w f.
template <int kSplit = 4, class F>  // kSplit: sub-triangles along each edge
double integrate_split(const Node& a, const Node& b, const Node& c, F&& f) {
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

// Closed forms of full slip over a cell whose normal stress is linear (see face_twist.hpp).
constexpr double kSliver = 1e-6;
struct SlipSums {
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  // V = ∫ σ (y - p) / |y - p| dA (N/m^0)
  double radial = 0.0;                                  // W = ∫ σ |y - p| dA (N m)
};

// ln((s_b + ρ_b) / (s_a + ρ_a)) = ∫ ds / ρ from s_a to s_b (ρ = √(h² + s²)), without the
// cancellation of s + ρ for s < 0 (there s + ρ = h² / (ρ - s)).
double inverse_radius_integral(double sa, double sb, double ra, double rb, double h) {
  if (sa >= 0.0 && sb >= 0.0) return std::log((sb + rb) / (sa + ra));
  if (sa <= 0.0 && sb <= 0.0) return std::log((ra - sa) / (rb - sb));
  const double ah = std::abs(h);
  return std::asinh(sb / ah) - std::asinh(sa / ah);
}

// V and W over a convex cell (vertices in order, either sense) on which σ(p + d) = s0 + q · d,
// d in the plane of unit normal n: the cell is the signed fan of triangles (p, v_i, v_i+1).
// On the edge v_i -> v_i+1 with unit direction t, ν = t × n, the points are p + h ν + s t
// (h = (v_i - p) · ν, signed) and the triangle is y = p + λ (h ν + s t), dA = λ h dλ ds, so a
// function homogeneous of degree k in d integrates to h / (k + 2) ∫ f(h ν + s t) ds; the
// integrals in s are elementary (ρ = |d| on the edge):
//   ∫ d / ρ dA    = (h/2) [ν h L + t (ρ_b - ρ_a)],               L = ∫ ds / ρ,
//   ∫ ρ dA        = (h/3) R1,                                     R1 = ∫ ρ ds = [s ρ + h² L]/2,
//   ∫ ρ d dA      = (h/4) [ν h R1 + t (ρ_b³ - ρ_a³)/3],
//   ∫ d dᵀ / ρ dA = (h/3) [ν νᵀ h² L + (ν tᵀ + t νᵀ) h (ρ_b - ρ_a) + t tᵀ (s ρ - h² L)/2].
// Then V = s0 ∫ d/ρ + (∫ d dᵀ/ρ) q and W = s0 ∫ ρ + q · ∫ ρ d.
// Empty for a cell too thin to carry a gradient (the rule then integrates it).
std::optional<SlipSums> linear_slip_sums(std::span<const Eigen::Vector3d> v,
                                         std::span<const double> stress,
                                         const Eigen::Vector3d& normal, const Eigen::Vector3d& p) {
  SlipSums out;
  const std::size_t m = v.size();
  if (m < 3) return std::nullopt;
  // The stress gradient q from the cell's largest fan triangle (σ is linear on the cell).
  std::size_t best = 1;
  double best_area = -1.0;
  for (std::size_t k = 1; k + 1 < m; ++k) {
    const double a2 = (v[k] - v[0]).cross(v[k + 1] - v[0]).squaredNorm();
    if (a2 > best_area) {
      best_area = a2;
      best = k;
    }
  }
  if (!(best_area > 0.0)) return std::nullopt;
  const Eigen::Vector3d e1 = v[best] - v[0], e2 = v[best + 1] - v[0];
  const Eigen::Vector3d nn = e1.cross(e2);
  // The gradient only from a triangle that is not a sliver (twice its area at least 1e-6 of the
  // cell's diameter squared), and only if every vertex agrees with it (to 1e-9 of the largest
  // stress): a sliver cell's closures, at nearly coincident vertices, need not be those of one
  // plane, and a wrong gradient carried to a distant centre would ruin the sums.
  double diameter2 = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < m; ++i) {
    largest = std::max(largest, std::abs(stress[i]));
    for (std::size_t j = i + 1; j < m; ++j)
      diameter2 = std::max(diameter2, (v[j] - v[i]).squaredNorm());
  }
  if (!(nn.norm() >= kSliver * diameter2)) return std::nullopt;
  const Eigen::Vector3d q =
      ((stress[best] - stress[0]) * e2.cross(nn) + (stress[best + 1] - stress[0]) * nn.cross(e1)) /
      nn.squaredNorm();
  for (std::size_t i = 1; i < m; ++i) {
    if (!(std::abs(stress[0] + q.dot(v[i] - v[0]) - stress[i]) <= 1e-9 * largest))
      return std::nullopt;
  }
  const double s0 = stress[0] + q.dot(p - v[0]);
  Eigen::Vector3d d_over_r = Eigen::Vector3d::Zero(), r_d = Eigen::Vector3d::Zero();
  Eigen::Vector3d ddq = Eigen::Vector3d::Zero();  // (∫ d dᵀ / ρ dA) q
  double r_int = 0.0, signed_area = 0.0;
  for (std::size_t i = 0; i < m; ++i) {
    const Eigen::Vector3d a = v[i] - p, b = v[(i + 1) % m] - p;
    const Eigen::Vector3d edge = b - a;
    const double length = edge.norm();
    if (!(length > 0.0)) continue;
    const Eigen::Vector3d t = edge / length, nu = t.cross(normal);
    const double h = a.dot(nu);
    signed_area += 0.5 * h * length;
    // A triangle of zero height adds nothing (its terms vanish like h² ln h).
    if (!(std::abs(h) > 1e-14 * length)) continue;
    const double sa = a.dot(t), sb = b.dot(t), ra = a.norm(), rb = b.norm();
    const double l = inverse_radius_integral(sa, sb, ra, rb, h);
    const double dr = length * (sa + sb) / (ra + rb);  // ρ_b - ρ_a, without cancellation
    const double sr = sb * rb - sa * ra, hh = h * h;
    const double r1 = 0.5 * (sr + hh * l);
    const double qn = q.dot(nu), qt = q.dot(t);
    d_over_r += 0.5 * h * (h * l * nu + dr * t);
    r_int += h * r1 / 3.0;
    r_d += 0.25 * h * (h * r1 * nu + dr * (rb * rb + ra * rb + ra * ra) / 3.0 * t);
    ddq += (h / 3.0) *
           ((hh * l * qn + h * dr * qt) * nu + (h * dr * qn + 0.5 * (sr - hh * l) * qt) * t);
  }
  const double sense = signed_area < 0.0 ? -1.0 : 1.0;
  out.direction = sense * (s0 * d_over_r + ddq);
  out.radial = sense * (s0 * r_int + q.dot(r_d));
  return out;
}

// Beyond this many cell diameters from the centre the slip direction is smooth over the cell
// (analytic in a disc of that radius): the 7-point rule on the fan triangles alone is exact to
// about (1e-3)⁶, while the closed forms' terms, of order D² a σ, cancel to the result's a² σ.
constexpr double kFarCentre = 1e3;
// The largest error of the stress's linear stand-in the closed forms accept, relative to the
// cell's largest stress.
constexpr double kLinearStressTolerance = 1e-6;

// The cell's stresses at its vertices when σ_n is linear over the cell within
// kLinearStressTolerance of its largest value: the linear law exactly (the closure is linear); the
// exponential law by its chord in g between the cell's least and largest closures, whose error
// is at most σ''(g_max) Δg² / 8 = b² (σ(g_max) + a) Δg² / 8 (a convex function above its chord).
// False otherwise (the quadrature then integrates the cell).
bool linear_cell_stress(const ClosureCell& cell, const NormalLaw& law,
                        SmallVector<double, 8>& out) {
  const auto& g = cell.closures;
  out.clear();
  if (const auto* linear = std::get_if<LinearNormal>(&law)) {
    for (const double gi : g) out.push_back(linear->stiffness * std::max(gi, 0.0));
    return true;
  }
  const auto& e = std::get<ExponentialNormal>(law);
  const auto [lo, hi] = std::minmax_element(g.begin(), g.end());
  const double g0 = std::max(*lo, 0.0), g1 = std::max(*hi, 0.0), spread = g1 - g0;
  const double s0 = normal_stress(law, g0), s1 = normal_stress(law, g1);
  if (spread > 0.0) {
    const double gap = e.b * e.b * (s1 + e.a) * spread * spread / 8.0;
    if (!(gap <= kLinearStressTolerance * s1)) return false;
  }
  const double slope = spread > 0.0 ? (s1 - s0) / spread : 0.0;
  for (const double gi : g) out.push_back(s0 + slope * (std::max(gi, 0.0) - g0));
  return true;
}

// A unit normal of a cell's plane (Newell's sum; either sense).
Eigen::Vector3d cell_normal(std::span<const Eigen::Vector3d> v) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (std::size_t i = 1; i + 1 < v.size(); ++i) n += (v[i] - v[0]).cross(v[i + 1] - v[0]);
  const double norm = n.norm();
  return norm > 0.0 ? Eigen::Vector3d(n / norm) : Eigen::Vector3d::Zero();
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
  // Over a triangle with vertices u_i (from the centre) and closures g_i, with the barycentric
  // integrals ∫ λ_i λ_j λ_k dA = A (1 + δ_ij + δ_jk + δ_ik + 2 δ_ij δ_jk) / 60 (and
  // ∫ λ_i λ_j dA = A (1 + δ_ij) / 12), U = Σ u_i, T = Σ |u_i|², G = Σ g_i:
  //   ∫ r² dA = A (|U|² + T) / 12,   ∫ g r² dA = A (G (|U|² + T) + 2 (Σ g_i u_i) · U
  //   + 2 Σ g_i |u_i|²) / 60.
  ClosurePolarMoments m;
  for (const ClosureCell& cell : cells) {
    const auto& v = cell.vertices;
    const auto& g = cell.closures;
    if (v.size() < 3) continue;
    const Eigen::Vector3d u0 = v[0] - centre;
    const double t0 = u0.squaredNorm();
    for (std::size_t k = 1; k + 1 < v.size(); ++k) {
      const Eigen::Vector3d u1 = v[k] - centre, u2 = v[k + 1] - centre;
      const double area = 0.5 * (u1 - u0).cross(u2 - u0).norm();
      const double t1 = u1.squaredNorm(), t2 = u2.squaredNorm();
      const Eigen::Vector3d sum = u0 + u1 + u2;
      const double quadratic = sum.squaredNorm() + t0 + t1 + t2;
      const double gsum = g[0] + g[k] + g[k + 1];
      const Eigen::Vector3d gu = g[0] * u0 + g[k] * u1 + g[k + 1] * u2;
      const double gt = g[0] * t0 + g[k] * t1 + g[k + 1] * t2;
      m.polar_moment += area * quadratic / 12.0;
      m.closure_polar_moment += area * (gsum * quadratic + 2.0 * gu.dot(sum) + 2.0 * gt) / 60.0;
    }
  }
  return m;
}

FaceTwistMoments face_twist_moments(std::span<const ClosureCell> cells, const NormalLaw& law,
                                    const Eigen::Vector3d& centre) {
  FaceTwistMoments m;
  SmallVector<double, 8> stress;
  for (const ClosureCell& cell : cells) {
    const std::span<const Eigen::Vector3d> vertices(cell.vertices.data(), cell.vertices.size());
    const PolygonMoments pm = polygon_moments(vertices, centre);
    m.compressed_area += pm.area;
    m.polar_moment += pm.polar_moment;
    m.radial_moment += pm.radial_moment;
    if (linear_cell_stress(cell, law, stress)) {
      const std::span<const double> s(stress.data(), stress.size());
      if (const auto sums = linear_slip_sums(vertices, s, cell_normal(vertices), centre)) {
        m.radial_normal_moment += sums->radial;
        continue;
      }
    }
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
  SmallVector<double, 8> stress;
  const Eigen::Vector3d& p = centre.point;
  // Sums by the rule with kSplit² sub-triangles on each fan triangle of the cell.
  const auto by_rule = [&]<int kSplit>(const ClosureCell& cell) {
    const auto& v = cell.vertices;
    const auto& g = cell.closures;
    for (std::size_t k = 1; k + 1 < v.size(); ++k) {
      FullSlip t;  // this triangle's sums Σ w f
      const double area = integrate_split<kSplit>(
          {v[0], g[0]}, {v[k], g[k]}, {v[k + 1], g[k + 1]}, [&](const Node& y, double weight) {
            const double sigma = normal_stress(law, y.g);
            // w = s n × (y - p): the slip of B at y; the traction on B opposes it.
            const Eigen::Vector3d w = centre.sense * normal.cross(y.x - p);
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
  };
  for (const ClosureCell& cell : cells) {
    const auto& v = cell.vertices;
    double size = 0.0;
    for (const auto& x : v) size = std::max(size, (x - v[0]).norm());
    if ((p - v[0]).norm() > kFarCentre * size) {
      by_rule.template operator()<1>(cell);
      continue;
    }
    const std::optional<SlipSums> sums =
        linear_cell_stress(cell, law, stress)
            ? linear_slip_sums(std::span<const Eigen::Vector3d>(v.data(), v.size()),
                               std::span<const double>(stress.data(), stress.size()), normal, p)
            : std::nullopt;
    if (sums) {
      // Traction -σ s n × d / |d| (d = y - p): F = -s n × V, power W, and the moment about x_p
      // -s ∫ σ (y - x_p) · d / |d| dA = -s (W + (p - x_p) · V).
      s.force -= centre.sense * normal.cross(sums->direction);
      s.moment -= centre.sense * (sums->radial + (p - force_point).dot(sums->direction));
      s.power += sums->radial;
    } else {
      by_rule.template operator()<4>(cell);
    }
  }
  return s;
}

}  // namespace blockdem
