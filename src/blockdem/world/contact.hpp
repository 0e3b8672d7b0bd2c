// A persistent contact between two blocks: geometry of this step, joint law, shear history.
#pragma once

#include <Eigen/Core>

#include "blockdem/collision/boon2012.hpp"
#include "blockdem/collision/contact_geometry.hpp"
#include "blockdem/contact/shear_state.hpp"
#include "blockdem/contact/twist.hpp"

namespace blockdem {

/// The narrow phase's result as a contact keeps it between steps: ContactGeometry without the
/// slice polygon, which only the narrow phase itself needs (it is ~400 bytes per contact), and
/// without the overlap LP's ball, which the pair's warm start keeps. Whether the LP found
/// r* > tolerance is Contact::touching (beside the other flags, without padding).
struct ContactGeometryRecord {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();    ///< contact point x_c (m)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit normal, from A to B (-)
  double overlap = 0.0;  ///< δ: chord of A∩B through x_c along n (m)
  double area = 0.0;     ///< A_c: area of the slice of A∩B at x_c (m^2)

  ContactGeometryRecord() = default;
  explicit ContactGeometryRecord(const ContactGeometry& g)
      : point(g.point), normal(g.normal), overlap(g.overlap), area(g.area) {}
};

struct Contact {
  int a = -1;    ///< first block (the normal points from a to b)
  int b = -1;    ///< second block
  int law = -1;  ///< index into World::joint_laws()
  // The flags sit together beside the indices (no padding between doubles).
  bool has_history = false;  ///< false on the step the contact forms
  bool integrated = false;   ///< the force came from face integration (else point contact)
  bool sliding = false;      ///< the shear law yielded this step
  bool touching = false;     ///< this step's overlap LP found r* > tolerance (geometry is set)

  ContactGeometryRecord geometry;  ///< this step's geometry
  ShearState shear;                ///< shear history (force on b, plastic slip)
  TwistState twist;                ///< twisting moment about the normal (on b)
  Eigen::Vector3d previous_normal = Eigen::Vector3d::UnitZ();

  double normal_stress = 0.0;  ///< σ_n (Pa); face-integrated: mean over the compressed area
  /// Where the normal and shear forces act (m): x_c in mode boon2012, the centre of pressure
  /// of an integrated face contact.
  Eigen::Vector3d force_point = Eigen::Vector3d::Zero();
  double compressed_area = 0.0;  ///< area carrying stress (m^2); boon2012: the slice area
  double peak_stress = 0.0;      ///< largest normal stress over the contact (Pa)
  double peak_closure = 0.0;     ///< largest closure over the contact (m)
  double normal_force = 0.0;     ///< F_n (N), compression positive, acts on b along +normal
  double shear_stiffness = 0.0;  ///< k_s A of the last shear update, for its energy (N/m)

  /// Total force on b (N); the force on a is its negative.
  Eigen::Vector3d force_on_b() const { return normal_force * geometry.normal + shear.force; }
};

/// Back to a fresh contact (no history, no forces), keeping the pair and its bond state: a bond
/// that broke stays broken, and an intact one stays intact, while the pair remains a candidate.
inline void forget_history(Contact& c) {
  if (!c.has_history) return;
  Contact fresh;
  fresh.a = c.a;
  fresh.b = c.b;
  fresh.law = c.law;
  fresh.shear.bond = c.shear.bond;
  c = fresh;
}

}  // namespace blockdem
