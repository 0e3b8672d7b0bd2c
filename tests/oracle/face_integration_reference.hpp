// The face-integrated contact's first implementation, kept as the slow, obviously-correct oracle of
// the fast one: every (upper plane, lower plane) pair clipped against every plane, and the
// exponential law's divided differences by a fixed 24-term series.
#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

#include "blockdem/collision/face_contact.hpp"
#include "blockdem/contact/normal_integral.hpp"
#include "blockdem/geometry/halfspace.hpp"

namespace blockdem::oracle {

/// One cell of linear closure (see ClosureCell).
struct ReferenceCell {
  std::vector<Eigen::Vector3d> vertices;  ///< on the contact plane, in order (m)
  std::vector<double> closures;           ///< closure at each vertex, >= 0 (m)
};

struct ReferenceFaceGeometry {
  bool face_type = false;
  std::vector<ReferenceCell> cells;
};

/// Same contract as face_contact_geometry: one candidate cell per (upper, lower) plane pair, each
/// a square of half-side `extent` clipped against the pair's closure, every lateral plane and
/// every other upper and lower plane.
ReferenceFaceGeometry reference_face_contact_geometry(std::span<const Halfspace> planes_a,
                                                      std::span<const Halfspace> planes_b,
                                                      const Eigen::Vector3d& origin,
                                                      const Eigen::Vector3d& normal, double extent,
                                                      const FaceContactSettings& settings = {});

/// Same contract as integrate_normal_stress_over_triangle, with the exponential law's divided
/// differences by a fixed 24-term Taylor series about each node set's own mean.
TriangleStressMoments reference_stress_over_triangle(const NormalLaw& law,
                                                     const Eigen::Vector3d& closures);

/// Same contract as integrate_normal_stress_over_polygon (fan from vertex 0).
PolygonStressResultant reference_stress_over_polygon(const NormalLaw& law,
                                                     std::span<const Eigen::Vector3d> vertices,
                                                     std::span<const double> closures);

}  // namespace blockdem::oracle
