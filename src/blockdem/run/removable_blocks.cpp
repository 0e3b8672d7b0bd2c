// Removable blocks: the blocks an excavation exposes, the faces each shares with the rock that
// stays and their joint strengths, and its block-theory limit equilibrium.
#include "blockdem/run/removable_blocks.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "blockdem/analysis/block_theory.hpp"
#include "blockdem/collision/shared_face.hpp"
#include "blockdem/collision/uniform_grid.hpp"
#include "blockdem/contact/joint_strength.hpp"
#include "blockdem/contact/shear_laws.hpp"
#include "blockdem/numerics/number_text.hpp"
#include "blockdem/world/bolt.hpp"

namespace blockdem {
namespace {

/// The face law of plane `plane` of block `k` (-1: none).
int face_law(const Scenario& sc, std::size_t k, int plane) {
  if (k >= sc.face_laws.size() || sc.face_laws[k].empty()) return -1;
  return sc.face_laws[k][static_cast<std::size_t>(plane)];
}

/// The joint law between block `a` and block `b` where they share `face` (plane_a on `a`), as
/// the world chooses it (World::shared_face_law, the pair's lower block index first): the face
/// law of the block of lower index, else the other's, else the last group rule that covers both
/// groups (World::law_for); -1 when none.
int contact_law(const Scenario& sc, std::size_t a, std::size_t b, const SharedFace& face) {
  const int first = a < b ? face_law(sc, a, face.plane_a) : face_law(sc, b, face.plane_b);
  const int second = a < b ? face_law(sc, b, face.plane_b) : face_law(sc, a, face.plane_a);
  int law = first >= 0 ? first : second;
  if (law >= 0) return law;
  const std::string& ga = sc.blocks[a].group();
  const std::string& gb = sc.blocks[b].group();
  auto matches = [](const std::string& rule, const std::string& group) {
    return rule.empty() || rule == group;
  };
  for (const JointRule& r : sc.joint_rules) {
    if ((matches(r.group_a, ga) && matches(r.group_b, gb)) ||
        (matches(r.group_a, gb) && matches(r.group_b, ga)))
      law = r.law;
  }
  return law;
}

/// Where two blocks touch: the shared polygon, when it is a face and not an edge.
std::optional<SharedFace> touching(const Block& a, const PosedBlock& pa, const Block& b,
                                   const PosedBlock& pb) {
  const double reach = a.shape.bounding_radius() + b.shape.bounding_radius();
  if ((a.position - b.position).norm() > reach) return std::nullopt;
  auto face = shared_face(a.shape, pa.vertices, pa.planes, pb.planes, 1e-9 * reach);
  const double size = std::min(a.shape.bounding_radius(), b.shape.bounding_radius());
  if (face && !(face->area > 1e-6 * size * size)) return std::nullopt;
  return face;
}

/// One of a block's contact planes as found: its face's plane (-1: a roller), the joint set
/// that made that face ("" for none), the joint strength summed over its neighbours.
struct FoundPlane {
  int plane = -1;
  ContactPlane contact;
  double friction_area = 0.0;  ///< sum of tan(phi) A over the neighbours (m^2)
  double cohesion_area = 0.0;  ///< sum of c A (N)
};

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

/// The blocks' poses, formed when first asked for (a rock mass of a million blocks needs those
/// near the opening only).
class Poses {
 public:
  explicit Poses(const Scenario& sc) : sc_(sc) {}
  const PosedBlock& operator[](std::size_t k) {
    auto it = posed_.find(k);
    if (it == posed_.end()) it = posed_.emplace(k, posed_block(sc_.blocks[k])).first;
    return it->second;
  }

