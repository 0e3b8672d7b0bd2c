// A persistent contact between two blocks: geometry of this step, joint law, shear history.
#pragma once

#include <Eigen/Core>

#include "blockdem/collision/boon2012.hpp"
#include "blockdem/collision/contact_geometry.hpp"
#include "blockdem/collision/inscribed_ball.hpp"
#include "blockdem/contact/shear_state.hpp"

namespace blockdem {

struct Contact {
  int a = -1;    ///< first block (the normal points from a to b)
  int b = -1;    ///< second block
  int law = -1;  ///< index into World::joint_laws()

  ContactGeometry geometry;  ///< this step's geometry
  ShearState shear;          ///< shear history (force on b, plastic slip)
  bool has_history = false;  ///< false on the step the contact forms
  Eigen::Vector3d previous_normal = Eigen::Vector3d::UnitZ();

  double normal_stress = 0.0;  ///< σ_n (Pa); face-integrated: mean over the compressed area
  /// Where the normal and shear forces act (m): x_c in mode boon2012, the centre of pressure
  /// of an integrated face contact.
  Eigen::Vector3d force_point = Eigen::Vector3d::Zero();
  bool integrated = false;       ///< the force came from face integration (else point contact)
  double compressed_area = 0.0;  ///< area carrying stress (m^2); boon2012: the slice area
  double peak_stress = 0.0;      ///< largest normal stress over the contact (Pa)
  double peak_closure = 0.0;     ///< largest closure over the contact (m)
  double normal_force = 0.0;     ///< F_n (N), compression positive, acts on b along +normal
  bool sliding = false;          ///< the shear law yielded this step

  // Warm starts between steps.
  Boon2012Cache narrow_cache;
  InscribedBall previous_ball;

  /// Total force on b (N); the force on a is its negative.
  Eigen::Vector3d force_on_b() const { return normal_force * geometry.normal + shear.force; }
};

}  // namespace blockdem
