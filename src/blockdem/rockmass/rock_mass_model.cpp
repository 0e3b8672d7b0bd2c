// Reading a scenario's rock mass (every key checked) and making its world blocks.
#include "blockdem/rockmass/rock_mass_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include <omp.h>

#include "blockdem/geometry/geometry_error.hpp"
#include "blockdem/numerics/shares.hpp"
#include "blockdem/numerics/units.hpp"
#include "blockdem/rockmass/excavation_shapes.hpp"
#include "blockdem/scenario/in_situ_input.hpp"

namespace blockdem {
namespace {

// "KEY: REASON" from the slicer or a validate() into (key, reason).
std::pair<std::string, std::string> split_message(const std::string& what) {
  const auto colon = what.find(": ");
  if (colon == std::string::npos) return {"", what};
  return {what.substr(0, colon), what.substr(colon + 2)};
}

int law_by_name(const CheckedTable& t, const std::string& key,
                const std::map<std::string, int>& laws) {
  if (!t.has(key)) return -1;
  const std::string name = t.string(key);
  const auto it = laws.find(name);
  if (it == laws.end()) t.fail(key, "no joint law named \"" + name + "\" in [[joint_laws]]");
  return it->second;
}

// The most planes of a region or an excavation: far more than a convex outline drawn by hand
// needs, and few enough for the outline's facets, each clipped by every other plane.
constexpr std::size_t kMaxOutlinePlanes = 1000;

// The rows of a plane list (`key`), at most kMaxOutlinePlanes.
std::vector<std::vector<double>> plane_rows(const CheckedTable& t, const std::string& key) {
  auto rows = t.rows(key, 4);
  if (rows.size() > kMaxOutlinePlanes)
    t.fail(key, "has " + std::to_string(rows.size()) + " planes, more than the limit of " +
                    std::to_string(kMaxOutlinePlanes));
  return rows;
}

Halfspace plane_row(const CheckedTable& t, const std::string& key, const std::vector<double>& r) {
  const Eigen::Vector3d n(r[0], r[1], r[2]);
  const double len = n.norm();
  if (!(len > 0.0)) t.fail(key, "a plane normal is the zero vector");
  return Halfspace{n / len, r[3] / len};
}

Region read_region(const CheckedTable& r) {
  const CheckedTable g = r.table("region");
  Region region;
  if (g.has("planes")) {
    if (g.has("min") || g.has("max")) g.fail("planes", "give either planes or min and max");
    std::vector<Halfspace> planes;
    for (const auto& row : plane_rows(g, "planes")) planes.push_back(plane_row(g, "planes", row));
    region = Region::from_planes(planes);
  } else {
    const Eigen::Vector3d lo = g.vec3("min"), hi = g.vec3("max");
    for (int i = 0; i < 3; ++i) {
      if (!(hi[i] > lo[i]))
        g.fail("max", "must exceed min along every axis (the region is not closed)");
    }
    region = Region::box(lo, hi);
  }
  g.finish();
  return region;
}

Spacing read_spacing(const CheckedTable& t) {
  Spacing s;
  if (!t.is_table("spacing")) {
    s.mean = t.number("spacing");
    return s;
  }
  const CheckedTable sp = t.table("spacing");
  s.mean = sp.number("mean");
  const std::string d =
      sp.choice("distribution", "constant", {"constant", "exponential", "normal", "lognormal"});
  s.distribution = d == "exponential" ? Spacing::Distribution::exponential
                   : d == "normal"    ? Spacing::Distribution::normal
                   : d == "lognormal" ? Spacing::Distribution::lognormal
                                      : Spacing::Distribution::constant;
  s.sd = sp.number("sd", 0.0);
  if (sp.has("seed")) s.seed = static_cast<std::uint64_t>(sp.integer("seed", 0));
  sp.finish();
  return s;
}

JointSet read_joint_set(const CheckedTable& t, std::size_t i, const Eigen::Vector3d& centre) {
  JointSet s;
  std::string fallback = "J";  // appended, not operator+ (GCC 12 -Wrestrict false positive)
  fallback.append(std::to_string(i + 1));
  s.name = t.string("name", fallback);
  s.dip_deg = t.number("dip_deg");
  s.dip_direction_deg = t.number("dip_direction_deg");
  s.origin = t.vec3("origin", centre);
  if (t.has("extent")) {
    const CheckedTable e = t.table("extent");
    JointExtent x;
    if (e.has("radius")) {
      if (e.has("size")) e.fail("size", "give either radius (a disc) or size (a rectangle)");
      x.radius = e.number("radius");
    } else {
      const auto size = e.numbers("size");
      if (size.size() != 2) e.fail("size", "must be two lengths [along strike, along dip]");
      x.shape = JointExtent::Shape::rectangle;
      x.size = Eigen::Vector2d(size[0], size[1]);
    }
    s.extent = x;
    if (e.has("centres")) {
      for (const auto& r : e.rows("centres", 3)) s.centres.emplace_back(r[0], r[1], r[2]);
    }
    if (e.has("seed")) s.placement_seed = static_cast<std::uint64_t>(e.integer("seed", 0));
    s.persistence = e.number("persistence", s.persistence);
    e.finish();
  }
  if (!(s.extent && !s.centres.empty()) || t.has("spacing")) s.spacing = read_spacing(t);
  try {
    s.validate();
  } catch (const std::invalid_argument& err) {
    const auto [key, why] = split_message(err.what());
    t.fail(key, why);
  }
  return s;
}

Excavation read_excavation(const CheckedTable& t, std::size_t i) {
  Excavation ex;
  std::string fallback = "excavation_";
  fallback.append(std::to_string(i + 1));
  ex.name = t.string("name", fallback);
  const std::string shape = t.choice("shape", "tunnel", {"tunnel", "box", "planes", "slope"});
  if (shape == "slope") {
    // A slope cut: the rock in front of a face through the toe line (dip, dip direction) and
    // above the toe's level. The face's normal out of the rock left standing is
    // (sin d sin a, sin d cos a, cos d) for dip d and dip direction a (x east, y north, z up).
    const Eigen::Vector3d toe = t.vec3("toe");
    const double dip = t.number("dip_deg");
    if (!(dip > 0.0 && dip <= 90.0)) t.fail("dip_deg", "must be in (0, 90]");
    const double dd = t.number("dip_direction_deg");
    if (!(dd >= 0.0 && dd < 360.0)) t.fail("dip_direction_deg", "must be in [0, 360)");
    const double d = dip * kPi / 180.0, a = dd * kPi / 180.0;
    const Eigen::Vector3d n(std::sin(d) * std::sin(a), std::sin(d) * std::cos(a), std::cos(d));
    ex.planes.push_back(Halfspace{-n, -n.dot(toe)});
    ex.planes.push_back(Halfspace{-Eigen::Vector3d::UnitZ(), -toe.z()});
  } else if (shape == "box") {
    const Eigen::Vector3d lo = t.vec3("min"), hi = t.vec3("max");
    for (int k = 0; k < 3; ++k) {
      if (!(hi[k] > lo[k])) t.fail("max", "must exceed min along every axis");
    }
    ex.planes = Region::box(lo, hi).planes;
  } else if (shape == "planes") {
    for (const auto& row : plane_rows(t, "planes"))
      ex.planes.push_back(plane_row(t, "planes", row));
    if (ex.planes.empty()) t.fail("planes", "needs at least one plane");
  } else {
    TunnelSpec tu;
    const std::string profile = t.choice("profile", "horseshoe", {"horseshoe", "circle"});
    tu.profile = profile == "circle" ? TunnelSpec::Profile::circle : TunnelSpec::Profile::horseshoe;
    tu.centre = t.vec3("centre");
    tu.radius = t.positive("radius", 0.0);
    tu.wall_height = t.positive("wall_height", tu.radius);
    tu.trend_deg = t.number("trend_deg", 0.0);
    if (!(tu.trend_deg >= 0.0 && tu.trend_deg < 360.0)) t.fail("trend_deg", "must be in [0, 360)");
    tu.plunge_deg = t.number("plunge_deg", 0.0);
    if (!(std::abs(tu.plunge_deg) < 90.0)) t.fail("plunge_deg", "must be in (-90, 90)");
    const std::int64_t sides = t.integer("sides", tu.sides);
    if (sides < 4 || sides > 256)
      t.fail("sides", "must be in [4, 256], got " + std::to_string(sides));
    tu.sides = static_cast<int>(sides);
    if (t.has("length")) tu.length = t.positive("length", 0.0);
    ex.planes = tunnel_planes(tu);
  }
  t.finish();
  return ex;
}

}  // namespace

std::string RockMassModel::block_name(std::size_t i) {
  return "rock_" + std::to_string(i + 1);
}

int RockMassModel::law_of(const FaceTag& tag) const {
  if (tag.source == FaceSource::region) return -1;
  if (tag.bonded && bonded_law >= 0) return bonded_law;
  if (tag.source == FaceSource::joint) return set_laws[tag.index];
  return -1;
}

std::string RockMassModel::label(const FaceTag& tag) const {
  switch (tag.source) {
    case FaceSource::region:
      return "region " + rock_mass.region_face_names[tag.index];
    case FaceSource::joint:
      return spec.joint_sets[tag.index].name + (tag.bonded ? " bonded" : "");
    case FaceSource::excavation:
      return "excavation " + spec.excavations[tag.index].name + (tag.bonded ? " bonded" : "");
  }
  return "";
}

RockMassModel read_rock_mass(const CheckedTable& root,
                             const std::map<std::string, double>& materials,
                             const std::map<std::string, int>& laws,
                             const std::optional<StressField>& in_situ, int cut_threads) {
  RockMassModel m;
  const CheckedTable r = root.table("rock_mass");
  m.spec.region = read_region(r);
  if (r.has("material")) {
    const std::string name = r.string("material");
    const auto it = materials.find(name);
    if (it == materials.end())
      r.fail("material", "no material named \"" + name + "\" in [[materials]]");
    if (r.has("density")) r.fail("density", "give either material or density, not both");
    m.density = it->second;
  } else {
    m.density = r.positive("density", 0.0);
  }
  m.group = r.string("group", m.group);
  SlicingSettings& s = m.spec.settings;
  s.min_block_volume = r.positive("min_block_volume", 0.0, true);
  s.max_aspect_ratio = r.positive("max_aspect_ratio", 0.0, true);
  s.small_blocks = r.choice("small_blocks", "merge", {"merge", "remove"}) == "remove"
                       ? SlicingSettings::SmallBlocks::remove
                       : SlicingSettings::SmallBlocks::merge;
  s.cut_tolerance = r.positive("cut_tolerance", 0.0, true);
  s.threads = cut_threads;
  s.max_blocks = r.integer("max_blocks", s.max_blocks);
  if (s.max_blocks < 1) r.fail("max_blocks", "must be at least 1");
  s.max_joints = r.integer("max_joints", s.max_joints);
  if (s.max_joints < 1) r.fail("max_joints", "must be at least 1");
  m.default_law = law_by_name(r, "law", laws);
  m.bonded_law = law_by_name(r, "bonded_law", laws);
  r.finish();

  // The region's centre: the default origin of a joint set.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  try {
    centre = Polyhedron::from_planes(m.spec.region.planes).centroid();
  } catch (const GeometryError& e) {
    root.fail("rock_mass.region",
              std::string("the region is not a closed convex solid: ") + e.what());
  }
  const auto sets = root.tables("joint_sets");
  for (std::size_t i = 0; i < sets.size(); ++i) {
    m.spec.joint_sets.push_back(read_joint_set(sets[i], i, centre));
    for (std::size_t k = 0; k < i; ++k) {
      if (m.spec.joint_sets[k].name == m.spec.joint_sets[i].name)
        sets[i].fail("name", "joint set \"" + m.spec.joint_sets[i].name +
                                 "\" is defined twice (also joint_sets[" + std::to_string(k + 1) +
                                 "]): faces and outputs name joints by their set");
    }
    m.set_laws.push_back(law_by_name(sets[i], "law", laws));
    sets[i].finish();
  }
  const auto exs = root.tables("excavations");
  for (std::size_t i = 0; i < exs.size(); ++i) {
    m.spec.excavations.push_back(read_excavation(exs[i], i));
    for (std::size_t k = 0; k < i; ++k) {
      if (m.spec.excavations[k].name == m.spec.excavations[i].name)
        exs[i].fail("name", "excavation \"" + m.spec.excavations[i].name + "\" is defined twice");
    }
  }
  for (const auto& b : root.tables("boundaries")) {
    BoundaryCondition bc;
    for (const auto& face : b.strings("faces")) {
      const auto& names = m.spec.region.face_names;
      const auto it = std::find(names.begin(), names.end(), face);
      if (it == names.end()) {
        std::string valid;
        for (const auto& n : names) valid += (valid.empty() ? "\"" : ", \"") + n + "\"";
        b.fail("faces", "the region has no face \"" + face + "\" (its faces: " + valid + ")");
      }
      bc.faces.push_back(static_cast<int>(it - names.begin()));
    }
    if (bc.faces.empty()) b.fail("faces", "name at least one region face");
    const std::string kind = b.choice("condition", "fixed", {"fixed", "roller", "stress"});
    bc.kind = kind == "roller"   ? BoundaryCondition::Kind::roller
              : kind == "stress" ? BoundaryCondition::Kind::stress
                                 : BoundaryCondition::Kind::fixed;
    if (b.has("stress")) {
      if (bc.kind != BoundaryCondition::Kind::stress)
        b.fail("stress", "a given stress needs condition = \"stress\"");
      bc.stress.stress = read_stress_tensor(b, "stress");
    } else if (bc.kind == BoundaryCondition::Kind::stress) {
      if (!in_situ)
        b.fail("condition",
               "a stress boundary takes the [in_situ] field's traction: give [in_situ], or a "
               "uniform stress = { xx = ..., ... } here");
      bc.stress = *in_situ;
    }
    if (bc.kind == BoundaryCondition::Kind::roller) {
      for (int f : bc.faces) {
        if (m.spec.region.planes[f].normal.cwiseAbs().maxCoeff() < 1.0 - 1e-12)
          b.fail("condition", "a roller needs a face normal to x, y or z");
      }
    }
    b.finish();
    m.boundaries.push_back(bc);
  }
  try {
    m.rock_mass = slice_rock_mass(m.spec);
  } catch (const std::invalid_argument& e) {
    auto [key, why] = split_message(e.what());
    if (key == "region" || key == "min_block_volume" || key == "max_aspect_ratio")
      key = "rock_mass." + key;
    root.fail(key, why);
  }
  if (m.rock_mass.blocks.empty()) root.fail("rock_mass", "no block is left after slicing");
  // A stress boundary loads the blocks on its faces: at least one must be there.
  for (std::size_t k = 0; k < m.boundaries.size(); ++k) {
    const BoundaryCondition& bc = m.boundaries[k];
    if (bc.kind != BoundaryCondition::Kind::stress) continue;
    bool touched = false;
    for (const auto& cell : m.rock_mass.blocks) {
      for (const auto& f : cell.faces()) {
        touched |= f.tag.source == FaceSource::region &&
                   std::find(bc.faces.begin(), bc.faces.end(), f.tag.index) != bc.faces.end();
      }
    }
    if (!touched)
      root.fail("boundaries[" + std::to_string(k + 1) + "].faces",
                "no block has a face on these region faces: a stress there would load nothing");
  }
  return m;
}

