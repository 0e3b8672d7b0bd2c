// An in-situ stress field and what it puts on a joint face: the traction σ·n integrated over the
// face polygon, and the closure field a normal law needs to carry it (the prestress of a joint
// contact at set-up).
#pragma once

#include <Eigen/Core>
#include <span>
#include <string>

#include "blockdem/contact/normal_laws.hpp"

namespace blockdem {

/// A stress field linear in depth: σ(x) = stress + gradient_z (x_z - reference_z), world axes
/// (x east, y north, z up), compression positive (Pa). It is in equilibrium with gravity g = -g e_z
/// in rock of density ρ when its divergence balances the weight: ∂σ_iz/∂z = -ρ g δ_iz, i.e.
/// gradient_z(z, z) = -ρ g and gradient_z(x, z) = gradient_z(y, z) = 0.
struct StressField {
  Eigen::Matrix3d stress = Eigen::Matrix3d::Zero();      ///< σ at z = reference_z (Pa)
  double reference_z = 0.0;                              ///< (m)
  Eigen::Matrix3d gradient_z = Eigen::Matrix3d::Zero();  ///< dσ/dz (Pa/m)

  /// σ(x) (Pa).
  Eigen::Matrix3d at(const Eigen::Vector3d& x) const {
    return stress + gradient_z * (x.z() - reference_z);
  }
  /// The field moved with the scene: a point x of the file is x - origin in the simulation.
  StressField shifted_by(const Eigen::Vector3d& origin) const {
    StressField f = *this;
    f.reference_z -= origin.z();
    return f;
  }
  /// An empty string when both tensors are symmetric and finite, else what is wrong.
  std::string problem() const;
};

/// The common shorthand of an in-situ field: vertical stress σ_v = ρ g (ground_z - z), the weight
/// of the rock above, and horizontal stresses k_x σ_v and k_y σ_v along horizontal axes x' and y'
/// turned clockwise (seen from above) by `trend_deg` from x and y: trend 0 puts k_x along x
/// (east), trend 90 along -y (south-north), so that x' has the azimuth 90 + trend_deg.
StressField stress_from_overburden(double ground_z, double density, double gravity, double k_x,
                                   double k_y, double trend_deg);

/// The field's traction on a planar convex face, exact for the linear field. The face has unit
/// normal n from side A to side B; the traction on B is σ n (compression positive: a compressive
/// σ_n pushes B along +n).
struct FaceTraction {
  double area = 0.0;                                   ///< (m^2)
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< x̄ (m)
  Eigen::Vector3d force = Eigen::Vector3d::Zero();     ///< ∫ σ n dA on B (N)
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();    ///< ∫ (x - x̄) × σ n dA on B (N m)
  /// σ_n(x) = n·σ(x)n = normal_stress + normal_stress_gradient · (x - x̄) over the face (Pa).
  double normal_stress = 0.0;
  Eigen::Vector3d normal_stress_gradient = Eigen::Vector3d::Zero();  ///< in the face (Pa/m)
  double least_normal_stress = 0.0;  ///< the smallest σ_n over the face (at a vertex) (Pa)
  Eigen::Vector3d least_point = Eigen::Vector3d::Zero();  ///< where it is (m)

  /// The shear force on B, ∫ (σ n - σ_n n) dA (N).
  Eigen::Vector3d shear_force(const Eigen::Vector3d& n) const { return force - n.dot(force) * n; }
  /// The twisting moment on B about n and x̄ (N m): the shear traction's; the normal traction's
  /// moment lies in the face.
  double twisting_moment(const Eigen::Vector3d& n) const { return n.dot(moment); }
};

/// The traction of `field` over the polygon `vertices` (in order, m) with unit normal n (A to B).
/// Throws std::invalid_argument for fewer than 3 vertices or no area.
FaceTraction face_traction(const StressField& field, std::span<const Eigen::Vector3d> vertices,
                           const Eigen::Vector3d& n);

/// A closure field linear over a face, δ(x) = value + gradient · (x - point) (m).
struct LinearClosure {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();     ///< (m)
  double value = 0.0;                                  ///< δ at point (m)
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();  ///< in the face (-)

  double at(const Eigen::Vector3d& x) const { return value + gradient.dot(x - point); }
};

/// The linear closure over the face (polygon `vertices`, unit normal n) under which `law` carries
/// the normal part of `traction`: the same normal force and the same moment in the face, so the
/// face's resultant is the field's exactly. For the linear law σ_n = k_n δ this is δ = σ_n(x) / k_n
/// pointwise; for a nonlinear law, whose pointwise inverse is not linear where σ_n varies, the
/// three coefficients are solved (Newton) for the force and both moments, to round-off. Throws
/// std::invalid_argument when σ_n is not positive over the whole face or no solution is found.
LinearClosure closure_for_traction(const NormalLaw& law, std::span<const Eigen::Vector3d> vertices,
                                   const Eigen::Vector3d& n, const FaceTraction& traction);

/// The closure u_n at which `law` carries σ_n (m): the law's inverse (σ_n > 0).
double closure_for_stress(const NormalLaw& law, double normal_stress);

}  // namespace blockdem
