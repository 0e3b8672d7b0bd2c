// What is measured on a voussoir beam at each load level: thrust, deflections,
// rotations, abutment slip, per-joint forces and thrust points, statics check, line of thrust.
#pragma once

#include <optional>
#include <vector>

#include "blockdem/analysis/thrust_line_fit.hpp"
#include "blockdem/voussoir/beam.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

/// One joint of the beam: between consecutive blocks, abutments included (left to right).
struct VoussoirJoint {
  int left = -1, right = -1;  ///< block indices
  bool in_contact = false;
  double x = 0.0, z = 0.0;    ///< thrust point: contact point (boon2012) or centre of pressure (m)
  double normal_force = 0.0;  ///< (N)
  double horizontal_force = 0.0;  ///< x component of the force the left block receives from the
                                  ///< right, sign flipped: compression positive (N)
  double shear_force = 0.0;       ///< |shear force| (N)
  double normal_stress = 0.0;     ///< (Pa)
  double closure = 0.0;           ///< overlap δ (boon2012) or largest closure (integrated) (m)
  double area = 0.0;         ///< contact area (m^2): slice area, or compressed area when integrated
  double peak_stress = 0.0;  ///< (Pa)
  /// Depth of the compressed zone across the beam (m): compressed area / block width (the
  /// hinge depth of an integrated face contact).
  double compressed_depth = 0.0;
  double plastic_slip = 0.0;  ///< (m)
  bool sliding = false;
};

struct VoussoirBlockState {
  int index = -1;
  double ux = 0.0, uz = 0.0;  ///< centroid displacement since the reference state (m)
  double deflection =
      0.0;  ///< downward displacement of the bottom-face centre since the reference (m)
  double rotation = 0.0;  ///< rotation about +y since the reference (rad)
};

struct VoussoirLevel {
  double g_level = 0.0;
  double thrust = 0.0;       ///< horizontal reaction of the servo abutment (both: their mean) (N)
  double thrust_left = 0.0;  ///< horizontal reaction of the other abutment (both: the left one) (N)
  double midspan_deflection = 0.0;  ///< downward, bottom of the beam at x = S/2 (m)
  double abutment_slip = 0.0;       ///< mean downward slip of the beam ends at the abutments (m)
  double max_normal_stress = 0.0;   ///< (Pa)
  double beam_weight = 0.0;         ///< W at this level (N)
  /// |H z - W S/8| / (W S/8): H the midspan joint's horizontal force, z the height of its
  /// thrust point above the abutments' (mean); NaN for an odd number of blocks or an open joint.
  double equilibrium_residual = 0.0;
  double lever_arm = 0.0;  ///< z of the statics check (m)
  std::vector<VoussoirJoint> joints;
  std::vector<VoussoirBlockState> blocks;
  std::optional<ThrustLineFit> fit;  ///< absent when the fits fail (message in fit_error)
  std::string fit_error;
};

/// Reference pose for deflections: the state after the preload.
struct VoussoirReference {
  std::vector<Eigen::Vector3d> positions;
  std::vector<Eigen::Quaterniond> orientations;
};

VoussoirReference capture_reference(const World& world);

/// Measures the beam. `g_level` is the current gravity in g.
VoussoirLevel measure_voussoir(const World& world, const VoussoirSpec& spec,
                               const VoussoirLayout& layout, const VoussoirReference& reference,
                               double g_level);

}  // namespace blockdem