namespace {

// The traction -σ m of `field` over a block's face (outward normal m) as constant loads on the
// block: the force -∫ σ m dA and its moment about the block's centroid, exact for the field.
void add_boundary_traction(Block& b, const ConvexCell& cell, const CellFace& face,
                           const StressField& field) {
  const int f = static_cast<int>(&face - cell.faces().data());
  const std::vector<Eigen::Vector3d> polygon = cell.face_polygon(f);
  const FaceTraction t = face_traction(field, polygon, face.plane.normal);
  const Eigen::Vector3d force = -t.force;
  const Eigen::Vector3d moment = -((t.centroid - b.position).cross(t.force) + t.moment);
  b.set_external_force(b.external_force() + force);
  b.set_external_torque(b.external_torque() + moment);
}

// The world block of cell i, its faces' laws and joint sets (empty when none has one), in
// their places in `out`.
void make_one_block(const RockMassModel& m, std::size_t i, RockMassBlocks& out) {
  const ConvexCell& c = m.rock_mass.blocks[i];
  std::vector<Halfspace> planes;
  for (const auto& f : c.faces()) planes.push_back(f.plane);
  // A cell cut from the (closed) region is closed.
  Block b = make_block(Polyhedron::from_closed_planes(planes), m.density,
                       RockMassModel::block_name(i), m.group);
  // Each world plane of the block is one of the cell's faces: match by normal and offset.
  std::vector<int> laws(b.world_planes.size(), -1);
  std::vector<int> sets(b.world_planes.size(), -1);
  const double scale = 1e-9 * (1.0 + b.position.norm() + b.shape.bounding_radius());
  for (std::size_t j = 0; j < b.world_planes.size(); ++j) {
    const Halfspace& h = b.world_planes[j];
    for (const auto& f : c.faces()) {
      if (h.normal.dot(f.plane.normal) > 1.0 - 1e-9 &&
          std::abs(h.offset - f.plane.offset) < scale) {
        laws[j] = m.law_of(f.tag);
        if (f.tag.source == FaceSource::joint) sets[j] = f.tag.index;
        break;
      }
    }
  }
  for (const auto& bc : m.boundaries) {
    for (const auto& f : c.faces()) {
      if (f.tag.source != FaceSource::region ||
          std::find(bc.faces.begin(), bc.faces.end(), f.tag.index) == bc.faces.end())
        continue;
      if (bc.kind == BoundaryCondition::Kind::fixed) {
        b.motion = Motion::fixed;
      } else if (bc.kind == BoundaryCondition::Kind::stress) {
        add_boundary_traction(b, c, f, bc.stress);
      } else {
        Eigen::Index axis = 0;
        f.plane.normal.cwiseAbs().maxCoeff(&axis);
        b.blocked_translation[axis] = true;
        b.blocked_rotation.setConstant(true);
      }
    }
  }
  const bool any_law = std::any_of(laws.begin(), laws.end(), [](int l) { return l >= 0; });
  if (any_law) out.face_laws[i] = std::move(laws);
  const bool any_set = std::any_of(sets.begin(), sets.end(), [](int k) { return k >= 0; });
  if (any_set) out.face_sets[i] = std::move(sets);
  out.blocks[i] = std::move(b);
}

}  // namespace

