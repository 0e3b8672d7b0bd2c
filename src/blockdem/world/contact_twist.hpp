// The twisting resistance of a world contact over one step: the contact area's moments, the
// torsional spring (contact/twist.hpp) with the shear law's terms, and the spin of the stored
// shear force with the contact frame about the normal.
#pragma once

#include <Eigen/Core>
#include <span>

#include "blockdem/collision/face_contact.hpp"
#include "blockdem/collision/slice_polygon.hpp"
#include "blockdem/contact/normal_laws.hpp"
#include "blockdem/contact/shear_laws.hpp"
#include "blockdem/contact/twist.hpp"

namespace blockdem {

/// The area terms of the torsional spring, about the compressed area's centroid.
struct TwistGeometry {
  double polar_moment = 0.0;          ///< J = ∫ r² dA (m^4)
  double radial_normal_moment = 0.0;  ///< ∫ σ_n r dA (N m)
};

/// Face-integrated contact: J and ∫ σ_n(g) r dA over the cells of linear closure
/// (face_twist_moments), about the centroid of the cells.
TwistGeometry face_twist_geometry(std::span<const ClosureCell> cells, const NormalLaw& law);

/// Point contact (boon2012): J of the slice polygon about its centroid and σ_n ∫ r dA for the
/// uniform stress σ_n (Pa) the point contact assumes.
TwistGeometry slice_twist_geometry(const SlicePolygon& slice, double normal_stress);

/// Turns the stored shear force and elastic displacement about the unit normal n by `angle`
/// (rad, counter-clockwise about n): the contact frame's spin, the mean spin of the two blocks
/// ((ω_A + ω_B)/2 · n) dt. A rigid rotation of both blocks then carries the force with them.
void spin_shear_state(ShearState& state, const Eigen::Vector3d& normal, double angle);

/// One step of a contact's torsional spring (update_twist) with the terms of its shear law at
/// σ_n (twist_law_terms); `spin` is B's rotation relative to A about n (rad). Returns k_s J, the
/// spring (N m/rad), for the rotational stiffness of the time step.
double advance_contact_twist(TwistState& twist, const ShearLaw& law, const ShearState& shear,
                             double normal_stress, const TwistGeometry& geometry, double spin);

}  // namespace blockdem
