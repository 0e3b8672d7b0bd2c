// Removable blocks: the faces an excavation exposes, each exposed block's contact planes and
// joint strengths, and its block-theory limit equilibrium.
#include "blockdem/run/removable_blocks.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "blockdem/analysis/block_theory.hpp"
#include "blockdem/collision/shared_face.hpp"
#include "blockdem/contact/joint_strength.hpp"
#include "blockdem/contact/shear_laws.hpp"
#include "blockdem/world/bolt.hpp"

namespace blockdem {
namespace {

/// A block at its pose: world vertices and planes.
struct Posed {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Halfspace> planes;
};
Posed posed(const Block& b) {
  Posed p;
  for (const auto& v : b.shape.vertices()) p.vertices.push_back(b.to_world(v));
  p.planes = planes_at_pose(b);
  return p;
}

/// The joint law of plane `plane` of block `k`: its face's law, else the last group rule that
/// covers the block's group (World::law_for's order); -1 when none.
int plane_law(const Scenario& sc, std::size_t k, int plane) {
  if (k < sc.face_laws.size() && !sc.face_laws[k].empty()) {
    const int law = sc.face_laws[k][static_cast<std::size_t>(plane)];
    if (law >= 0) return law;
  }
  const std::string& group = sc.blocks[k].group();
  int found = -1;
  for (const JointRule& r : sc.joint_rules) {
    if ((r.group_a.empty() || r.group_a == group) && (r.group_b.empty() || r.group_b == group))
      found = r.law;
  }
  return found;
}

/// Dip and dip direction (degrees, clockwise from north = +y) of the plane with normal n.
std::pair<double, double> dip_of(Eigen::Vector3d n) {
  if (n.z() < 0.0) n = -n;
  const double dip = std::acos(std::clamp(n.z(), -1.0, 1.0)) * 180.0 / M_PI;
  double direction = std::atan2(n.x(), n.y()) * 180.0 / M_PI;
  if (direction < 0.0) direction += 360.0;
  if (std::hypot(n.x(), n.y()) < 1e-12) direction = 0.0;
  return {dip, direction};
}

/// Gravity at the end of stage `stage`: the last one a stage up to it sets (m/s^2).
Eigen::Vector3d gravity_at(const Scenario& sc, std::size_t stage) {
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  for (std::size_t s = 0; s <= stage; ++s) {
    if (sc.stages[s].gravity) g = *sc.stages[s].gravity;
  }
  return g;
}

/// One exposed block's entry, or null when gravity cannot move it into the opening.
nlohmann::json block_entry(const Scenario& sc, std::size_t k, const std::vector<double>& exposed,
                           const Eigen::Vector3d& gravity, double required_factor,
                           const std::string& stage) {
  const Block& b = sc.blocks[k];
  const Posed p = posed(b);
  // The contact planes: each face's area less what it shares with removed blocks.
  std::vector<ContactPlane> planes;
  std::vector<int> plane_index;
  for (const Face& f : b.shape.faces()) {
    const double area = b.shape.face_area(static_cast<int>(&f - b.shape.faces().data()));
    const double touching = area - exposed[static_cast<std::size_t>(f.plane)];
    if (!(touching > 1e-6 * area)) continue;
    ContactPlane c;
    c.normal = p.planes[static_cast<std::size_t>(f.plane)].normal;
    c.area = touching;
    const int law = plane_law(sc, k, f.plane);
    if (law >= 0) {
      const JointStrength& s = strength_of(sc.joint_laws[static_cast<std::size_t>(law)].shear);
      c.friction_coefficient = s.friction_coefficient;
      c.cohesion = s.cohesion;
    }
    planes.push_back(c);
    plane_index.push_back(f.plane);
  }
  const double weight = b.mass * gravity.norm();
  const BlockEquilibrium eq = block_equilibrium(planes, gravity, weight);
  if (eq.mode == BlockMode::stable) return nullptr;
  nlohmann::json sliding = nlohmann::json::array();
  for (std::size_t m = 0; m < eq.planes.size(); ++m) {
    const std::size_t i = static_cast<std::size_t>(eq.planes[m]);
    const int plane = plane_index[i];
    std::string set;
    if (k < sc.face_sets.size() && !sc.face_sets[k].empty()) {
      const int s = sc.face_sets[k][static_cast<std::size_t>(plane)];
      if (s >= 0 && static_cast<std::size_t>(s) < sc.joint_sets.size())
        set = sc.joint_sets[static_cast<std::size_t>(s)];
    }
    const auto [dip, direction] = dip_of(planes[i].normal);
    sliding.push_back({{"joint_set", set},
                       {"dip_deg", dip},
                       {"dip_direction_deg", direction},
                       {"area_m2", planes[i].area},
                       {"normal_force_N", eq.normal_force[m]},
                       {"friction_deg", friction_deg_from(planes[i].friction_coefficient)},
                       {"cohesion_Pa", planes[i].cohesion}});
  }
  const double support = support_force(planes, eq, gravity, weight, -eq.direction, required_factor);
  return {{"block", b.name},
          {"stage", stage},
          {"volume_m3", b.shape.volume()},
          {"weight_N", weight},
          {"mode", to_string(eq.mode)},
          {"planes", sliding},
          {"direction", {eq.direction.x(), eq.direction.y(), eq.direction.z()}},
          {"factor_of_safety", eq.factor_of_safety},
          {"support_force_N", support}};
}

}  // namespace

nlohmann::json removable_blocks(const Scenario& sc, std::size_t stage, double required_factor) {
  nlohmann::json out = nlohmann::json::array();
  const Eigen::Vector3d gravity = gravity_at(sc, stage);
  if (gravity.norm() == 0.0) return out;
  // Blocks removed by this stage, and by it and the stages before (the opening so far).
  const std::set<std::string> now(sc.stages[stage].remove.begin(), sc.stages[stage].remove.end());
  std::set<std::string> removed;
  for (std::size_t s = 0; s <= stage; ++s)
    removed.insert(sc.stages[s].remove.begin(), sc.stages[s].remove.end());
  std::vector<std::size_t> gone;
  for (std::size_t k = 0; k < sc.blocks.size(); ++k) {
    if (removed.count(sc.blocks[k].name)) gone.push_back(k);
  }
  std::vector<Posed> gone_posed;
  for (std::size_t r : gone) gone_posed.push_back(posed(sc.blocks[r]));
  for (std::size_t k = 0; k < sc.blocks.size(); ++k) {
    const Block& b = sc.blocks[k];
    if (removed.count(b.name) || !b.is_dynamic()) continue;
    // The area of each of its planes that the opening exposes, and whether this stage did.
    std::vector<double> exposed(b.shape.planes().size(), 0.0);
    bool opened_now = false;
    const Posed p = posed(b);
    for (std::size_t g = 0; g < gone.size(); ++g) {
      const Block& r = sc.blocks[gone[g]];
      const double reach = b.shape.bounding_radius() + r.shape.bounding_radius();
      if ((b.position - r.position).norm() > reach) continue;
      const auto face =
          shared_face(b.shape, p.vertices, p.planes, gone_posed[g].planes, 1e-9 * reach);
      if (!face || !(face->area > 1e-6 * b.shape.bounding_radius() * b.shape.bounding_radius()))
        continue;
      exposed[static_cast<std::size_t>(face->plane_a)] += face->area;
      opened_now = opened_now || now.count(r.name) > 0;
    }
    if (!opened_now) continue;
    nlohmann::json entry =
        block_entry(sc, k, exposed, gravity, required_factor, sc.stages[stage].name);
    if (!entry.is_null()) out.push_back(std::move(entry));
  }
  std::stable_sort(out.begin(), out.end(), [](const nlohmann::json& x, const nlohmann::json& y) {
    return x["factor_of_safety"].get<double>() < y["factor_of_safety"].get<double>();
  });
  return out;
}

nlohmann::json block_theory_check(const nlohmann::json& stages, const StabilitySearch& sr) {
  if (!sr.failed_world || !sr.stable_world) return nullptr;
  // The block that moved most from the last stable trial to the first failed one.
  std::map<std::string, Eigen::Vector3d> stable;
  for (const Block& b : sr.stable_world->blocks()) stable[b.name] = b.position;
  const Block* mover = nullptr;
  double moved = 0.0;
  for (const Block& b : sr.failed_world->blocks()) {
    const auto it = stable.find(b.name);
    if (it == stable.end()) continue;
    const double d = (b.position - it->second).norm();
    if (d > moved) {
      moved = d;
      mover = &b;
    }
  }
  if (mover == nullptr) return nullptr;
  // Its block-theory entry: the latest excavation stage that lists it.
  const nlohmann::json* entry = nullptr;
  for (const auto& st : stages) {
    if (!st.contains("removable_blocks")) continue;
    for (const auto& b : st["removable_blocks"]) {
      if (b["block"] == mover->name) entry = &b;
    }
  }
  if (entry == nullptr) return nullptr;
  const double f = (*entry)["factor_of_safety"].get<double>();
  const bool agrees = f >= (1.0 - kBlockTheoryAgreement) * sr.last_stable &&
                      f <= (1.0 + kBlockTheoryAgreement) * sr.first_failed;
  return {{"block", mover->name},
          {"block_theory_factor", f},
          {"dem_factor", 0.5 * (sr.last_stable + sr.first_failed)},
          {"dem_bracket", {sr.last_stable, sr.first_failed}},
          {"agrees", agrees}};
}

}  // namespace blockdem
