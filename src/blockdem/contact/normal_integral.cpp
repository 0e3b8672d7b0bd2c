// Exact integrals of the normal laws over triangles and convex polygons with linear closure, via
// clipping at zero closure and divided differences (Hermite-Genocchi) for the exponential law.
#include "blockdem/contact/normal_integral.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "blockdem/contact/overloaded.hpp"

namespace blockdem {
namespace {

/// 1 / n! for small n.
double inverse_factorial(int n) {
  double value = 1.0;
  for (int k = 2; k <= n; ++k) value /= k;
  return value;
}

/// Divided difference exp[x_0, ..., x_n] of ascending nodes (repeats allowed, n <= 3), minus
/// 1/n! if `remainder`: that is the divided difference of exp(x) - sum_{k<=n} x^k / k!, which
/// stays accurate when the nodes are near zero.
/// Close nodes (spread <= 1): Taylor series about their mean c,
///   exp[x_0..x_n] = e^c sum_k h_k(x - c) / (n + k)!,
/// with h_k the complete homogeneous symmetric polynomials (h_0 = 1, h_1 = 0 about the mean);
/// terms fall like 1/(n! k!), so 24 terms reach rounding. Spread > 1: the recursion
/// f[x_0..x_n] = (f[x_1..x_n] - f[x_0..x_n-1]) / (x_n - x_0), which then loses at most a few
/// bits (the larger term dominates the difference).
double divided_difference_exp(const double* x, int count, bool remainder) {
  const int n = count - 1;
  if (n == 0) return remainder ? std::expm1(x[0]) : std::exp(x[0]);
  const double spread = x[n] - x[0];
  if (spread <= 1.0) {
    constexpr int kTerms = 24;
    double c = 0.0;
    for (int i = 0; i < count; ++i) c += x[i];
    c /= count;
    std::array<double, kTerms + 1> h{};
    h[0] = 1.0;
    for (int i = 0; i < count; ++i) {
      const double d = x[i] - c;
      for (int k = 1; k <= kTerms; ++k) h[k] += d * h[k - 1];
    }
    double weight = inverse_factorial(n);
    const double leading = weight;
    double tail = 0.0;
    for (int k = 1; k <= kTerms; ++k) {
      weight /= (n + k);
      tail += h[k] * weight;
    }
    return remainder ? std::expm1(c) * leading + std::exp(c) * tail
                     : std::exp(c) * (leading + tail);
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

/// Mean stress and barycentric-weighted means over a triangle whose vertex closures y are all >= 0.
/// The weights use the identities (1/A) int f(g) dA = 2 F[y0, y1, y2] with F'' = f and
/// (1/A) int lambda_j f(g) dA = 2 G[y_j, y_j, y_k, y_l] with G''' = f (Hermite-Genocchi).
void compressed_triangle_moments(const NormalLaw& law, const Eigen::Vector3d& y, double& mean,
                                 Eigen::Vector3d& weights) {
  std::visit(
      Overloaded{
          [&](const LinearNormal& lin) {
            // sigma = k g is linear: mean k g_bar; (1/A) int lambda_j lambda_i dA =
            // (1 + delta_ij) / 12.
            const double sum = y.sum();
            mean = lin.stiffness * sum / 3.0;
            for (int j = 0; j < 3; ++j) weights[j] = lin.stiffness * (sum + y[j]) / 12.0;
          },
          [&](const ExponentialNormal& e) {
            // sigma = a [exp(b g) - 1]; in x = b g the differences of exp(x) - 1 - ... carry the
            // law.
            const Eigen::Vector3d x = e.b * y;
            mean = 2.0 * e.a * exp_remainder_difference(std::array<double, 3>{x[0], x[1], x[2]});
            for (int j = 0; j < 3; ++j) {
              const int k = (j + 1) % 3, l = (j + 2) % 3;
              weights[j] = 2.0 * e.a *
                           exp_remainder_difference(std::array<double, 4>{x[j], x[j], x[k], x[l]});
            }
          },
      },
      law);
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
