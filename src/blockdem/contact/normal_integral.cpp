// Exact integrals of the normal laws over triangles and convex polygons with linear closure, via
// clipping at zero closure and divided differences (Hermite-Genocchi) for the exponential law.
#include "blockdem/contact/normal_integral.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <variant>

#include "blockdem/numerics/number_text.hpp"

namespace blockdem {
namespace {

constexpr int kMaxTerms = 24;  ///< 1/24! ~ 1.6e-24: enough for any spread <= 1

/// 1/m! for m <= 3 + kMaxTerms, each the previous one divided by m (so the series below use the
/// same values as dividing term by term, without a chain of divisions at run time).
constexpr std::array<double, kMaxTerms + 4> kInverseFactorial = [] {
  std::array<double, kMaxTerms + 4> t{};
  t[0] = 1.0;
  for (int m = 1; m < kMaxTerms + 4; ++m) t[m] = t[m - 1] / m;
  return t;
}();

/// 1/k for k <= kMaxTerms (entry 0 unused).
constexpr std::array<double, kMaxTerms + 1> kInverse = [] {
  std::array<double, kMaxTerms + 1> t{};
  for (int k = 1; k <= kMaxTerms; ++k) t[k] = 1.0 / k;
  return t;
}();
constexpr double kEulerE = 2.718281828459045;
constexpr double kRoundOff = 0x1p-53;

/// Number of Taylor terms k = 1..K after which the rest of the series is below round-off:
/// about a centre c with every |x_i - c| <= r <= 1, the degree-k term of a divided difference of
/// order n is at most r^k / (n! k!) in magnitude (h_k has C(n+k, n) monomials), so the terms
/// after K sum to at most e r^(K+1) / (n! (K+1)!). `floor` is a lower bound of the divided
/// difference being summed, times n! / e^c.
int terms_needed(double r, double floor) {
  const double tolerance = kRoundOff * floor / kEulerE;
  double bound = 1.0;  // r^k / k!
  for (int k = 1; k <= kMaxTerms; ++k) {
    bound *= r * kInverse[k];
    if (bound <= tolerance) return k - 1;
  }
  return kMaxTerms;
}

/// The four remainder differences of a compressed triangle whose nodes x_i >= 0 lie within 1 of
/// each other, from one Taylor series about c = mean(x): r3 = E[x_0, x_1, x_2] and
/// r4_j = E[x_j, x_j, x_k, x_l], E[x_0..x_n] = exp[x_0..x_n] - 1/n! the divided difference of
/// exp(x) - sum_{k<=n} x^k / k!, which stays accurate when the nodes are near zero:
///   E[x_0..x_n] = expm1(c) / n! + e^c sum_{k>=1} h_k(x - c) / (n + k)!,
/// h_k the complete homogeneous symmetric polynomials (h_1 = 0 about the mean). With
/// d_i = x_i - c, the 4-node h_k(d_j, d_0, d_1, d_2) = h_k(d_0, d_1, d_2) + d_j h_(k-1)(d_j, d_0,
/// d_1, d_2), so the four series share the 3-node h_k, exp(c) and expm1(c).
void close_node_remainders(const Eigen::Vector3d& x, double& r3, Eigen::Vector3d& r4) {
  const double c = (x[0] + x[1] + x[2]) / 3.0;
  const Eigen::Vector3d d = x.array() - c;
  const double r = d.cwiseAbs().maxCoeff();
  const double exp_c = std::exp(c), expm1_c = std::expm1(c);
  // Each remainder is at least the mean of its nodes (>= 3c/4) and at least expm1(min x), in
  // units of 1/n!: by Hermite-Genocchi it is the simplex mean of e^t - 1 >= t, over 1/n!.
  const double floor = std::max(0.75 * c, std::expm1(x.minCoeff())) / exp_c;
  const int terms = floor > 0.0 ? terms_needed(r, floor) : kMaxTerms;
  // h_k over the first one, two, three nodes (prefix), and with d_j repeated (extended).
  Eigen::Vector3d prefix(1.0, 1.0, 1.0), extended(1.0, 1.0, 1.0);
  double tail3 = 0.0;
  Eigen::Vector3d tail4 = Eigen::Vector3d::Zero();
  for (int k = 1; k <= terms; ++k) {
    prefix[0] = d[0] * prefix[0];
    prefix[1] = prefix[0] + d[1] * prefix[1];
    prefix[2] = prefix[1] + d[2] * prefix[2];
    extended = (prefix[2] + d.array() * extended.array()).matrix();
    tail3 += prefix[2] * kInverseFactorial[2 + k];
    tail4 += extended * kInverseFactorial[3 + k];
  }
  r3 = expm1_c * 0.5 + exp_c * tail3;
  r4 = (expm1_c / 6.0 + exp_c * tail4.array()).matrix();
}

/// exp[x_0, ..., x_n] for ascending nodes (repeats allowed) with e_i = exp(x_i) given: the
/// recursion f[x_0..x_n] = (f[x_1..x_n] - f[x_0..x_n-1]) / (x_n - x_0) while the spread exceeds 1
/// (the larger term dominates: at most a few bits lost), and below that the Taylor series about
/// the lowest node, exp[x] = e^{x_0} sum_k h_k(x - x_0) / (n + k)!, whose terms are all positive
/// (x_i - x_0 >= 0) and are summed until the rest is below round-off (terms_needed with a floor
/// of 1: the sum is at least its leading term 1/n!). No exp is evaluated: the triangle's three
/// exponentials serve all its divided differences.
double divided_difference_from_exps(const double* x, const double* e, int count) {
  const int n = count - 1;
  if (n == 0) return e[0];
  const double spread = x[n] - x[0];
  if (spread > 1.0) {
    return (divided_difference_from_exps(x + 1, e + 1, n) - divided_difference_from_exps(x, e, n)) /
           spread;
  }
  const int terms = terms_needed(spread, 1.0);
  std::array<double, kMaxTerms + 1> h{};
  h[0] = 1.0;
  for (int i = 1; i < count; ++i) {
    const double d = x[i] - x[0];
    for (int k = 1; k <= terms; ++k) h[k] += d * h[k - 1];
  }
  double sum = kInverseFactorial[n];
  for (int k = 1; k <= terms; ++k) {
    sum += h[k] * kInverseFactorial[n + k];
  }
  return e[0] * sum;
}

/// The four remainder differences of a compressed triangle (as in close_node_remainders) when its
/// nodes spread over more than 1: exp(x_i) once per node, then the sorted node sets
/// {x_0, x_1, x_2} and {x_j, x_j, x_k, x_l} through divided_difference_from_exps.
void wide_node_remainders(const Eigen::Vector3d& x, double& r3, Eigen::Vector3d& r4) {
  // Nodes in ascending order, with their exponentials and original indices.
  std::array<int, 3> order{0, 1, 2};
  std::sort(order.begin(), order.end(), [&](int p, int q) { return x[p] < x[q]; });
  std::array<double, 3> xs{}, es{};
  for (int i = 0; i < 3; ++i) {
    xs[i] = x[order[i]];
    es[i] = std::exp(xs[i]);
  }
  r3 = divided_difference_from_exps(xs.data(), es.data(), 3) - 0.5;
  for (int i = 0; i < 3; ++i) {
    // The sorted set with node i repeated.
    std::array<double, 4> x4{}, e4{};
    for (int m = 0, p = 0; m < 3; ++m) {
      x4[p] = xs[m];
      e4[p++] = es[m];
      if (m == i) {
        x4[p] = xs[m];
        e4[p++] = es[m];
      }
    }
    r4[order[i]] = divided_difference_from_exps(x4.data(), e4.data(), 4) - 1.0 / 6.0;
  }
}

/// Mean stress and barycentric-weighted means over a triangle whose vertex closures y are all >= 0.
/// The weights use the identities (1/A) int f(g) dA = 2 F[y0, y1, y2] with F'' = f and
/// (1/A) int lambda_j f(g) dA = 2 G[y_j, y_j, y_k, y_l] with G''' = f (Hermite-Genocchi).
/// One overload per law: the polygon's loop below is compiled once per law, so the law is
/// dispatched once per polygon, not once per fan triangle.
void compressed_triangle_moments(const LinearNormal& lin, const Eigen::Vector3d& y, double& mean,
                                 Eigen::Vector3d& weights) {
  // sigma = k g is linear: mean k g_bar; (1/A) int lambda_j lambda_i dA = (1 + delta_ij) / 12.
  const double sum = y.sum();
  mean = lin.stiffness * sum / 3.0;
  for (int j = 0; j < 3; ++j) weights[j] = lin.stiffness * (sum + y[j]) / 12.0;
}

void compressed_triangle_moments(const ExponentialNormal& e, const Eigen::Vector3d& y, double& mean,
                                 Eigen::Vector3d& weights) {
  // sigma = a [exp(b g) - 1]; in x = b g the differences of exp(x) - 1 - ... carry the law.
  // Close nodes: one series; nodes spread more than 1: the three exponentials.
  const Eigen::Vector3d x = e.b * y;
  double r3 = 0.0;
  Eigen::Vector3d r4;
  if (x.maxCoeff() - x.minCoeff() <= 1.0) {
    close_node_remainders(x, r3, r4);
  } else {
    wide_node_remainders(x, r3, r4);
  }
  mean = 2.0 * e.a * r3;
  weights = 2.0 * e.a * r4;
}

[[noreturn, gnu::cold, gnu::noinline]] void throw_not_finite(const char* what, double value) {
  throw std::invalid_argument(std::string("integrate_normal_stress: ") + what +
                              " must be finite, got " + number_text(value));
}

// A test inlined where it is made (once per closure and coordinate); the message is built out of
// line.
inline void require_finite(const char* what, double value) {
  if (!std::isfinite(value)) throw_not_finite(what, value);
}

template <class Law>
TriangleStressMoments partly_open_triangle_moments(const Law& law, const Eigen::Vector3d& closures);

// integrate_normal_stress_over_triangle for one law. Inlined into the polygon's loop: the
// compressed triangle (the usual case) is a few dozen operations; a triangle that is partly
// open is clipped out of line.
template <class Law>
[[gnu::always_inline]] inline TriangleStressMoments triangle_moments(
    const Law& law, const Eigen::Vector3d& closures) {
  for (int i = 0; i < 3; ++i) require_finite("a vertex closure", closures[i]);
  TriangleStressMoments result;
  if (closures.maxCoeff() <= 0.0) return result;
  if (closures.minCoeff() >= 0.0) {
    // Compressed throughout (the usual case): the clip below would keep the three vertices and
    // the fan one triangle of fraction exactly 1, so the same products and sums are formed
    // directly, with the same values.
    double mean = 0.0;
    Eigen::Vector3d weights;
    compressed_triangle_moments(law, closures, mean, weights);
    const double fraction = 1.0;
    result.mean_stress += fraction * mean;
    result.vertex_weights +=
        fraction * (weights[0] * Eigen::Vector3d::Unit(0) + weights[1] * Eigen::Vector3d::Unit(1) +
                    weights[2] * Eigen::Vector3d::Unit(2));
    result.compressed_fraction += fraction;
    return result;
  }
  return partly_open_triangle_moments(law, closures);
}

// A triangle with closures of both signs: the part where g > 0.
template <class Law>
TriangleStressMoments partly_open_triangle_moments(const Law& law,
                                                   const Eigen::Vector3d& closures) {
  TriangleStressMoments result;
  // Clip the triangle at g = 0 in barycentric coordinates (Sutherland-Hodgman on one line):
  // at most four vertices, each with its barycentric point and closure (exactly 0 on the cut).
  std::array<Eigen::Vector3d, 4> points;
  std::array<double, 4> values{};
  int count = 0;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const double gi = closures[i], gj = closures[j];
    if (gi >= 0.0) {
      points[count] = Eigen::Vector3d::Unit(i);
      values[count++] = gi;
    }
    if ((gi > 0.0 && gj < 0.0) || (gi < 0.0 && gj > 0.0)) {
      const double t = gi / (gi - gj);
      points[count] = (1.0 - t) * Eigen::Vector3d::Unit(i) + t * Eigen::Vector3d::Unit(j);
      values[count++] = 0.0;
    }
  }
  // Fan the clipped polygon; a sub-triangle's area fraction is |det| of its (lambda_1, lambda_2)
  // edge vectors, the reference triangle having area 1/2 in those coordinates.
  for (int k = 1; k + 1 < count; ++k) {
    const Eigen::Vector3d e1 = points[k] - points[0];
    const Eigen::Vector3d e2 = points[k + 1] - points[0];
    const double fraction = std::abs(e1[1] * e2[2] - e1[2] * e2[1]);
    if (fraction == 0.0) continue;
    double mean = 0.0;
    Eigen::Vector3d weights;
    compressed_triangle_moments(law, Eigen::Vector3d(values[0], values[k], values[k + 1]), mean,
                                weights);
    result.mean_stress += fraction * mean;
    result.vertex_weights +=
        fraction * (weights[0] * points[0] + weights[1] * points[k] + weights[2] * points[k + 1]);
    result.compressed_fraction += fraction;
  }
  return result;
}

}  // namespace

