// The twisting resistance of a world contact over one step.
#include "blockdem/world/contact_twist.hpp"

#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "blockdem/collision/face_twist.hpp"
#include "blockdem/contact/twist_law.hpp"
#include "blockdem/geometry/polygon_moments.hpp"

namespace blockdem {

TwistGeometry face_twist_geometry(std::span<const ClosureCell> cells, const NormalLaw& law) {
  // The centroid of the cells: area-weighted centroids of each (exact, polygon_moments).
  double area = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  for (const ClosureCell& cell : cells) {
    const std::span<const Eigen::Vector3d> v(cell.vertices.data(), cell.vertices.size());
    if (v.empty()) continue;
    const PolygonMoments pm = polygon_moments(v, v[0]);
    area += pm.area;
    first += pm.area * pm.centroid;
  }
  TwistGeometry g;
  if (!(area > 0.0)) return g;
  const FaceTwistMoments m = face_twist_moments(cells, law, first / area);
  g.polar_moment = m.polar_moment;
  g.radial_normal_moment = m.radial_normal_moment;
  return g;
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
  return g;
}

void spin_shear_state(ShearState& state, const Eigen::Vector3d& normal, double angle) {
  if (angle == 0.0) return;
  const Eigen::AngleAxisd turn(angle, normal);
  state.force = turn * state.force;
  state.elastic_displacement = turn * state.elastic_displacement;
}

double advance_contact_twist(TwistState& twist, const ShearLaw& law, const ShearState& shear,
                             double normal_stress, const TwistGeometry& geometry, double spin) {
  const TwistLawTerms terms = twist_law_terms(law, shear, normal_stress);
  TwistIncrement inc;
  inc.spin = spin;
  inc.shear_stiffness = terms.shear_stiffness;
  inc.polar_moment = geometry.polar_moment;
  inc.radial_normal_moment = geometry.radial_normal_moment;
  inc.friction_coefficient = terms.friction_coefficient;
  return update_twist(twist, inc).stiffness;
}

}  // namespace blockdem
