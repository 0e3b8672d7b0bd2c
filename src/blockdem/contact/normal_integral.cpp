// Exact integrals of the normal laws over triangles and convex polygons with linear closure, via
// clipping at zero closure and divided differences (Hermite-Genocchi) for the exponential law.
#include "blockdem/contact/normal_integral.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace blockdem {
namespace {

/// 1 / n! for small n.
double inverse_factorial(int n) {
  double value = 1.0;
  for (int k = 2; k <= n; ++k) value /= k;
  return value;
}

constexpr int kMaxTerms = 24;  ///< 1/24! ~ 1.6e-24: enough for any spread <= 1
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
    bound *= r / k;
    if (bound <= tolerance) return k - 1;
  }
  return kMaxTerms;
}

/// Divided difference exp[x_0, ..., x_n] of ascending nodes (repeats allowed, n <= 3), minus
/// 1/n! if `remainder`: that is the divided difference of exp(x) - sum_{k<=n} x^k / k!, which
/// stays accurate when the nodes are near zero.
/// Close nodes (spread <= 1): Taylor series about their mean c,
///   exp[x_0..x_n] = e^c sum_k h_k(x - c) / (n + k)!,
/// with h_k the complete homogeneous symmetric polynomials (h_0 = 1, h_1 = 0 about the mean),
/// summed until the remaining terms are below round-off (terms_needed). Spread > 1: the recursion
/// f[x_0..x_n] = (f[x_1..x_n] - f[x_0..x_n-1]) / (x_n - x_0), which then loses at most a few
/// bits (the larger term dominates the difference).
double divided_difference_exp(const double* x, int count, bool remainder) {
  const int n = count - 1;
  if (n == 0) return remainder ? std::expm1(x[0]) : std::exp(x[0]);
  const double spread = x[n] - x[0];
  if (spread <= 1.0) {
    double c = 0.0;
    for (int i = 0; i < count; ++i) c += x[i];
    c /= count;
    const double r = std::max(c - x[0], x[n] - c);
    // Lower bounds (times n!): e^{x_0} for exp itself; for the remainder, the simplex mean of
    // e^t - 1 >= t, i.e. c, and e^{x_0} - 1 (Hermite-Genocchi).
    const double exp_c = std::exp(c);
    const double floor = remainder ? std::max(c, std::expm1(x[0])) / exp_c : std::exp(x[0] - c);
    const int terms = floor > 0.0 ? terms_needed(r, floor) : kMaxTerms;
    std::array<double, kMaxTerms + 1> h{};
    h[0] = 1.0;
    for (int i = 0; i < count; ++i) {
      const double d = x[i] - c;
      for (int k = 1; k <= terms; ++k) h[k] += d * h[k - 1];
    }
    double weight = inverse_factorial(n);
    const double leading = weight;
    double tail = 0.0;
    for (int k = 1; k <= terms; ++k) {
      weight /= (n + k);
      tail += h[k] * weight;
    }
    return remainder ? std::expm1(c) * leading + exp_c * tail : exp_c * (leading + tail);
  }
  const double value =
      (divided_difference_exp(x + 1, n, false) - divided_difference_exp(x, n, false)) / spread;
  return remainder ? value - inverse_factorial(n) : value;
}

/// divided_difference_exp(..., remainder = true) of unsorted nodes.
template <std::size_t N>
double exp_remainder_difference(std::array<double, N> nodes) {
  std::sort(nodes.begin(), nodes.end());
  return divided_difference_exp(nodes.data(), static_cast<int>(N), true);
}

