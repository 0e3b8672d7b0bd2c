// One pair's work in a step (World::evaluate_pair): the narrow phase, the joint law for the
// contact, and its response through the named steps of response/ (normal, then shear and twist
// held together against the limit surface). Force assembly: normal force, then shear.
#include <algorithm>
#include <cmath>
#include <exception>
#include <iterator>
#include <limits>
#include <optional>
#include <stdexcept>

#include "blockdem/collision/small_vector.hpp"
#include "blockdem/contact/twist.hpp"
#include "blockdem/geometry/polygon_moments.hpp"
#include "blockdem/response/contact_damping.hpp"
#include "blockdem/response/contact_energy.hpp"
#include "blockdem/response/contact_twist.hpp"
#include "blockdem/response/face_laws.hpp"
#include "blockdem/response/normal_response.hpp"
#include "blockdem/response/shear_response.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

namespace {

// A face contact leaves out the planes of either block that hold the other's box with this
// fraction of the other's bounding radius to spare (planes_holding): the far faces, not the
// faces flush with the other block.
constexpr double kHoldingClearance = 1e-6;

// A contact's terms of this step, before its pair is evaluated: none until a force acts.
void clear_step_terms(Contact& ct) {
  ct.slip_work = 0.0;
  ct.shear_couple = 0.0;
  ct.stiffness = 0.0;
  ct.twist_stiffness = 0.0;
}

// The contact takes this step's geometry; no force yet.
void take_geometry(Contact& ct, const ContactGeometry& g) {
  ct.geometry = ContactGeometryRecord(g);
  ct.touching = g.touching;
  ct.integrated = false;
}

// The contact takes this step's normal response: F_n and σ_n, and the force values of a face
// contact (a point contact's follow from its geometry and σ_n).
void take_normal_response(Contact& ct, const NormalResponse& r) {
  ct.integrated = r.integrated;
  ct.normal_force = r.force;
  ct.normal_stress = r.stress;
  if (r.integrated) {
    ct.set_force_values(r.force_point, r.compressed_area, r.peak_stress, r.peak_closure, r.energy);
  } else {
    ct.take_point_values();
  }
}

// What the tangential steps of a pair read besides its contact state.
struct TangentialInput {
  const Block& a;
  const Block& b;
  const JointLaw& law;
  const ContactGeometry& geometry;  // this step's narrow phase
  const FaceContactGeometry& face;  // its cells (mode face_integrated), else none
  const NormalResponse& normal;     // this step's normal response
  const Eigen::Vector3d& previous;  // the normal of the last shear update
  double dt = 0.0;                  // (s)
  bool twist = false;               // the torsional spring acts
};

// B's motion relative to A over the step at x, about the unit normal n: the slip of the
// material points in the tangent plane (none on the step the contact forms: `moved` false) and
// the turn `turn` (rad).
ContactMotion relative_motion(const TangentialInput& in, const Eigen::Vector3d& x,
                              const Eigen::Vector3d& n, bool moved, double turn) {
  ContactMotion m;
  m.point = x;
  m.normal = n;
  if (moved) m.slip = tangential_slip(in.b.point_velocity(x) - in.a.point_velocity(x), n, in.dt);
  m.turn = turn;
  return m;
}

// A contact's twist and shear over the step, after its normal response: the torsional spring
// turned by B's spin relative to A (from the state before the shear update: bond and plastic
// slip), the stored shear force carried into this step's frame and the law's increment from the
// slip at the shear spring's point, then, on a face contact with twist, force and moment held
// together against Coulomb's law at every point; the contact then has a history, turned to this
// step's normal, and its springs for the automatic time step. Returns whether the bond broke.
bool respond_tangentially(Contact& ct, const TangentialInput& in) {
  const Block& a = in.a;
  const Block& b = in.b;
  const Eigen::Vector3d& n = ct.geometry.normal;
  const double spin = in.twist && ct.has_history
                          ? relative_spin(a.angular_velocity, b.angular_velocity, n, in.dt)
                          : 0.0;
  const FaceStress stress{in.face.cells, in.law.normal};
  std::optional<TwistGeometry> twist_area;
  TwistStep turned;
  if (in.twist) {
    twist_area = twist_geometry(in.normal, in.geometry, in.face, n);
    turned = advance_twist(ct.twist, in.law.shear, ct.shear, in.normal.stress, *twist_area, stress,
                           spin);
    ct.twist_stiffness = turned.stiffness;
  }
  // With twist, the stored force also turns with the contact's spin about n (the blocks' mean).
  if (ct.has_history) {
    const double frame =
        in.twist ? frame_spin(a.angular_velocity, b.angular_velocity, n, in.dt) : 0.0;
    carry_shear_state(ct.shear, in.previous, n, frame);
  }
  const ContactMotion motion = relative_motion(in, in.normal.shear_point, n, ct.has_history, spin);
  const Eigen::Vector3d force_before = ct.shear.force;
  const double energy_before = ct.shear.elastic_energy;
  const ShearResult sr = shear_response(ct.shear, in.law.shear, in.normal.load(), motion);
  ct.sliding = sr.sliding;
  // The ledger's shear spring: what it holds, and the work done on it that it does not hold.
  const ShearSpringEnergy spring =
      shear_spring_energy(in.law.shear, force_before, energy_before, ct.shear, sr, motion.slip);
  ct.shear.elastic_energy = spring.stored;
  ct.slip_work = spring.unstored + turned.slip_work;
  if (twist_area && in.normal.integrated) {
    const ShearTwistLimit limit =
        limit_shear_and_twist(ct.shear, ct.twist, in.law.shear, in.normal.load(), *twist_area,
                              stress, motion, ct.force_point(), sr.stiffness, turned.stiffness);
    if (limit.slipped) {
      ct.sliding = true;
      ct.slip_work += limit.shear_released;
      ct.slip_work += limit.twist_released;
    }
  }
  ct.take_normal_as_previous();
  ct.has_history = true;
  // Stiffness for the automatic time step: normal and shear springs k A (N/m).
  ct.stiffness = in.normal.stiffness + sr.stiffness;
  return sr.broke;
}

// A prestressed pair's planes of A, its face plane moved out, and the closure to add over it.
struct PrestressedPlanes {
  SmallVector<Halfspace, 16> planes;
  ClosureOffset offset;

