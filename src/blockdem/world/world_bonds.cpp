// Bonded joints that have opened: a rock bridge between two blocks carries tension (and shear up to
// c + sigma_n tan(phi), sigma_n < 0) after the blocks have moved apart, until it breaks. The narrow
// phase sees no overlap there, so the joint's closure is followed incrementally from the last
// touching step, or from zero on a face the blocks share at the start (a rock mass's cut faces).
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "blockdem/collision/shared_face.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

std::optional<SharedFace> World::shared_face_of(const Block& a, const Block& b, double gap) const {
  const double tolerance = 1e-9 * (a.shape.bounding_radius() + b.shape.bounding_radius()) + gap;
  // A face, not two blocks meeting along an edge (a sliver within the tolerance) ...
  const double size = std::min(a.shape.bounding_radius(), b.shape.bounding_radius());
  const double min_area = 1e-6 * size * size;
  // A's world vertices only for its faces on one of B's planes (Block::to_world's arithmetic):
  // this runs for every pair of neighbours at set-up.
  auto face = shared_face(a.shape, a.orientation, a.position, a.world_planes, b.world_planes,
                          tolerance, min_area);
  if (!face) return face;
  if (!(face->area > min_area)) return std::nullopt;
  // ... nor pressed into each other along one: the polygon's width (its area over its widest
  // span) is many times the depth of pressing, as where two faces press, not two edges.
  if (gap > 0.0) {
    double span = 0.0;
    for (const auto& p : face->polygon)
      for (const auto& q : face->polygon) span = std::max(span, (p - q).norm());
    if (!(face->area > 10.0 * gap * span)) return std::nullopt;
  }
  return face;
}

bool World::any_breakable_law() const {
  return std::any_of(laws_.begin(), laws_.end(),
                     [](const JointLaw& l) { return strength_of(l.shear).can_break(); });
}

int World::shared_face_law(int a, int b, const SharedFace& face, int group_law) const {
  const std::span<const int> laws_a = face_laws(a);
  const std::span<const int> laws_b = face_laws(b);
  int law = laws_a.empty() ? -1 : laws_a[static_cast<std::size_t>(face.plane_a)];
  if (law < 0 && !laws_b.empty()) law = laws_b[static_cast<std::size_t>(face.plane_b)];
  return law < 0 ? group_law : law;
}

bool World::evaluate_open_bond(PairSlot& slot, Contact& ct, const OpenBondStart* start, double dt,
                               bool advance_shear) const {
  if (ct.shear.bond != BondState::intact) return false;
  const Block& a = blocks_[ct.a];
  const Block& b = blocks_[ct.b];
  bool fresh = false;
  // The joint's point, normal and area (closure: the geometry's overlap, see below).
  Eigen::Vector3d x, n;
  double area = 0.0;
  if (ct.has_history) {
    x = start != nullptr ? start->point : ct.force_point();
    n = start != nullptr ? start->normal : ct.previous_normal();
    area = start != nullptr ? start->area : ct.compressed_area();
  } else {
    // A bond starts only where the blocks share a face at the start of the run.
    if (step_count_ != 0 || !advance_shear) return false;
    // No law the face could take can break: no bond, and no shared face to look for.
    const auto breakable = [&](int l) {
      return l >= 0 && strength_of(laws_[static_cast<std::size_t>(l)].shear).can_break();
    };
    if (!breakable(slot.group_law) &&
        std::none_of(face_laws(ct.a).begin(), face_laws(ct.a).end(), breakable) &&
        std::none_of(face_laws(ct.b).begin(), face_laws(ct.b).end(), breakable))
      return false;
    const auto face = shared_face_of(a, b);
    if (!face) return false;
    const int law = shared_face_law(ct.a, ct.b, *face, slot.group_law);
    if (law < 0 || !strength_of(laws_[static_cast<std::size_t>(law)].shear).can_break())
      return false;
    ct.law = law;
    x = face->centroid;
    n = face->normal;
    ct.geometry.overlap = 0.0;
    area = face->area;
    fresh = true;
  }
  if (ct.law < 0) return false;
  const JointLaw& law = laws_[static_cast<std::size_t>(ct.law)];
  const JointStrength& strength = strength_of(law.shear);
  if (!strength.can_break()) return false;

  // The joint's point and normal move with block A; its closure changes by the relative normal
  // velocity of the material points there (compression positive).
  double closure = ct.geometry.overlap;
  Eigen::Vector3d v_rel = Eigen::Vector3d::Zero();
  if (advance_shear && !fresh) {
    v_rel = b.point_velocity(x) - a.point_velocity(x);
    closure -= v_rel.dot(n) * dt;
    x += a.point_velocity(x) * dt;
    const Eigen::Vector3d turned = (n + a.angular_velocity.cross(n) * dt).normalized();
    rotate_into_plane(ct.shear, n, turned);
    n = turned;
  }
  // Zero closure is not tension: a joint with sigma_t = 0 breaks only once it opens.
  const double sigma = closure >= 0.0
                           ? normal_stress(law.normal, closure)
                           : bonded_normal_stress(law.normal, strength, ct.shear, closure);
  if (ct.shear.bond != BondState::intact) {
    // The tension cut-off: the bond breaks for good and the joint opens.
    slot.broke = advance_shear;
    forget_history(ct);
    return true;
  }
  ct.touching = false;
  ct.geometry.point = x;
  ct.geometry.normal = n;
  ct.geometry.overlap = closure;
  ct.geometry.area = area;
  ct.integrated = false;
  ct.normal_stress = sigma;
  ct.normal_force = sigma * area;
  // Force point, compressed area, peak stress and closure: x, the area, sigma and the closure.
  ct.take_point_values();
  ct.take_normal_as_previous();
  ct.has_history = true;
  slot.active = true;
  const double kn = normal_tangent_stiffness(law.normal, std::max(closure, 0.0)) * area;
  // At exactly zero stress (the step a shared face is found) there is nothing to update: the
  // tension cut-off sigma_n <= -sigma_t must not fire at sigma_n = 0 for sigma_t = 0.
  if (!advance_shear || sigma == 0.0) {
    ct.stiffness = kn;
    return true;
  }
  ShearIncrement inc;
  inc.displacement = Eigen::Vector3d((v_rel - v_rel.dot(n) * n) * dt);
  inc.normal_force = ct.normal_force;
  inc.normal_stress = sigma;
  inc.contact_area = area;
  inc.normal = n;
  const ShearResult sr = update_shear(law.shear, ct.shear, inc);
  ct.sliding = sr.sliding;
  if (sr.broke) {
    // Broken in shear while open: the joint has no strength left and no normal force.
    slot.broke = true;
    slot.active = false;
    forget_history(ct);
    return true;
  }
  ct.stiffness = kn + sr.stiffness;
  return true;
}