TriangleStressMoments integrate_normal_stress_over_triangle(const NormalLaw& law,
                                                            const Eigen::Vector3d& closures) {
  return std::visit([&](const auto& l) { return triangle_moments(l, closures); }, law);
}

PolygonStressResultant integrate_normal_stress_over_polygon(
    const NormalLaw& law, std::span<const Eigen::Vector3d> vertices,
    std::span<const double> closures) {
  if (vertices.size() < 3 || vertices.size() != closures.size()) {
    throw std::invalid_argument(
        "integrate_normal_stress_over_polygon: need at least 3 vertices and one closure per "
        "vertex, got " +
        std::to_string(vertices.size()) + " vertices and " + std::to_string(closures.size()) +
        " closures");
  }
  for (const auto& v : vertices) {
    for (int i = 0; i < 3; ++i) require_finite("a vertex coordinate", v[i]);
  }
  PolygonStressResultant result;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  double max_closure = closures[0];
  std::visit(
      [&](const auto& l) {
        for (std::size_t k = 1; k + 1 < vertices.size(); ++k) {
          const Eigen::Vector3d& a = vertices[0];
          const Eigen::Vector3d& b = vertices[k];
          const Eigen::Vector3d& c = vertices[k + 1];
          const double area = 0.5 * (b - a).cross(c - a).norm();
          const TriangleStressMoments m =
              triangle_moments(l, Eigen::Vector3d(closures[0], closures[k], closures[k + 1]));
          result.area += area;
          result.compressed_area += area * m.compressed_fraction;
          result.force += area * m.mean_stress;
          moment +=
              area * (m.vertex_weights[0] * a + m.vertex_weights[1] * b + m.vertex_weights[2] * c);
        }
      },
      law);
  for (const double g : closures) max_closure = std::max(max_closure, g);
  result.peak_stress = normal_stress(law, max_closure);
  if (result.force > 0.0) result.centre_of_pressure = Eigen::Vector3d(moment / result.force);
  return result;
}

double normal_energy_over_polygon(const NormalLaw& law, std::span<const Eigen::Vector3d> vertices,
                                  std::span<const double> closures, double force) {
  // ∫ g dA and ∫ g² dA over the fan of triangles from vertex 0.
  double first = 0.0, second = 0.0;
  for (std::size_t i = 1; i + 1 < vertices.size(); ++i) {
    const double area =
        0.5 * (vertices[i] - vertices[0]).cross(vertices[i + 1] - vertices[0]).norm();
    const double g0 = closures[0], g1 = closures[i], g2 = closures[i + 1];
    first += area * (g0 + g1 + g2) / 3.0;
    second += area * (g0 * g0 + g1 * g1 + g2 * g2 + g0 * g1 + g1 * g2 + g2 * g0) / 6.0;
  }
  return std::visit(
      [&](const auto& l) {
        using Law = std::decay_t<decltype(l)>;
        if constexpr (std::is_same_v<Law, LinearNormal>) {
          return 0.5 * l.stiffness * second;
        } else {
          return force / l.b - l.a * first;
        }
      },
      law);
}

}  // namespace blockdem