  std::span<const Halfspace> take(const Block& a, const ContactPreload& p) {
    planes.clear();
    for (const Halfspace& h : a.world_planes) planes.push_back(h);
    planes[static_cast<std::size_t>(p.plane_a)].offset += p.shift;
    offset = p.offset_in_world(a);
    return {planes.data(), planes.size()};
  }
};

// The point of plane h that lies from x along n (m).
Eigen::Vector3d on_plane(const Halfspace& h, const Eigen::Vector3d& x, const Eigen::Vector3d& n) {
  return x + ((h.offset - h.normal.dot(x)) / h.normal.dot(n)) * n;
}

// The area of a face contact's cells (m^2).
double cells_area(const FaceContactGeometry& f) {
  double area = 0.0;
  for (const ClosureCell& c : f.cells) {
    area += polygon_area_centroid(
                std::span<const Eigen::Vector3d>(c.vertices.data(), c.vertices.size()))
                .area;
  }
  return area;
}

// A prestressed contact's first step: the field's shear force (and its energy in the shear
// spring, F² / (2 k_s A)) and, with twist, its twisting moment about the normal.
void take_prestress(Contact& ct, const ContactPreload& p, const Block& a, const JointLaw& law,
                    bool twist) {
  const Eigen::Vector3d& n = ct.geometry.normal;
  Eigen::Vector3d force = a.rotation() * p.shear_force;
  force -= n.dot(force) * n;
  ct.shear.force = force;
  const double area = ct.compressed_area();
  const double ks = shear_stiffness_estimate(law.shear, ct.normal_stress) * area;
  if (ks > 0.0) {
    ct.shear.elastic_energy = 0.5 * force.squaredNorm() / ks;
    // The degrading law's elastic displacement U_e, with F = -k_s A U_e.
    if (std::holds_alternative<DegradingShear>(law.shear))
      ct.shear.elastic_displacement = -force / ks;
  }
  if (twist) ct.twist.moment = p.twisting_moment;
}

}  // namespace

