// The voussoir beam: a row of equal blocks between two abutments,
// preloaded by a servo-controlled abutment at 1 g, then loaded by gravity steps.
#pragma once

#include <string>
#include <vector>

#include "blockdem/numerics/units.hpp"
#include "blockdem/world/stage.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

/// A jointed beam: x along the span, y across, z up; the beam's top at z = 0, its left end at
/// x = 0. Defaults: the paper's full-block beam (Talesnick et al. 2007 centrifuge model).
struct VoussoirSpec {
  int blocks = 6;                   ///< number of beam blocks (-)
  double block_length = 0.046;      ///< along the span (m)
  double block_width = 0.046;       ///< across the span (m)
  double block_depth = 0.046;       ///< beam depth T (m)
  double abutment_length = 0.060;   ///< abutment size along the span (m)
  double abutment_height = 0.100;   ///< abutment height; tops flush with the beam top (m)
  double density = 1207.0;          ///< (kg/m^3), the paper's Table 1
  double preload_force = 60.0;      ///< horizontal thrust applied by the servo at 1 g (N)
  double preload_tolerance = 0.01;  ///< servo settles within this fraction of preload_force (-)
  std::vector<double> g_levels = {2, 5, 10, 15, 20, 25, 30, 35, 40};  ///< after the 1 g preload
  /// Which abutment moves under servo control during the preload: "both" (default: the two move
  /// symmetrically, so the beam is loaded symmetrically), "left" or "right" (one moves, as in
  /// the centrifuge test; its push leaves a small path-dependent asymmetry in how the beam's
  /// weight is shared between the abutments).
  std::string servo_side = "both";
  JointLaw law;  ///< joint law of every joint (beam and abutments)
  /// Beam blocks move in the x-z plane only (no y translation, no rotation about x or z): the
  /// centrifuge model is a plane problem. The point contact of mode boon2012 transmits no
  /// twisting moment, so without this constraint out-of-plane modes are unresisted.
  bool plane_motion = true;
  /// Equilibrium tolerances of every level (see Stage). Tight, so that the symmetric beam stays
  /// symmetric to 1e-6 and the statics check H z = W S / 8 holds far inside 1%.
  double unbalanced_tolerance = 1e-7;
  double kinetic_tolerance = 1e-12;
  std::int64_t max_steps_per_level = 400000;
  /// Steps over which gravity is raised to each new level before equilibrium is sought.
  std::int64_t ramp_steps = 1000;
  /// When a level fails by a mechanism (snap-through), bisect between the last stable level and
  /// the failed one, each trial from the last stable equilibrium (the level's, then the last
  /// stable trial's), to collapse_tolerance (g).
  bool find_collapse = false;
  double collapse_tolerance = 0.5;  ///< (g)

  double span() const { return blocks * block_length; }  ///< S (m)
  double g_max() const { return g_levels.empty() ? 1.0 : g_levels.back(); }
  /// Throws std::invalid_argument naming the field for an impossible beam.
  void validate() const;
};

/// Where the beam's parts are in the world built from a VoussoirSpec.
struct VoussoirLayout {
  int left_abutment = 0;
  int right_abutment = 1;
  std::vector<int> beam;  ///< beam block indices, left to right
};

/// Blocks (abutments first, then the beam left to right), the joint law for all pairs, and the
/// stages: "preload" (1 g, servo to preload_force, then held) and one per g level.
struct VoussoirModel {
  std::vector<Block> blocks;
  JointLaw law;
  std::vector<Stage> stages;
  VoussoirLayout layout;
};

VoussoirModel build_voussoir(const VoussoirSpec& spec);

}  // namespace blockdem
