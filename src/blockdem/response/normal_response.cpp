// A contact's normal response over one step: the face contact's integrated normal force, and the
// points where the shear spring acts.
#include "blockdem/response/normal_response.hpp"

#include <algorithm>

#include "blockdem/contact/normal_integral.hpp"
#include "blockdem/geometry/polygon_moments.hpp"

namespace blockdem {

std::optional<NormalResponse> face_normal_response(const NormalLaw& law,
                                                   std::span<const ClosureCell> cells) {
  double force = 0.0, compressed = 0.0, peak = 0.0, closure = 0.0, energy = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (const auto& cell : cells) {
    const PolygonStressResultant r =
        integrate_normal_stress_over_polygon(law, cell.vertices, cell.closures);
    force += r.force;
    compressed += r.compressed_area;
    peak = std::max(peak, r.peak_stress);
    if (r.centre_of_pressure) moment += r.force * *r.centre_of_pressure;
    energy += normal_energy_over_polygon(law, cell.vertices, cell.closures, r.force);
    for (double gc : cell.closures) closure = std::max(closure, gc);
  }
  // Touching, but no closure anywhere to integrate.
  if (!(force > 0.0)) return std::nullopt;
  NormalResponse r;
  r.integrated = true;
  r.force = force;
  r.stress = force / compressed;
  r.force_point = moment / force;
  r.compressed_area = compressed;
  r.peak_stress = peak;
  r.peak_closure = closure;
  r.energy = energy;
  r.shear_point = compressed_area_centroid(cells, r.force_point);
  r.stiffness = normal_tangent_stiffness(law, r.peak_closure) * r.compressed_area;
  return r;
}

Eigen::Vector3d compressed_area_centroid(std::span<const ClosureCell> cells,
                                         const Eigen::Vector3d& fallback) {
  double area = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  for (const ClosureCell& cell : cells) {
    const PolygonMoments pm = polygon_area_centroid(
        std::span<const Eigen::Vector3d>(cell.vertices.data(), cell.vertices.size()));
    area += pm.area;
    first += pm.area * pm.centroid;
  }
  return area > 0.0 ? Eigen::Vector3d(first / area) : fallback;
}

Eigen::Vector3d slice_centroid(const SlicePolygon& slice, const Eigen::Vector3d& fallback) {
  // In the slice's plane coordinates, about x_c: one point to carry to the world.
  if (!(slice.area() > 0.0)) return fallback;
  return slice.to_world(slice.centroid_2d());
}

}  // namespace blockdem