/// The four remainder differences of a compressed triangle whose nodes x_i >= 0 lie within 1 of
/// each other, from one Taylor series about c = mean(x): r3 = E[x_0, x_1, x_2] and
/// r4_j = E[x_j, x_j, x_k, x_l], E the divided difference of exp(x) - 1 - ... (as above). With
/// d_i = x_i - c, the 4-node h_k(d_j, d_0, d_1, d_2) = h_k(d_0, d_1, d_2) + d_j h_(k-1)(d_j, d_0,
/// d_1, d_2), so the four series share the 3-node h_k, exp(c) and expm1(c).
void close_node_remainders(const Eigen::Vector3d& x, double& r3, Eigen::Vector3d& r4) {
  const double c = (x[0] + x[1] + x[2]) / 3.0;
  const Eigen::Vector3d d = x.array() - c;
  const double r = d.cwiseAbs().maxCoeff();
  const double exp_c = std::exp(c), expm1_c = std::expm1(c);
  // Each remainder is at least the mean of its nodes (>= 3c/4) and at least expm1(min x), in
  // units of 1/n! (see divided_difference_exp).
  const double floor = std::max(0.75 * c, std::expm1(x.minCoeff())) / exp_c;
  const int terms = floor > 0.0 ? terms_needed(r, floor) : kMaxTerms;
  // h_k over the first one, two, three nodes (prefix), and with d_j repeated (extended).
  Eigen::Vector3d prefix(1.0, 1.0, 1.0), extended(1.0, 1.0, 1.0);
  double weight3 = 0.5, weight4 = 1.0 / 6.0;  // 1/(n+k)! for n = 2, 3
  double tail3 = 0.0;
  Eigen::Vector3d tail4 = Eigen::Vector3d::Zero();
  for (int k = 1; k <= terms; ++k) {
    prefix[0] = d[0] * prefix[0];
    prefix[1] = prefix[0] + d[1] * prefix[1];
    prefix[2] = prefix[1] + d[2] * prefix[2];
    extended = (prefix[2] + d.array() * extended.array()).matrix();
    weight3 /= (2 + k);
    weight4 /= (3 + k);
    tail3 += prefix[2] * weight3;
    tail4 += extended * weight4;
  }
  r3 = expm1_c * 0.5 + exp_c * tail3;
  r4 = (expm1_c / 6.0 + exp_c * tail4.array()).matrix();
}

/// Mean stress and barycentric-weighted means over a triangle whose vertex closures y are all >= 0.
/// The weights use the identities (1/A) int f(g) dA = 2 F[y0, y1, y2] with F'' = f and
/// (1/A) int lambda_j f(g) dA = 2 G[y_j, y_j, y_k, y_l] with G''' = f (Hermite-Genocchi).
void compressed_triangle_moments(const NormalLaw& law, const Eigen::Vector3d& y, double& mean,
                                 Eigen::Vector3d& weights) {
  if (const auto* lin = std::get_if<LinearNormal>(&law)) {
    // sigma = k g is linear: mean k g_bar; (1/A) int lambda_j lambda_i dA = (1 + delta_ij) / 12.
    const double sum = y.sum();
    mean = lin->stiffness * sum / 3.0;
    for (int j = 0; j < 3; ++j) weights[j] = lin->stiffness * (sum + y[j]) / 12.0;
    return;
  }
  const auto& e = std::get<ExponentialNormal>(law);
  // sigma = a [exp(b g) - 1]; in x = b g the differences of exp(x) - 1 - ... carry the law.
  const Eigen::Vector3d x = e.b * y;
  if (x.maxCoeff() - x.minCoeff() <= 1.0) {
    double r3 = 0.0;
    Eigen::Vector3d r4;
    close_node_remainders(x, r3, r4);
    mean = 2.0 * e.a * r3;
    weights = 2.0 * e.a * r4;
    return;
  }
  mean = 2.0 * e.a * exp_remainder_difference(std::array<double, 3>{x[0], x[1], x[2]});
  for (int j = 0; j < 3; ++j) {
    const int k = (j + 1) % 3, l = (j + 2) % 3;
    weights[j] =
        2.0 * e.a * exp_remainder_difference(std::array<double, 4>{x[j], x[j], x[k], x[l]});
  }
}

void require_finite(const char* what, double value) {
  if (!std::isfinite(value)) {
    throw std::invalid_argument(std::string("integrate_normal_stress: ") + what +
                                " must be finite, got " + std::to_string(value));
  }
}

}  // namespace

TriangleStressMoments integrate_normal_stress_over_triangle(const NormalLaw& law,
                                                            const Eigen::Vector3d& closures) {
  for (int i = 0; i < 3; ++i) require_finite("a vertex closure", closures[i]);
  TriangleStressMoments result;
  if (closures.maxCoeff() <= 0.0) return result;

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
  for (std::size_t k = 1; k + 1 < vertices.size(); ++k) {
    const Eigen::Vector3d& a = vertices[0];
    const Eigen::Vector3d& b = vertices[k];
    const Eigen::Vector3d& c = vertices[k + 1];
    const double area = 0.5 * (b - a).cross(c - a).norm();
    const TriangleStressMoments m = integrate_normal_stress_over_triangle(
        law, Eigen::Vector3d(closures[0], closures[k], closures[k + 1]));
    result.area += area;
    result.compressed_area += area * m.compressed_fraction;
    result.force += area * m.mean_stress;
    moment += area * (m.vertex_weights[0] * a + m.vertex_weights[1] * b + m.vertex_weights[2] * c);
  }
  for (const double g : closures) max_closure = std::max(max_closure, g);
  result.peak_stress = normal_stress(law, max_closure);
  if (result.force > 0.0) result.centre_of_pressure = Eigen::Vector3d(moment / result.force);
  return result;
}

}  // namespace blockdem