void World::evaluate_pair(PairSlot& slot, Contact& ct, double dt, bool advance_shear) const {
  slot.active = false;
  slot.broke = false;
  clear_step_terms(ct);
  const std::span<const int> face_laws_a = face_laws(ct.a);
  const std::span<const int> face_laws_b = face_laws(ct.b);
  if (slot.group_law < 0 && face_laws_a.empty() && face_laws_b.empty()) return forget_history(ct);
  // Faces that do not press on each other: a bond may hold them, else the contact is gone.
  const auto open_bond = [&](const OpenBondStart* start) {
    if (!evaluate_open_bond(slot, ct, start, dt, advance_shear)) forget_history(ct);
  };
  const Block& a = blocks_[ct.a];
  const Block& b = blocks_[ct.b];
  const double extent = 2.0 * (a.bounding_radius + b.bounding_radius);
  // A prestressed joint: A's face plane moved out, and the closure of the field over it.
  const ContactPreload* preload = preloads_.find(ct.a, ct.b);
  PrestressedPlanes prestressed;
  std::span<const Halfspace> planes_a = a.world_planes;
  if (preload != nullptr) planes_a = prestressed.take(a, *preload);
  ContactGeometry g = narrow_phase(slot, planes_a, a, b, extent);
  // A prestressed joint's cells are those of the shared face, its closure the chord between the
  // face planes plus the field's; the point contact's are its closure at x_c (the chord less the
  // plane's move, plus the field's) over the compressed part of the face.
  FaceContactGeometry shared;
  if (preload != nullptr && g.touching) {
    shared = face_contact_geometry(a.world_planes, b.world_planes,
                                   on_plane(b.world_planes[preload->plane_b], g.point, g.normal),
                                   g.normal, extent, settings_.face_contact, &prestressed.offset);
    g.overlap += prestressed.offset.at(g.point) - preload->shift;
    g.area = cells_area(shared);
  }
  // A bond is on a face the blocks share at the start (a rock mass's cut faces, blocks placed
  // face to face, perhaps pressed into each other): two blocks that meet along an edge or at a
  // corner, or do not meet, are unbonded from the first step.
  if (advance_shear && step_count_ == 0 && !ct.has_history && ct.shear.bond == BondState::intact &&
      preload == nullptr && any_breakable_law()) {
    const double pressed = g.touching && g.overlap > 0.0 ? 2.0 * g.overlap : 0.0;
    if (!shared_face_of(a, b, pressed)) ct.shear.bond = BondState::unbonded;
  }
  if (!g.touching || !(g.area > 0.0) || !(g.overlap > 0.0)) return open_bond(nullptr);
  // Last step's normal, before this step's geometry replaces it (the shear force turns from it).
  const Eigen::Vector3d previous = ct.previous_normal();
  // The joint law of the faces in contact (a joint set's), else the group rules'.
  ct.law = face_law_for_contact(a, face_laws_a, b, face_laws_b, g, slot.group_law);
  if (ct.law < 0) return forget_history(ct);
  // An open bond met below starts from last step's values, which the new geometry replaces.
  const bool face_mode = settings_.contact_mode == ContactMode::face_integrated;
  const OpenBondStart start =
      face_mode ? OpenBondStart{ct.force_point(), previous, ct.compressed_area()} : OpenBondStart{};
  // The last step's normal force, for the work of the normal force below.
  NormalLevel last;
  if (ct.has_history && ct.normal_force > 0.0)
    last = {ct.normal_force, ct.geometry.normal, ct.force_point(), ct.normal_energy()};
  take_geometry(ct, g);
  const JointLaw& law = laws_[ct.law];
  // Normal force: σ_n(δ) A_c at x_c (the paper's point contact), or the law integrated over the
  // cells of a face contact, acting at the centre of pressure (mode face_integrated).
  const FaceContactGeometry fc =
      !face_mode ? FaceContactGeometry{}
      : preload != nullptr
          ? std::move(shared)
          : face_contact_geometry(a.world_planes, b.world_planes, g.point, ct.geometry.normal,
                                  extent, settings_.face_contact, nullptr,
                                  {planes_holding(a.world_planes, box_min_[ct.b], box_max_[ct.b],
                                                  kHoldingClearance * b.bounding_radius),
                                   planes_holding(b.world_planes, box_min_[ct.a], box_max_[ct.a],
                                                  kHoldingClearance * a.bounding_radius)});
  const std::optional<NormalResponse> normal = normal_response(law.normal, g, fc);
  if (!normal) return open_bond(&start);
  take_normal_response(ct, *normal);
  slot.active = true;
  // The field's shear force and twisting moment, held from the first step on.
  if (preload != nullptr && advance_shear && !ct.has_history && step_count_ == 0)
    take_prestress(ct, *preload, a, law, settings_.twist_enabled());
  if (advance_shear) {
    const bool twist = settings_.twist_enabled();
    slot.broke = respond_tangentially(ct, {a, b, law, g, fc, *normal, previous, dt, twist});
    // The normal force's work that the energy shown for it (½ F_n δ, ∫ e(g) dA) does not hold,
    // with the slip's dissipation (response/contact_energy.hpp), from the step after the contact
    // formed: the work of the steps in which a contact forms and opens, where the force jumps,
    // is the integrator's (docs/outputs.md), and cancels between the two in an elastic impact.
    if (last.force > 0.0) {
      const NormalLevel now{normal->force, ct.geometry.normal, normal->force_point, normal->energy};
      ct.slip_work += normal_unstored_work(a, b, last, last_dt_, now, dt);
    }
  } else {
    // A restore re-derives geometry and normal force only; the shear history stays as saved,
    // and so does the normal it was last turned to.
    ct.stiffness = normal->stiffness;
    ct.set_previous_normal(previous);
  }
  ct.shear_couple =
      shear_couple(normal->shear_point, ct.force_point(), ct.shear.force, ct.geometry.normal);
  // The viscous dashpot beside the normal spring (settings contact_damping), at the force point.
  if (advance_shear && settings_.contact_damping > 0.0) {
    const Dashpot d = contact_dashpot(settings_.contact_damping, a, b, ct.force_point(),
                                      ct.geometry.normal, normal->stiffness, normal->force, dt);
    ct.set_damping(d.force, -d.half_work);
  }
}

}  // namespace blockdem