int World::bonded_face_set(int a, int b) const {
  const auto& pa = blocks_[static_cast<std::size_t>(a)].world_planes;
  const auto& pb = blocks_[static_cast<std::size_t>(b)].world_planes;
  const double size = blocks_[static_cast<std::size_t>(a)].bounding_radius +
                      blocks_[static_cast<std::size_t>(b)].bounding_radius;
  // The pair of opposite planes nearest to coincident: the blocks have moved little since the
  // bond formed on their shared face (a bond breaks at a closure of sigma_t / k_n or a slip of
  // c / k_s).
  double best = std::numeric_limits<double>::infinity();
  std::size_t ia = 0, ib = 0;
  for (std::size_t i = 0; i < pa.size(); ++i) {
    for (std::size_t j = 0; j < pb.size(); ++j) {
      const double facing = pa[i].normal.dot(pb[j].normal);
      if (facing > -0.5) continue;
      const double misfit = std::abs(pa[i].offset + pb[j].offset) + (1.0 + facing) * size;
      if (misfit < best) {
        best = misfit;
        ia = i;
        ib = j;
      }
    }
  }
  if (!std::isfinite(best)) return -1;
  const auto set_of = [&](int block, std::size_t plane) {
    const std::span<const int> sets = face_sets_.of(static_cast<std::size_t>(block));
    return plane < sets.size() ? sets[plane] : -1;
  };
  const int set = set_of(a, ia);
  return set >= 0 ? set : set_of(b, ib);
}

std::size_t World::break_table_rows() const {
  return static_cast<std::size_t>(face_sets_.max_value(-1) + 2);
}

void World::add_step_breaks(const std::vector<std::array<std::int64_t, 2>>& breaks) {
  if (broken_by_set_.size() < breaks.size()) broken_by_set_.resize(breaks.size(), {0, 0});
  for (std::size_t k = 0; k < breaks.size(); ++k) {
    broken_by_set_[k][0] += breaks[k][0];
    broken_by_set_[k][1] += breaks[k][1];
  }
}

void World::tally_step_breaks(const std::vector<char>* counted) {
  step_breaks_.assign(break_table_rows(), {0, 0});
  for (std::size_t k = 0; k < slots_.size(); ++k) {
    const PairSlot& s = slots_[k];
    if (!s.broke || (counted != nullptr && (*counted)[k] == 0)) continue;
    const BondState bond = s.active ? contact_of(s).shear.bond : s.bond;
    const int set = bonded_face_set(s.a, s.b);
    step_breaks_[static_cast<std::size_t>(set + 1)][bond == BondState::broken_in_tension ? 0 : 1] +=
        1;
  }
}

}  // namespace blockdem
