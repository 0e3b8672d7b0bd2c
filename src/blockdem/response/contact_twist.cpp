// The twisting resistance of a contact over one step.
#include "blockdem/response/contact_twist.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "blockdem/geometry/polygon_moments.hpp"
#include "blockdem/response/face_twist.hpp"

namespace blockdem {

TwistGeometry face_twist_geometry(std::span<const ClosureCell> cells, const Eigen::Vector3d& normal,
                                  double force, const Eigen::Vector3d& pressure_centre) {
  const Eigen::Vector3d& p = pressure_centre;  // inside the contact: no cancellation
  double area = 0.0, polar = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  for (const ClosureCell& cell : cells) {
    const auto& v = cell.vertices;
    const std::size_t m = v.size();
    if (m == 0) continue;
    double a = 0.0, j = 0.0;
    Eigen::Vector3d f = Eigen::Vector3d::Zero();
    // Each edge's end is the next edge's start: its offset and squared length carry over.
    Eigen::Vector3d u = v[0] - p;
    double uu = u.squaredNorm();
    for (std::size_t i = 0; i < m; ++i) {
      const Eigen::Vector3d w = v[i + 1 < m ? i + 1 : 0] - p;
      const double ww = w.squaredNorm();
      const double signed_area = 0.5 * u.cross(w).dot(normal);
      a += signed_area;
      f += signed_area * (u + w) / 3.0;
      j += signed_area * (uu + ww + u.dot(w)) / 6.0;
      u = w;
      uu = ww;
    }
    const double orientation = a < 0.0 ? -1.0 : 1.0;  // a cell's vertices may run either way
    area += orientation * a;
    first += orientation * f;
    polar += orientation * j;
  }
  TwistGeometry g;
  g.exact = false;
  if (!(area > 0.0)) return g;
  const Eigen::Vector3d offset = first / area;  // c - p
  g.centre = p + offset;
  g.polar_moment = std::max(0.0, polar - area * offset.squaredNorm());
  // The largest squared distance, then one square root: the square root is monotonic, so this
  // is the largest of the distances, bit for bit.
  double max_radius2 = 0.0;
  for (const ClosureCell& cell : cells)
    for (const auto& x : cell.vertices)
      max_radius2 = std::max(max_radius2, (x - g.centre).squaredNorm());
  g.max_radius = std::max(g.max_radius, std::sqrt(max_radius2));
  g.radial_normal_moment = force * offset.norm();
  return g;
}

double face_radial_normal_bound(std::span<const ClosureCell> cells, const NormalLaw& law,
                                const TwistGeometry& geometry) {
  if (!(geometry.max_radius > 0.0)) return geometry.radial_normal_moment;
  const ClosurePolarMoments m = face_closure_polar_moments(cells, geometry.centre);
  if (!(m.polar_moment > 0.0)) return geometry.radial_normal_moment;
  // Jensen: σ_n is convex in g on g >= 0 (linear or exponential), so under the weight r² dA / J
  // ∫ σ_n(g) r² dA >= J σ_n(∫ g r² dA / J); and r <= r_max gives ∫ σ_n r dA >= that / r_max.
  const double mean_closure = m.closure_polar_moment / m.polar_moment;
  const double bound = normal_stress(law, mean_closure) * m.polar_moment / geometry.max_radius;
  return std::max(geometry.radial_normal_moment, bound);
}

double face_pressure_radial_bound(std::span<const ClosureCell> cells, const NormalLaw& law,
                                  const TwistGeometry& geometry, double force,
                                  const Eigen::Vector3d& pressure_centre) {
  const double d = (geometry.centre - pressure_centre).norm();
  // About c, less the offset: r_p >= r_c - d (the bound this one sharpens).
  const double about_centroid = geometry.radial_normal_moment - force * d;
  if (!(geometry.max_radius > 0.0)) return about_centroid;
  const ClosurePolarMoments m = face_closure_polar_moments(cells, geometry.centre);
  if (!(m.polar_moment > 0.0)) return about_centroid;
  // Directly about x_p: ∫ σ_n r_p dA >= ∫ σ_n r_p² dA / r_max,p, and with ∫ σ_n (y - c) dA =
  // F_n (x_p - c), ∫ σ_n r_p² dA = ∫ σ_n r_c² dA - F_n d² >= J σ_n(ḡ) - F_n d² (Jensen, as in
  // face_radial_normal_bound). r_max,p <= r_max + d: no vertex loop needed.
  const double mean_closure = m.closure_polar_moment / m.polar_moment;
  const double second = normal_stress(law, mean_closure) * m.polar_moment;
  const double about_pressure = (second - force * d * d) / (geometry.max_radius + d);
  const double about_centre =
      std::max(geometry.radial_normal_moment, second / geometry.max_radius) - force * d;
  return std::max(about_pressure, about_centre);
}

double face_radial_normal_moment(std::span<const ClosureCell> cells, const NormalLaw& law,
                                 const Eigen::Vector3d& centre) {
  // ∫ σ_n r dA >= 0 (σ_n >= 0, r >= 0), but the cells' closed forms cancel terms: a contact
  // barely closed, metres from the origin, can sum to a little below zero, which is round-off
  // for zero (update_twist refuses a negative value: it stopped a 1e5-block pile's settling in
  // mode face_integrated).
  return std::max(0.0, face_twist_moments(cells, law, centre).radial_normal_moment);
}

TwistGeometry slice_twist_geometry(const SlicePolygon& slice, double normal_stress) {
  const std::size_t n = slice.vertices.size();
  std::array<Eigen::Vector3d, SliceVertices::kInline> buffer;
  std::vector<Eigen::Vector3d> heap;
  Eigen::Vector3d* v = buffer.data();
  if (n > SliceVertices::kInline) {
    heap.resize(n);
    v = heap.data();
  }
  for (std::size_t i = 0; i < n; ++i) v[i] = slice.to_world(slice.vertices[i]);
  const PolygonMoments pm = polygon_moments_about_centroid(std::span<const Eigen::Vector3d>(v, n));
  TwistGeometry g;
  g.polar_moment = pm.polar_moment;
  g.radial_normal_moment = normal_stress > 0.0 ? normal_stress * pm.radial_moment : 0.0;
  g.exact = true;
  g.centre = pm.centroid;
  return g;
}

double step_contact_twist(TwistState& twist, const TwistLawTerms& terms,
                          const TwistGeometry& geometry, double spin) {
  TwistIncrement inc;
  inc.spin = spin;
  inc.shear_stiffness = terms.shear_stiffness;
  inc.polar_moment = geometry.polar_moment;
  inc.radial_normal_moment = geometry.radial_normal_moment;
  inc.friction_coefficient = terms.friction_coefficient;
  return update_twist(twist, inc).stiffness;
}

}  // namespace blockdem
