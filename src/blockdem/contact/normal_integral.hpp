// Exact integrals of a normal joint law over a triangle or convex polygon on which the closure
// varies linearly: resultant force, centre of pressure, compressed area, peak stress. These are the
// kernels of the face-integrated contact mode.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>

#include "blockdem/contact/normal_laws.hpp"

namespace blockdem {

/// Area averages over a triangle with barycentric coordinates lambda_i and closure
/// g = sum_i lambda_i g_i (the parts with g <= 0 carry no stress).
struct TriangleStressMoments {
  double mean_stress = 0.0;  ///< (1/A) integral sigma_n(g) dA (Pa)
  /// (1/A) integral lambda_i sigma_n(g) dA (Pa); they sum to mean_stress, and the centre of
  /// pressure is sum_i vertex_weights[i] x_i / mean_stress.
  Eigen::Vector3d vertex_weights = Eigen::Vector3d::Zero();
  double compressed_fraction = 0.0;  ///< fraction of the area where g > 0 (-)
};

/// Integrates the law over a triangle with vertex closures `closures` (m). Exact up to rounding
/// for both laws: the triangle is clipped at g = 0, the linear law integrates in closed form, and
/// the exponential law through divided differences of exp (Hermite-Genocchi formula), evaluated
/// by a Taylor series where the closures are close and by recursion where they are not, so that
/// no cancellation occurs.
TriangleStressMoments integrate_normal_stress_over_triangle(const NormalLaw& law,
                                                            const Eigen::Vector3d& closures);

/// The resultant of the normal stress over a contact polygon.
struct PolygonStressResultant {
  double force = 0.0;            ///< integral sigma_n dA (N)
  double area = 0.0;             ///< polygon area (m^2)
  double compressed_area = 0.0;  ///< area where the closure is positive (m^2)
  double peak_stress = 0.0;      ///< sigma_n at the largest vertex closure (Pa)
  /// Point of application of the force (m); empty when the force is zero.
  std::optional<Eigen::Vector3d> centre_of_pressure;
};

/// Integrates the law over a planar convex polygon (vertices in order, m) with closures at the
/// vertices (m) of a field that is linear over the polygon. The polygon is split into a fan of
/// triangles from vertex 0. Throws std::invalid_argument for fewer than 3 vertices, a size
/// mismatch or non-finite input.
PolygonStressResultant integrate_normal_stress_over_polygon(
    const NormalLaw& law, std::span<const Eigen::Vector3d> vertices,
    std::span<const double> closures);

/// The energy stored in the joint over the same polygon, the integral of the strain-energy
/// density e(g) = ∫_0^g sigma_n(s) ds (J): (k_n / 2) ∫ g² dA for the linear law, exact over each
/// triangle of the fan (A/6 (g0² + g1² + g2² + g0 g1 + g1 g2 + g2 g0)); for the exponential law
/// e = sigma_n / b - a g, so ∫ e dA = F / b - a ∫ g dA with `force` F = ∫ sigma_n dA of the same
/// polygon (N). The closures must be >= 0 (a contact cell's).
double normal_energy_over_polygon(const NormalLaw& law, std::span<const Eigen::Vector3d> vertices,
                                  std::span<const double> closures, double force);

}  // namespace blockdem
