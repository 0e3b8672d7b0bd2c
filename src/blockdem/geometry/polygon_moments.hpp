// Exact area moments of a planar convex polygon about a point of its plane: area, centroid, polar
// moment J = ∫ r² dA and radial moment ∫ r dA (the twisting resistance of a contact face), the
// second moment tensor (a linear field's resultant over the polygon), and the clip of a polygon by
// a half-space.
#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

#include "blockdem/geometry/halfspace.hpp"

namespace blockdem {

struct PolygonMoments {
  double area = 0.0;                                   ///< A (m^2)
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< (m)
  double polar_moment = 0.0;   ///< J = ∫ |y - p|² dA about the given point p (m^4)
  double radial_moment = 0.0;  ///< ∫ |y - p| dA about the given point p (m^3)
};

/// Moments of a planar convex polygon (vertices in order, m) about a point `pole` of its plane,
/// by a fan of triangles (pole, v_i, v_i+1) in polar coordinates about the pole: a triangle whose
/// far edge lies at distance h from the pole and spans angles ψ1..ψ2 from the foot of the
/// perpendicular has ∫ r² dA = (h⁴/4) ∫ sec⁴ψ dψ and ∫ r dA = (h³/3) ∫ sec³ψ dψ, both in closed
/// form; each triangle is signed by its orientation, so a pole outside the polygon works too.
/// Fewer than three vertices, or a polygon whose area is zero within round-off (its signed fan
/// not positive), give zero moments; J and ∫ r dA are never negative.
PolygonMoments polygon_moments(std::span<const Eigen::Vector3d> vertices,
                               const Eigen::Vector3d& pole);

/// Moments about the polygon's own centroid.
PolygonMoments polygon_moments_about_centroid(std::span<const Eigen::Vector3d> vertices);

/// The area and centroid of polygon_moments_about_centroid (the same values, bit for bit),
/// without the polar and radial moments (left zero): no transcendental function per edge.
PolygonMoments polygon_area_centroid(std::span<const Eigen::Vector3d> vertices);

/// The second moment S = ∫ (x - c)(x - c)ᵀ dA of a planar convex polygon (vertices in order about
/// its unit normal n or against it, m) about a point c of its plane (m^4), exact, by a fan of
/// triangles (c, v_i, v_i+1): a triangle with vertices 0, p, q about c has
/// (A/12)(p pᵀ + q qᵀ + (p + q)(p + q)ᵀ). With c the centroid, a field linear over the polygon,
/// f(x) = f(c) + ∇f · (x - c), has ∫ f dA = A f(c) and ∫ (x - c) f dA = S ∇f.
Eigen::Matrix3d polygon_second_moment(std::span<const Eigen::Vector3d> vertices,
                                      const Eigen::Vector3d& c, const Eigen::Vector3d& n);

/// The part of a convex polygon (vertices in order, m) inside the half-space h (h.normal · x <=
/// h.offset), in the same order (Sutherland & Hodgman 1974, one clip plane); empty when no part
/// of it is inside, the polygon itself when all of it is.
std::vector<Eigen::Vector3d> clip_polygon(std::span<const Eigen::Vector3d> vertices,
                                          const Halfspace& h);

}  // namespace blockdem