 private:
  const Scenario& sc_;
  std::unordered_map<std::size_t, PosedBlock> posed_;  // references stay valid as it grows
};

/// Pairs of blocks (i < j) whose bounding spheres' boxes overlap (a superset of the pairs that
/// touching() can find: it needs the centres within the sum of the radii), for which `want`
/// holds, sorted by (i, j).
template <class Want>
std::vector<std::pair<int, int>> near_pairs(const Scenario& sc, Want&& want) {
  const std::size_t n = sc.blocks.size();
  std::vector<Eigen::Vector3d> lo(n), hi(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Block& b = sc.blocks[k];
    // A little wider than the sphere, so that rounding never drops a pair at the limit.
    const double r = b.shape.bounding_radius() * (1.0 + 1e-9);
    lo[k] = b.position.array() - r;
    hi[k] = b.position.array() + r;
  }
  std::vector<std::pair<int, int>> pairs;
  UniformGrid().find_pairs(lo, hi, want, pairs);
  return pairs;
}

/// A block's contact planes: the faces it shares with blocks that stay (`neighbours`: the
/// candidates among them, in increasing index; their joint strengths area-weighted over its
/// neighbours on one plane), and two frictionless planes across each axis along which a roller
/// boundary blocks its translation.
std::vector<FoundPlane> contact_planes(const Scenario& sc, Poses& poses,
                                       const std::vector<int>& neighbours, std::size_t k) {
  const Block& b = sc.blocks[k];
  std::map<int, FoundPlane> by_plane;
  for (const int jj : neighbours) {
    const auto j = static_cast<std::size_t>(jj);
    if (j == k) continue;
    const auto face = touching(b, poses[k], sc.blocks[j], poses[j]);
    if (!face) continue;
    FoundPlane& f = by_plane[face->plane_a];
    f.plane = face->plane_a;
    f.contact.normal = face->normal;
    f.contact.area += face->area;
    const int law = contact_law(sc, k, j, *face);
    if (law < 0) continue;
    const JointStrength& s = strength_of(sc.joint_laws[static_cast<std::size_t>(law)].shear);
    f.friction_area += s.friction_coefficient * face->area;
    f.cohesion_area += s.cohesion * face->area;
  }
  std::vector<FoundPlane> out;
  for (auto& [plane, f] : by_plane) {
    f.contact.friction_coefficient = f.friction_area / f.contact.area;
    f.contact.cohesion = f.cohesion_area / f.contact.area;
    out.push_back(f);
  }
  for (int axis = 0; axis < 3; ++axis) {
    if (!b.blocked_translation(axis)) continue;
    for (const double sign : {1.0, -1.0}) {
      FoundPlane roller;
      roller.plane = -1 - axis;
      roller.contact.normal = sign * Eigen::Vector3d::Unit(axis);
      out.push_back(roller);
    }
  }
  return out;
}

/// One exposed block's entry, or null when gravity cannot move it into the opening.
nlohmann::json block_entry(const Scenario& sc, std::size_t k, const std::vector<FoundPlane>& found,
                           const Eigen::Vector3d& gravity, double required_factor,
                           const std::string& stage) {
  const Block& b = sc.blocks[k];
  std::vector<ContactPlane> planes;
  for (const FoundPlane& f : found) planes.push_back(f.contact);
  const double weight = b.mass * gravity.norm();
  const BlockEquilibrium eq = block_equilibrium(planes, gravity, weight);
  if (eq.mode == BlockMode::stable) return nullptr;
  nlohmann::json sliding = nlohmann::json::array();
  for (std::size_t m = 0; m < eq.planes.size(); ++m) {
    const std::size_t i = static_cast<std::size_t>(eq.planes[m]);
    const int plane = found[i].plane;
    std::string set;
    if (plane >= 0 && k < sc.face_sets.size() && !sc.face_sets[k].empty()) {
      const int s = sc.face_sets[k][static_cast<std::size_t>(plane)];
      if (s >= 0 && static_cast<std::size_t>(s) < sc.joint_sets.size())
        set = sc.joint_sets[static_cast<std::size_t>(s)];
    }
    const auto [dip, direction] = dip_of(planes[i].normal);
    sliding.push_back({{"contact", plane >= 0 ? "joint" : "roller"},
                       {"joint_set", set},
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
  const std::set<std::string> now_names(sc.stages[stage].remove.begin(),
                                        sc.stages[stage].remove.end());
  std::set<std::string> removed_names;
  for (std::size_t s = 0; s <= stage; ++s)
    removed_names.insert(sc.stages[s].remove.begin(), sc.stages[s].remove.end());
  const std::size_t n = sc.blocks.size();
  std::vector<char> now(n, 0), removed(n, 0);
  for (std::size_t k = 0; k < n; ++k) {
    now[k] = now_names.count(sc.blocks[k].name) > 0 ? 1 : 0;
    removed[k] = removed_names.count(sc.blocks[k].name) > 0 ? 1 : 0;
  }
  Poses poses(sc);
  // Exposed by this stage: a free block that stays and shares a face with a block this stage
  // removes (the candidates from a grid over the blocks' boxes, not every pair).
  std::vector<char> exposed(n, 0);
  const auto opened = [&](int i, int j) { return now[i] && !removed[j]; };
  for (const auto& [i, j] :
       near_pairs(sc, [&](int i, int j) { return opened(i, j) || opened(j, i); })) {
    const auto [r, k] = now[i] ? std::pair{i, j} : std::pair{j, i};
    const auto uk = static_cast<std::size_t>(k), ur = static_cast<std::size_t>(r);
    if (exposed[uk] || !sc.blocks[uk].is_dynamic()) continue;
    if (touching(sc.blocks[uk], poses[uk], sc.blocks[ur], poses[ur])) exposed[uk] = 1;
  }
  // The exposed blocks' neighbours that stay, each list in increasing index.
  std::map<std::size_t, std::vector<int>> neighbours;
  for (std::size_t k = 0; k < n; ++k)
    if (exposed[k]) neighbours[k];
  const auto beside = [&](int i, int j) { return exposed[i] && !removed[j]; };
  for (const auto& [i, j] :
       near_pairs(sc, [&](int i, int j) { return beside(i, j) || beside(j, i); })) {
    if (beside(i, j)) neighbours[static_cast<std::size_t>(i)].push_back(j);
    if (beside(j, i)) neighbours[static_cast<std::size_t>(j)].push_back(i);
  }
  for (auto& [k, list] : neighbours) {
    std::sort(list.begin(), list.end());
    nlohmann::json entry = block_entry(sc, k, contact_planes(sc, poses, list, k), gravity,
                                       required_factor, sc.stages[stage].name);
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

std::string removable_blocks_line(const nlohmann::json& removable) {
  std::string line = "  block theory: " + std::to_string(removable.size()) + " removable block" +
                     (removable.size() == 1 ? "" : "s");
  for (std::size_t k = 0; k < removable.size() && k < 3; ++k) {
    const nlohmann::json& b = removable[k];
    line += (k == 0 ? ": " : ", ") + b["block"].get<std::string>() + " " +
            b["mode"].get<std::string>() +
            " F = " + number_text(b["factor_of_safety"].get<double>(), "%.4g");
  }
  if (removable.size() > 3) line += ", ...";
  return line + " (summary.json, removable_blocks)";
}

std::string block_theory_check_line(const nlohmann::json& check) {
  return "  block theory: " + check["block"].get<std::string>() +
         " F = " + number_text(check["block_theory_factor"].get<double>(), "%.4g") +
         (check["agrees"].get<bool>() ? ", agrees" : ", differs") +
         " (summary.json, block_theory_check)";
}

}  // namespace blockdem
