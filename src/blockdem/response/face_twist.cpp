// Polar and radial moments and full slip over a face contact's cells, for the twisting resistance.
#include "blockdem/response/face_twist.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <variant>

#include "blockdem/contact/overloaded.hpp"
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
// The rule's points per fan triangle: 7 on each of its 4² similar sub-triangles.
constexpr std::size_t kRulePoints = 7 * 16;
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
                                         std::span<const double> stress, double stress_per_closure,
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
  // cell's diameter squared), and only if every vertex agrees with it: a sliver cell's closures,
  // at nearly coincident vertices, need not be those of one plane, and a wrong gradient carried
  // to a distant centre would ruin the sums.
  double diameter2 = 0.0, largest = 0.0, reach = 0.0;
  for (std::size_t i = 0; i < m; ++i) {
    largest = std::max(largest, std::abs(stress[i]));
    reach = std::max(reach, v[i].cwiseAbs().maxCoeff());
    for (std::size_t j = i + 1; j < m; ++j)
      diameter2 = std::max(diameter2, (v[j] - v[i]).squaredNorm());
  }
  if (!(nn.norm() >= kSliver * diameter2)) return std::nullopt;
  const Eigen::Vector3d q =
      ((stress[best] - stress[0]) * e2.cross(nn) + (stress[best + 1] - stress[0]) * nn.cross(e1)) /
      nn.squaredNorm();
  // Agreement to 1e-9 of the largest stress, or to the round-off of the closures: each is a
  // difference of plane offsets at the vertex's coordinates (face_contact), so it carries an
  // absolute error of some ulps of the coordinates' magnitude X, whatever its own size; the
  // stress δσ = σ' 16 ε X (σ' the stand-in's stress per closure). The gradient from the triangle
  // then errs by up to 2 δσ D / |e1 × e2| (D the cell's diameter), which the prediction at a
  // vertex up to D away multiplies by D; with the errors of the two stresses compared, 4 δσ
  // (1 + D² / |e1 × e2|). Cells accepted this way integrate a plane within that of their
  // closures, as those of a cell that passes at 1e-9 do.
  const double round_off = 16.0 * std::numeric_limits<double>::epsilon() * reach *
                           std::abs(stress_per_closure) * 4.0 * (1.0 + diameter2 / nn.norm());
  for (std::size_t i = 1; i < m; ++i) {
    if (!(std::abs(stress[0] + q.dot(v[i] - v[0]) - stress[i]) <= 1e-9 * largest + round_off))
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

// The exponential law's radial moments along a ray (exponential_slip_sums): for j = 0, 1, 2,
// φ_j(x) = ∫_0^1 exp(-x (1 - t)) t^j dt and ψ_j(x) = φ_j(x) - 1 / (j + 1). For |x| < 1/2 the
// series ψ_j = Σ_{k>=1} (-x)^k j! / (j + k + 1)! (12 terms: the first omitted is below 1e-14 of
// ψ_j); otherwise φ_0 = -expm1(-x) / x and, by parts, φ_j = (1 - j φ_{j-1}) / x (each step
// multiplies the round-off by at most j / |x| <= 4).
struct RayMoments {
  std::array<double, 3> phi, psi;
};
constexpr int kSeriesTerms = 12;
constexpr std::array<std::array<double, kSeriesTerms + 1>, 3> series_coefficients() {
  std::array<std::array<double, kSeriesTerms + 1>, 3> c{};
  for (int j = 0; j < 3; ++j) {
    double ck = j == 2 ? 2.0 : 1.0;  // j!
    for (int i = 1; i <= j + 1; ++i) ck /= i;
    for (int k = 1; k <= kSeriesTerms; ++k) {
      ck /= (j + k + 1);
      c[j][k] = ck;  // j! / (j + k + 1)!
    }
  }
  return c;
}
constexpr auto kSeries = series_coefficients();

// From j = `first` on (the series; the recurrence needs them all).
RayMoments ray_moments(double x, int first) {
  RayMoments r{};
  if (std::abs(x) < 0.5) {
    for (int j = first; j < 3; ++j) {
      double sum = 0.0;
      for (int k = kSeriesTerms; k >= 1; --k) sum = (sum + kSeries[j][k]) * -x;
      r.psi[j] = sum;
      r.phi[j] = 1.0 / (j + 1) + sum;
    }
    return r;
  }
  r.phi[0] = -std::expm1(-x) / x;
  r.phi[1] = (1.0 - r.phi[0]) / x;
  r.phi[2] = (1.0 - 2.0 * r.phi[1]) / x;
  for (int j = 0; j < 3; ++j) r.psi[j] = r.phi[j] - 1.0 / (j + 1);
  return r;
}

// Full slip of the exponential law σ = a (exp(b g) - 1) over a cell on which the closure g is
// linear (and >= 0), in polar coordinates about p: along a ray the closure is linear in r, so
// the radial integrals ∫ σ r^m dr (m = 1 for V, m = 2 for W) are closed forms (RayMoments), and
// the angle is integrated by Gauss-Legendre along each edge (see face_twist.hpp).
//
// Ray: from r = R1 (closure g1) to the edge point at r = ρ (closure g_e), λ1 = R1 / ρ,
// x = b (g_e - g1); with r = R1 + t (ρ - R1) and exp(b g(r)) = exp(b g_e) exp(-x (1 - t)),
//   ∫_{R1}^{ρ} σ r^m dr = a ρ^{m+1} Σ_j C(m, j) λ1^{m-j} (1 - λ1)^{j+1}
//                           [expm1(b g_e) φ_j(x) + ψ_j(x)]   (=: a ρ^{m+1} Ĩ_m),
// written with expm1 and ψ so that a small b g (σ ≈ a b g) loses nothing to the "-1".
// Edge: the points p + d(s), d = h ν + s t as in linear_slip_sums; the fan triangle's area
// element is (h / ρ²) ds r dr, and with s = |h| sinh u (ds = ρ du, ρ = |h| cosh u) the angular
// integrands h d Ĩ_1 (for V) and h ρ² Ĩ_2 (for W) are analytic in u: no 1/ρ singularity is left
// for the quadrature. Per edge, Gauss-Legendre (6 points) on pieces of at most kPieceWidth in u
// and kPieceExponent in b g_e (both bound the integrand's variation on a piece).
// Where the rays start: p inside the cell (or on its boundary), R1 = 0 and g1 = g(p) from the
// fan triangle containing p (an interpolation). p outside: the chord L between the two vertices
// where the edges seen from p turn from near (h of the other sign than the cell's) to far
// divides every ray's chord of the cell; each edge integrates between L and itself (the near
// edges, with their negative h and λ1 > 1, the part of the cell between them and L), so g1 is
// interpolated on L, every closure used is one of the cell's, and the parts of the signed fan
// between p and L, which cancel, are never formed (the stress extrapolated there can exceed the
// cell's by exp(b Δg)).
constexpr double kPieceWidth = 2.0;
constexpr double kPieceExponent = 1.0;
constexpr double kPoleRatio = 0.5;
// Gauss-Legendre on [-1, 1]: nodes and weights.
struct GaussPoint {
  double x, w;
};
constexpr std::array<GaussPoint, 4> kGauss{{{-0.8611363115940526, 0.3478548451374538},
                                            {-0.3399810435848563, 0.6521451548625461},
                                            {0.3399810435848563, 0.6521451548625461},
                                            {0.8611363115940526, 0.3478548451374538}}};

std::optional<SlipSums> exponential_slip_sums(std::span<const Eigen::Vector3d> v,
                                              std::span<const double> g,
                                              const ExponentialNormal& law,
                                              const Eigen::Vector3d& normal,
                                              const Eigen::Vector3d& p) {
  const std::size_t m = v.size();
  if (m < 3) return std::nullopt;
  // Heights of the edges seen from p, the cell's sense, and which edges are far (p sees the
  // cell's inside beyond them: +1), near (-1) or of no height (0).
  SmallVector<double, 8> heights;
  SmallVector<int, 8> side;
  double signed_area = 0.0, diameter2 = 0.0;
  for (std::size_t i = 0; i < m; ++i) {
    const Eigen::Vector3d edge = v[(i + 1) % m] - v[i];
    const double length = edge.norm();
    const double h = length > 0.0 ? (v[i] - p).dot(edge.cross(normal)) / length : 0.0;
    heights.push_back(h);
    side.push_back(h > 1e-14 * length ? 1 : h < -1e-14 * length ? -1 : 0);
    signed_area += 0.5 * h * length;
    for (std::size_t j = i + 1; j < m; ++j)
      diameter2 = std::max(diameter2, (v[j] - v[i]).squaredNorm());
  }
  if (!(signed_area != 0.0)) return std::nullopt;
  const double sense = signed_area < 0.0 ? -1.0 : 1.0;
  const auto far = [&](std::size_t i) { return sense * side[i] > 0; };
  const auto near = [&](std::size_t i) { return sense * side[i] < 0; };
  bool outside = false;
  for (std::size_t i = 0; i < m; ++i) outside = outside || near(i);
  // The rays' start: the chord L (outside) or p with its closure (inside).
  Eigen::Vector3d chord_start = Eigen::Vector3d::Zero(), chord = Eigen::Vector3d::Zero();
  Eigen::Vector3d chord_normal = Eigen::Vector3d::Zero();
  double chord_height = 0.0, g_lo = 0.0, g_hi = 0.0, g_p = 0.0;
  if (outside) {
    std::size_t lo = m, hi = m;
    for (std::size_t i = 0; i < m; ++i) {
      if (far(i) && !far((i + m - 1) % m)) lo = i;
      if (far(i) && !far((i + 1) % m)) hi = (i + 1) % m;
    }
    if (lo == m || hi == m || lo == hi) return std::nullopt;
    chord_start = v[lo];
    chord = v[hi] - v[lo];
    chord_normal = chord.cross(normal).normalized();
    chord_height = (v[lo] - p).dot(chord_normal);
    if (chord_height < 0.0) {
      chord_normal = -chord_normal;
      chord_height = -chord_height;
    }
    if (!(chord_height > 0.0)) return std::nullopt;
    g_lo = g[lo];
    g_hi = g[hi];
  } else {
    // g(p) by interpolation in the fan triangle (v0, v_k, v_k+1) that contains p best (the
    // largest least barycentric coordinate); none of them a sliver.
    double best = -std::numeric_limits<double>::infinity();
    for (std::size_t k = 1; k + 1 < m; ++k) {
      const double area = (v[k] - v[0]).cross(v[k + 1] - v[0]).dot(normal);
      if (!(std::abs(area) >= kSliver * diameter2)) continue;
      const double l1 = (v[k] - p).cross(v[k + 1] - p).dot(normal) / area;
      const double l2 = (v[k + 1] - p).cross(v[0] - p).dot(normal) / area;
      const double l3 = 1.0 - l1 - l2;
      const double least = std::min({l1, l2, l3});
      if (least > best) {
        best = least;
        g_p = l1 * g[0] + l2 * g[k] + l3 * g[k + 1];
      }
    }
    if (!(best > -1e-6)) return std::nullopt;
  }
  const double b = law.b;
  // An edge's span in u, the widest piece and the pole (outside: λ1 = h_L / (d · ν_L) has a pole
  // at the ray parallel to L, and the pieces shrink towards it, each at most kPoleRatio of its
  // distance from it; at least 1/64 of the edge).
  struct EdgeSpan {
    double ua = 0.0, ub = 0.0, widest = 0.0, pole = 0.0;
    bool has_pole = false;
  };
  const auto edge_span = [&](std::size_t i) {
    const double h = heights[i], ah = std::abs(h);
    const Eigen::Vector3d a = v[i] - p, edge = v[(i + 1) % m] - v[i];
    const double length = edge.norm();
    const Eigen::Vector3d t = edge / length, nu = t.cross(normal);
    const double sa = a.dot(t), slope = (g[(i + 1) % m] - g[i]) / length;
    EdgeSpan e;
    e.ua = std::asinh(sa / ah);
    e.ub = std::asinh((sa + length) / ah);
    // The widest piece: b g_e changes along u at the rate b |slope| ρ, at most at the farther end.
    const double rate = b * std::abs(slope) * std::max(a.norm(), (a + edge).norm());
    e.widest = 1.0 / std::max(1.0 / kPieceWidth, rate / kPieceExponent);
    const double across_t = t.dot(chord_normal);
    e.has_pole = outside && across_t != 0.0;
    e.pole = e.has_pole ? std::asinh(-h * nu.dot(chord_normal) / across_t / ah) : 0.0;
    return e;
  };
  const auto piece_end = [](const EdgeSpan& e, double u0) {
    double width = e.widest;
    if (e.has_pole && e.pole <= u0) width = std::min(width, kPoleRatio * (u0 - e.pole));
    if (e.has_pole && e.pole > u0)
      width = std::min(width, kPoleRatio * (e.pole - u0) / (1.0 + kPoleRatio));
    width = std::max(width, (e.ub - e.ua) / 64.0);
    // An edge seen almost end-on spans a few ulps of u: a width below u0's ulp would not move
    // u0, so the last piece ends at ub.
    const double u1 = std::min(u0 + width, e.ub);
    return u1 > u0 ? u1 : e.ub;
  };
  // A cell whose pieces would take more points than the rule's (kRulePoints per fan triangle)
  // is left to the rule: a strongly curved stress seen from a centre close to an edge can ask
  // for up to 64 pieces per edge, and the rule is then the cheaper of two accurate answers.
  std::size_t points = 0;
  SmallVector<EdgeSpan, 8> spans;
  for (std::size_t i = 0; i < m; ++i) {
    spans.push_back(EdgeSpan{});
    if (!far(i) && !near(i)) continue;
    const EdgeSpan& e = spans.back() = edge_span(i);
    for (double u0 = e.ua; u0 < e.ub; u0 = piece_end(e, u0)) points += kGauss.size();
  }
  if (points > kRulePoints * (m - 2)) return std::nullopt;
  SlipSums out;
  for (std::size_t i = 0; i < m; ++i) {
    const double h = heights[i];
    if (!far(i) && !near(i)) continue;  // a triangle of zero height adds nothing
    const Eigen::Vector3d a = v[i] - p, edge = v[(i + 1) % m] - v[i];
    const double length = edge.norm();
    const Eigen::Vector3d t = edge / length, nu = t.cross(normal);
    const double sa = a.dot(t), ah = std::abs(h);
    const double ga = g[i], slope = (g[(i + 1) % m] - ga) / length;  // g_e = ga + slope (s - sa)
    const EdgeSpan& e = spans[i];
    Eigen::Vector3d edge_v = Eigen::Vector3d::Zero();
    double edge_w = 0.0;
    for (double u0 = e.ua; u0 < e.ub;) {
      const double u1 = piece_end(e, u0), half = 0.5 * (u1 - u0), mid = u0 + half;
      u0 = u1;
      Eigen::Vector3d piece_v = Eigen::Vector3d::Zero();
      double piece_w = 0.0;
      for (const GaussPoint& gp : kGauss) {
        const double u = mid + gp.x * half, weight = gp.w;
        const double eu = std::exp(u);
        const double s = 0.5 * ah * (eu - 1.0 / eu), rho2 = h * h + s * s;  // |h| sinh u
        const Eigen::Vector3d d = h * nu + s * t;
        const double ge = ga + slope * (s - sa), bg = b * ge;
        const double expm = bg > 0.5 ? std::exp(bg) - 1.0 : std::expm1(bg);
        double lambda = 0.0, g1 = g_p;
        if (outside) {
          const double across = d.dot(chord_normal);
          if (!(across > 0.0)) return std::nullopt;
          lambda = chord_height / across;
          const double along =
              std::clamp((p + lambda * d - chord_start).dot(chord) / chord.squaredNorm(), 0.0, 1.0);
          g1 = g_lo + along * (g_hi - g_lo);
        }
        const RayMoments rm = ray_moments(b * (ge - g1), outside ? 0 : 1);
        const auto term = [&](int j) { return expm * rm.phi[j] + rm.psi[j]; };
        double i1, i2;
        if (lambda == 0.0) {
          i1 = term(1);
          i2 = term(2);
        } else {
          const double mu = 1.0 - lambda, t0 = term(0), t1 = term(1);
          i1 = mu * (lambda * t0 + mu * t1);
          i2 = mu * (lambda * lambda * t0 + mu * (2.0 * lambda * t1 + mu * term(2)));
        }
        piece_v += (weight * i1) * d;
        piece_w += weight * rho2 * i2;
      }
      edge_v += half * piece_v;
      edge_w += half * piece_w;
    }
    out.direction += h * edge_v;
    out.radial += h * edge_w;
  }
  out.direction *= sense * law.a;
  out.radial *= sense * law.a;
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
bool linear_cell_stress(const ClosureCell& cell, const NormalLaw& law, SmallVector<double, 8>& out,
                        double& stress_per_closure) {
  const auto& g = cell.closures;
  out.clear();
  return std::visit(
      Overloaded{
          [&](const LinearNormal& linear) {
            for (const double gi : g) out.push_back(linear.stiffness * std::max(gi, 0.0));
            stress_per_closure = linear.stiffness;
            return true;
          },
          [&](const ExponentialNormal& e) {
            const auto [lo, hi] = std::minmax_element(g.begin(), g.end());
            const double g0 = std::max(*lo, 0.0), g1 = std::max(*hi, 0.0), spread = g1 - g0;
            const double s0 = normal_stress(law, g0), s1 = normal_stress(law, g1);
            if (spread > 0.0) {
              const double gap = e.b * e.b * (s1 + e.a) * spread * spread / 8.0;
              if (!(gap <= kLinearStressTolerance * s1)) return false;
            }
            const double slope = spread > 0.0 ? (s1 - s0) / spread : 0.0;
            for (const double gi : g) out.push_back(s0 + slope * (std::max(gi, 0.0) - g0));
            stress_per_closure = e.b * (s1 + e.a);  // the law's largest slope on the cell
            return true;
          },
      },
      law);
}

// The closed forms of full slip over a cell whose stress is not linear: the exponential law's
// (exponential_slip_sums, about `centre`); none for the linear law, whose stress is linear over
// every cell (linear_cell_stress).
std::optional<SlipSums> curved_slip_sums(std::span<const Eigen::Vector3d> vertices,
                                         std::span<const double> closures, const NormalLaw& law,
                                         const Eigen::Vector3d& normal,
                                         const Eigen::Vector3d& centre) {
  return std::visit(Overloaded{
                        [](const LinearNormal&) -> std::optional<SlipSums> { return std::nullopt; },
                        [&](const ExponentialNormal& e) {
                          return exponential_slip_sums(vertices, closures, e, normal, centre);
                        },
                    },
                    law);
}

// A unit normal of a cell's plane (Newell's sum; either sense).
Eigen::Vector3d cell_normal(std::span<const Eigen::Vector3d> v) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (std::size_t i = 1; i + 1 < v.size(); ++i) n += (v[i] - v[0]).cross(v[i + 1] - v[0]);
  const double norm = n.norm();
  return norm > 0.0 ? Eigen::Vector3d(n / norm) : Eigen::Vector3d::Zero();
}

// Whether the cell is a sliver (linear_slip_sums: its largest fan triangle's twice area below
// kSliver of its diameter squared). Its area is then below kSliver D² / 2, so the rule on its
// fan triangles alone (7 points, no split) errs by a fraction of the cell's own sums, themselves
// below kSliver D² σ_max (times |y - p| for W): under 1e-6 of those of a contact of that
// diameter, within the closed forms' tolerance; 16 sub-triangles would buy nothing but cost.
bool sliver_cell(std::span<const Eigen::Vector3d> v) {
  double twice_area = 0.0, diameter2 = 0.0;
  for (std::size_t k = 1; k + 1 < v.size(); ++k)
    twice_area = std::max(twice_area, (v[k] - v[0]).cross(v[k + 1] - v[0]).norm());
  for (std::size_t i = 0; i < v.size(); ++i) {
    for (std::size_t j = i + 1; j < v.size(); ++j)
      diameter2 = std::max(diameter2, (v[j] - v[i]).squaredNorm());
  }
  return !(twice_area >= kSliver * diameter2);
}

// ∫ σ_n(g) |x - centre| dA over a triangle, by the rule on its kSplit² similar sub-triangles.
template <int kSplit>
double radial_stress_moment(const Node& a, const Node& b, const Node& c, const NormalLaw& law,
                            const Eigen::Vector3d& centre) {
  double sum = 0.0;
  const double area = integrate_split<kSplit>(a, b, c, [&](const Node& y, double weight) {
    sum += weight * normal_stress(law, y.g) * (y.x - centre).norm();
  });
  return sum * area;
}

// Adds to `s` full slip over the cell by the rule with kSplit² sub-triangles on each fan
// triangle of the cell.
template <int kSplit>
void add_slip_by_rule(FullSlip& s, const ClosureCell& cell, const NormalLaw& law,
                      const Eigen::Vector3d& normal, const Eigen::Vector3d& force_point,
                      const SlipCentre& centre) {
  const Eigen::Vector3d& p = centre.point;
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
    if (double slope = 0.0; linear_cell_stress(cell, law, stress, slope)) {
      const std::span<const double> s(stress.data(), stress.size());
      if (const auto sums = linear_slip_sums(vertices, s, slope, cell_normal(vertices), centre)) {
        m.radial_normal_moment += sums->radial;
        continue;
      }
    }
    const std::span<const double> g(cell.closures.data(), cell.closures.size());
    if (const auto sums = curved_slip_sums(vertices, g, law, cell_normal(vertices), centre)) {
      m.radial_normal_moment += sums->radial;
      continue;
    }
    const bool sliver = sliver_cell(vertices);
    for (std::size_t k = 1; k + 1 < vertices.size(); ++k) {
      const Node a{vertices[0], cell.closures[0]}, b{vertices[k], cell.closures[k]},
          c{vertices[k + 1], cell.closures[k + 1]};
      m.radial_normal_moment += sliver ? radial_stress_moment<1>(a, b, c, law, centre)
                                       : radial_stress_moment<4>(a, b, c, law, centre);
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
  for (const ClosureCell& cell : cells) {
    const auto& v = cell.vertices;
    double size = 0.0;
    for (const auto& x : v) size = std::max(size, (x - v[0]).norm());
    if ((p - v[0]).norm() > kFarCentre * size) {
      add_slip_by_rule<1>(s, cell, law, normal, force_point, centre);
      continue;
    }
    const std::span<const Eigen::Vector3d> vertices(v.data(), v.size());
    double slope = 0.0;
    std::optional<SlipSums> sums =
        linear_cell_stress(cell, law, stress, slope)
            ? linear_slip_sums(vertices, std::span<const double>(stress.data(), stress.size()),
                               slope, normal, p)
            : std::nullopt;
    if (!sums) {
      sums = curved_slip_sums(vertices,
                              std::span<const double>(cell.closures.data(), cell.closures.size()),
                              law, normal, p);
    }
    if (sums) {
      // Traction -σ s n × d / |d| (d = y - p): F = -s n × V, power W, and the moment about x_p
      // -s ∫ σ (y - x_p) · d / |d| dA = -s (W + (p - x_p) · V).
      s.force -= centre.sense * normal.cross(sums->direction);
      s.moment -= centre.sense * (sums->radial + (p - force_point).dot(sums->direction));
      s.power += sums->radial;
    } else if (sliver_cell(vertices)) {
      add_slip_by_rule<1>(s, cell, law, normal, force_point, centre);
    } else {
      add_slip_by_rule<4>(s, cell, law, normal, force_point, centre);
    }
  }
  return s;
}

FullSlip face_full_slip_by_rule(std::span<const ClosureCell> cells, const NormalLaw& law,
                                const Eigen::Vector3d& normal, const Eigen::Vector3d& force_point,
                                const SlipCentre& centre) {
  FullSlip s;
  for (const ClosureCell& cell : cells)
    add_slip_by_rule<4>(s, cell, law, normal, force_point, centre);
  return s;
}

}  // namespace blockdem
