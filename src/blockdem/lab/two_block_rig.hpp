// The virtual laboratory's two-block rig: a top box resting on a bottom box, loaded through the
// engine (World), and the readings a lab would take from it (closure, load cell stresses).
#pragma once

#include <Eigen/Core>

#include "blockdem/contact/normal_laws.hpp"
#include "blockdem/contact/shear_laws.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

/// The rig. The bottom block is `prescribed` (at rest, or moved along x to shear the joint). The
/// top block is free along z only (its x, y translations and all rotations are blocked, like a
/// platen in a loading frame) and is pressed by its own weight: the world's gravity is set to
/// -sigma_n A / m along z, so its weight is the normal load. The joint is the top block's bottom
/// face, area A = top_size.x * top_size.y. The world's broad phase only pairs a block with a free
/// one, which is why the moving block is the bottom one: the joint sees the same relative motion.
struct TwoBlockRigDef {
  Eigen::Vector3d top_size{0.1, 0.1, 0.05};  ///< top block, x (shear direction), y, z (m)
  double bottom_height = 0.05;               ///< bottom block along z (m); as wide as the top in y
  double density = 2500.0;                   ///< both blocks (kg/m^3)
  double damping = 0.8;                      ///< Cundall local damping of the top block (-)
  /// How the engine turns the overlap into forces; default the paper's point contact.
  ContactMode contact_mode = ContactMode::boon2012;
  double rounding_distance = 2e-4;  ///< r_round of the Boon 2012 narrow phase (m)
  /// Equilibrium stages (normal load levels): tolerances on the world's measures (-).
  double unbalanced_tolerance = 1e-5;
  double kinetic_tolerance = 1e-10;
  std::int64_t max_steps_per_level = 50000;  ///< a level that needs more has not converged (-)

  /// Throws std::invalid_argument naming the parameter ("two-block rig: ...").
  void validate() const;
  /// Nominal joint area A (m^2): the top block's bottom face.
  double joint_area() const { return top_size.x() * top_size.y(); }
};

/// What the rig measures after a step.
struct RigReading {
  double closure =
      0.0;  ///< from the blocks' positions: bottom's top face minus top's bottom face (m)
  double shear_displacement = 0.0;  ///< top relative to bottom along x since the start (m)
  double normal_stress = 0.0;  ///< load cell: contact force on the top block along z over A (Pa)
  double shear_stress = 0.0;   ///< load cell: contact force on the top block along -x over A (Pa)
  // The contact as the engine sees it (zeros when the blocks do not touch).
  bool touching = false;
  double overlap = 0.0;       ///< delta, chord overlap (m)
  double contact_area = 0.0;  ///< A_c (m^2)
  double plastic_slip = 0.0;  ///< beta, ShearState::plastic_slip (m)
};

/// A world holding the rig: block 0 is "bottom" (its top face at z = 0, centred at x = 0,
/// `bottom_length` along x), block 1 is "top" (centred above it, its bottom face at
/// z = -initial_closure), one joint law between them, gravity zero.
World make_two_block_rig(const TwoBlockRigDef& rig, const NormalLaw& normal, const ShearLaw& shear,
                         double bottom_length, double initial_closure);

/// Index of the rig's blocks in the world.
inline constexpr int rig_bottom = 0;
inline constexpr int rig_top = 1;

/// Gravity (m/s^2, along -z) that makes the top block's weight sigma_n A.
double rig_gravity_for_stress(const World& world, const TwoBlockRigDef& rig, double normal_stress);

/// Reads the rig after a step.
RigReading read_rig(const World& world, const TwoBlockRigDef& rig);

}  // namespace blockdem
