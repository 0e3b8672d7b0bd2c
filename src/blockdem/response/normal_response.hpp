// A contact's normal response over one step, from its geometry alone: the point contact's
// σ_n(δ) A_c at x_c (Boon et al. 2012), or the joint law integrated over the cells of linear
// closure of a face contact, acting at the centre of pressure; and where the shear spring acts.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>

#include "blockdem/collision/contact_geometry.hpp"
#include "blockdem/collision/face_contact.hpp"
#include "blockdem/collision/slice_polygon.hpp"
#include "blockdem/contact/normal_laws.hpp"

namespace blockdem {

/// The normal load a contact carries in a step, as the shear and twist steps read it.
struct ContactLoad {
  double stress = 0.0;  ///< σ_n (Pa), compression positive; a face contact's mean over `area`
  double force = 0.0;   ///< F_n (N), compression positive, on B along +n
  double area = 0.0;    ///< the area carrying stress (m^2)
};

/// What a contact's normal springs give in one step.
struct NormalResponse {
  bool integrated = false;  ///< the law integrated over a face contact's cells (else point contact)
  double force = 0.0;       ///< F_n (N), compression positive, on B along +n
  double stress = 0.0;      ///< σ_n (Pa); integrated: F_n over the compressed area
  /// x_f, where the normal force acts: x_c, or the centre of pressure (m).
  Eigen::Vector3d force_point = Eigen::Vector3d::Zero();
  double compressed_area = 0.0;  ///< the slice area A_c, or the area where the closure is > 0 (m^2)
  double peak_stress = 0.0;      ///< the largest σ_n over the contact (Pa)
  double peak_closure = 0.0;     ///< the largest closure: δ, or the cells' largest (m)
  /// The energy stored in the normal springs (J): ∫ e(g) dA over the cells, or ½ F_n δ for a
  /// point contact (exact for the linear law at a uniform closure).
  double energy = 0.0;
  /// x_s, where the shear spring acts: the centroid of the compressed area (of the slice, for a
  /// point contact), a point that moves with both faces (m).
  Eigen::Vector3d shear_point = Eigen::Vector3d::Zero();
  /// k_n A: the law's tangent stiffness at the peak closure times the compressed area (N/m), the
  /// normal spring of the automatic time step.
  double stiffness = 0.0;

  ContactLoad load() const { return {stress, force, compressed_area}; }
};

/// The centroid of a face contact's compressed area, the union of its cells (m); `fallback`
/// where the cells have no area.
Eigen::Vector3d compressed_area_centroid(std::span<const ClosureCell> cells,
                                         const Eigen::Vector3d& fallback);

/// The centroid of a point contact's slice polygon, in world coordinates (m); `fallback` where
/// the slice has no area.
Eigen::Vector3d slice_centroid(const SlicePolygon& slice, const Eigen::Vector3d& fallback);

/// Point contact (Boon et al. 2012): σ_n(δ) of the law at the overlap δ over the slice area A_c,
/// acting at x_c. The shear spring acts at the slice's centroid, not at x_c: x_c slides across
/// the face as the block rocks (a spring whose end moves over the block is not conservative).
inline NormalResponse point_normal_response(const NormalLaw& law, const ContactGeometry& g) {
  NormalResponse r;
  r.stress = normal_stress(law, g.overlap);
  r.force = r.stress * g.area;
  r.force_point = g.point;
  r.compressed_area = g.area;
  r.peak_stress = r.stress;
  r.peak_closure = g.overlap;
  r.energy = 0.5 * r.force * g.overlap;
  r.shear_point = slice_centroid(g.slice, g.point);
  r.stiffness = normal_tangent_stiffness(law, r.peak_closure) * r.compressed_area;
  return r;
}

/// Face contact: the law integrated over each cell of linear closure
/// (integrate_normal_stress_over_polygon, normal_energy_over_polygon), F_n the sum, acting at the
/// centre of pressure x_p = Σ F_i x_i / F_n; σ_n = F_n / A over the compressed area A. The shear
/// spring acts at the centroid of the compressed area, not at x_p, which slides across the face
/// as the block rocks (millimetres per microradian on a stiff joint): a prism on its face, whose
/// sliding and spinning frequencies are equal (I_z / m = J / A), flutters under such a spring,
/// undamped. None when no cell is closed (no closure anywhere to integrate).
std::optional<NormalResponse> face_normal_response(const NormalLaw& law,
                                                   std::span<const ClosureCell> cells);

/// A contact's normal response: integrated over the cells of `face` when a block presents a face
/// to the contact (face.face_type), else the point contact's from `g`. None when a face contact
/// has no closure anywhere.
inline std::optional<NormalResponse> normal_response(const NormalLaw& law, const ContactGeometry& g,
                                                     const FaceContactGeometry& face) {
  if (face.face_type) return face_normal_response(law, face.cells);
  return point_normal_response(law, g);
}

}  // namespace blockdem