RockMassBlocks make_rock_mass_blocks(const RockMassModel& m, int threads) {
  if (threads <= 0) threads = omp_get_max_threads();
  const auto count = static_cast<std::int64_t>(m.rock_mass.blocks.size());
  // Each thread makes contiguous shares of the blocks, several per thread, in their places: the
  // blocks are those of one thread. A share's error is kept, and the first share's thrown (one
  // thread's error).
  RockMassBlocks out;
  out.blocks.resize(static_cast<std::size_t>(count));
  out.face_laws.resize(static_cast<std::size_t>(count));
  out.face_sets.resize(static_cast<std::size_t>(count));
  for_each_share(share_count(count, threads, 64), count, threads,
                 [&](std::int64_t, std::int64_t begin, std::int64_t end) {
                   for (auto i = static_cast<std::size_t>(begin); i < static_cast<std::size_t>(end);
                        ++i)
                     make_one_block(m, i, out);
                 });
  for (std::size_t e = 0; e < m.spec.excavations.size(); ++e) {
    auto& names = out.excavated[m.spec.excavations[e].name];
    for (int i : m.rock_mass.blocks_inside(m.spec, static_cast<int>(e)))
      names.push_back(RockMassModel::block_name(static_cast<std::size_t>(i)));
  }
  return out;
}

}  // namespace blockdem
