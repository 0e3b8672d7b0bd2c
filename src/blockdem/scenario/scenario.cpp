// Scenario file reader: every key checked, every value validated, errors name file and key
// (the world it describes is built in build_world.cpp).
#include "blockdem/scenario/scenario.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>
#include <utility>

#include "blockdem/collision/boon2012.hpp"
#include "blockdem/geometry/geometry_error.hpp"
#include "blockdem/numerics/units.hpp"
#include "blockdem/scenario/base_motion_input.hpp"
#include "blockdem/scenario/bolt_input.hpp"
#include "blockdem/scenario/in_situ_input.hpp"
#include "blockdem/scenario/stage_input.hpp"
#include "blockdem/scenario/water_input.hpp"
#include "blockdem/world/contact_mode.hpp"
#include "blockdem/world/stability.hpp"

namespace blockdem {
namespace {

void read_settings(const CheckedTable& t, WorldSettings& s, bool& allow_initial_overlap) {
  s.gravity = t.vec3("gravity", s.gravity);
  s.damping = t.number("damping", s.damping);
  if (!(s.damping >= 0.0 && s.damping < 1.0)) t.fail("damping", "must be in [0, 1)");
  // Viscous contact damping: the fraction of critical damping of each contact's dashpot.
  s.contact_damping = t.number("contact_damping", s.contact_damping);
  if (!(s.contact_damping >= 0.0 && s.contact_damping < 1.0))
    t.fail("contact_damping", "must be a fraction of critical damping in [0, 1)");
  // "auto" (the default) or a positive number of seconds.
  if (t.is_string("time_step")) {
    if (t.string("time_step") != "auto")
      t.fail("time_step", "must be \"auto\" or a positive number of seconds");
  } else if (t.has("time_step")) {
    s.time_step = t.positive("time_step", 0.0);
  }
  s.safety_factor = t.positive("safety_factor", s.safety_factor);
  if (s.safety_factor > 1.0) t.fail("safety_factor", "must be at most 1");
  s.contact_mode = *parse_contact_mode(
      t.choice("contact_mode", to_string(s.contact_mode), contact_mode_names()));
  const double face_angle_deg = t.positive("face_angle_deg", rad_to_deg(s.face_contact.face_angle));
  if (face_angle_deg >= 45.0) t.fail("face_angle_deg", "must be below 45 degrees");
  s.face_contact.face_angle = deg_to_rad(face_angle_deg);
  s.boon2012.rounding_distance = t.positive("rounding_distance", s.boon2012.rounding_distance);
  s.boon2012.overlap_tolerance =
      t.positive("overlap_tolerance", s.boon2012.overlap_tolerance, true);
  // Twisting resistance of the joints: default on in face_integrated, off in boon2012.
  if (t.has("twist")) s.twist = t.boolean("twist", s.twist_enabled());
  s.max_speed = t.positive("max_speed", s.max_speed);
  s.max_overlap_fraction = t.positive("max_overlap_fraction", s.max_overlap_fraction);
  // A divergence checkpoint larger than this (MiB) is kept in a scratch file; 0: always.
  const double checkpoint_mib = t.positive(
      "checkpoint_memory_mib", static_cast<double>(s.checkpoint_memory_limit) / 1048576.0, true);
  if (checkpoint_mib > 1e9) t.fail("checkpoint_memory_mib", "must be at most 1e9 (MiB)");
  s.checkpoint_memory_limit = static_cast<std::size_t>(checkpoint_mib * 1048576.0);
  allow_initial_overlap = t.choice("initial_overlap", "refuse", {"refuse", "allow"}) == "allow";
  // Ground water from the start (a stage may set another table or make the model dry).
  s.water = read_water(t, false).water;
  t.finish();
}

Eigen::Matrix3d read_rotation(const CheckedTable& t) {
  if (!t.has("rotation_deg") && !t.has("rotation_axis")) return Eigen::Matrix3d::Identity();
  const double angle = t.number("rotation_deg", 0.0);
  const Eigen::Vector3d axis = t.vec3("rotation_axis", Eigen::Vector3d::UnitZ());
  if (!(axis.norm() > 0.0) || !std::isfinite(axis.norm()))
    t.fail("rotation_axis", "must be a non-zero vector of finite length");
  return Eigen::AngleAxisd(deg_to_rad(angle), axis.normalized()).toRotationMatrix();
}

/// Box blocks already made, by the bits of (size, rotation, density): identical boxes are built
/// once (vertex enumeration, principal axes) and share one body-frame shape. The key is the exact
/// bit pattern, so a block from the cache is the block the computation would give.
using BoxKey = std::array<std::uint64_t, 13>;
using BoxCache = std::map<BoxKey, Block>;

BoxKey box_key(const Eigen::Vector3d& size, const Eigen::Matrix3d& rot, double density) {
  BoxKey k{};
  for (int i = 0; i < 3; ++i)
    k[static_cast<std::size_t>(i)] = std::bit_cast<std::uint64_t>(size[i]);
  for (int i = 0; i < 9; ++i)
    k[static_cast<std::size_t>(3 + i)] = std::bit_cast<std::uint64_t>(rot.data()[i]);
  k[12] = std::bit_cast<std::uint64_t>(density);
  return k;
}

Block read_block(const CheckedTable& t, const std::map<std::string, double>& materials,
                 BoxCache& boxes) {
  const std::string name = t.string("name");
  const std::string group = t.string("group", "default");
  double density = 0.0;
  if (t.has("material")) {
    const std::string m = t.string("material");
    auto it = materials.find(m);
    if (it == materials.end())
      t.fail("material", "no material named \"" + m + "\" in [[materials]]");
    density = it->second;
    if (t.has("density")) t.fail("density", "give either material or density, not both");
  } else {
    density = t.positive("density", 0.0);
  }
  const std::string shape = t.choice("shape", "box", {"box", "planes", "vertices"});
  const Eigen::Matrix3d rot = read_rotation(t);
  const Eigen::Vector3d pos = t.vec3("position", Eigen::Vector3d::Zero());
  Polyhedron poly;
  const Block* made = nullptr;  // an identical box made before
  BoxKey key{};
  try {
    if (shape == "box") {
      const Eigen::Vector3d size = t.vec3("size");
      for (int i = 0; i < 3; ++i) {
        if (!(size[i] > 0.0)) t.fail("size", "box sides must be positive");
      }
      key = box_key(size, rot, density);
      const auto it = boxes.find(key);
      if (it != boxes.end()) {
        made = &it->second;
      } else {
        poly = Polyhedron::box(size);
      }
    } else if (shape == "planes") {
      std::vector<Halfspace> planes;
      for (const auto& r : t.rows("planes", 4)) {
        Eigen::Vector3d n(r[0], r[1], r[2]);
        const double len = n.norm();
        if (!(len > 0.0)) t.fail("planes", "a plane normal is the zero vector");
        // Normals given with any length are normalised, offsets scaled with them.
        planes.push_back(Halfspace{n / len, r[3] / len});
      }
      poly = Polyhedron::from_planes(planes);
    } else {
      std::vector<Eigen::Vector3d> pts;
      for (const auto& r : t.rows("vertices", 3)) pts.emplace_back(r[0], r[1], r[2]);
      // Two vertices at one point are a typing error, not a shape (the hull would hide it).
      double extent = 0.0;
      for (const auto& p : pts) extent = std::max(extent, p.cwiseAbs().maxCoeff());
      for (std::size_t i = 0; i < pts.size(); ++i) {
        for (std::size_t j = 0; j < i; ++j) {
          if ((pts[i] - pts[j]).norm() <= 1e-12 * std::max(extent, 1e-300))
            t.fail("vertices",
                   "vertex " + std::to_string(i + 1) + " repeats vertex " + std::to_string(j + 1));
        }
      }
      poly = Polyhedron::from_vertices(pts);
    }
  } catch (const GeometryError& e) {
    t.fail(shape == "box" ? "size" : shape, e.what());
  }
  // Box: `position` is its centre. Planes/vertices: the shape is rotated about the origin of
  // its own coordinates, then moved by `position`. A shape that positioning makes degenerate
  // (coordinates so large that the block's size is lost in round-off) is an input error.
  if (!(pos.cwiseAbs().maxCoeff() < 1e12))
    t.fail("position", "must be finite and within 1e12 m of the origin");
  Block b;
  try {
    // The mass properties come from the shape in its own coordinates, then the block is moved:
    // its body frame does not depend on where it sits (full precision far from the origin).
    if (made) {
      b = *made;
      b.name = name;
      b.set_group(group);
    } else {
      poly = poly.transformed(rot, Eigen::Vector3d::Zero());
      b = make_block(poly, density, name, group);
      if (shape == "box") boxes.emplace(key, b);
    }
    b.position += pos;
    b.initial_position = b.position;
  } catch (const GeometryError& e) {
    t.fail("position", "block \"" + name + "\" is degenerate once positioned: " + e.what());
  }

  const std::string motion = t.choice("motion", "free", {"free", "fixed", "prescribed", "servo"});
  b.set_external_force(t.vec3("external_force", Eigen::Vector3d::Zero()));
  b.set_external_torque(t.vec3("external_torque", Eigen::Vector3d::Zero()));
  b.velocity = t.vec3("velocity", Eigen::Vector3d::Zero());
  b.angular_velocity = t.vec3("angular_velocity", Eigen::Vector3d::Zero());
  if (motion == "fixed") {
    b.motion = Motion::fixed;
    if (t.has("velocity") || t.has("angular_velocity")) {
      t.fail("velocity", "a fixed block cannot have a velocity (use motion = \"prescribed\")");
    }
  } else if (motion == "prescribed") {
    b.motion = Motion::prescribed;
  } else if (motion == "servo") {
    b.motion = Motion::servo;
    const CheckedTable s = t.table("servo");
    const Eigen::Vector3d axis = s.vec3("axis");
    if (!(axis.norm() > 0.0) || !std::isfinite(axis.norm()))
      s.fail("axis", "must be a non-zero vector of finite length");
    Servo& servo = b.edit_servo();
    servo.axis = axis.normalized();
    servo.target_force = s.positive("target_force", 0.0, true);
    servo.gain = s.positive("gain", 0.0, true);
    servo.max_speed = s.positive("max_speed", 0.0, true);
    servo.tolerance = s.positive("tolerance", servo.tolerance);
    s.finish();
  } else {
    b.motion = Motion::free;
  }
  for (const auto& dof : t.strings("blocked_dofs")) {
    static const std::vector<std::string> names = {"x", "y", "z", "rx", "ry", "rz"};
    const auto it = std::find(names.begin(), names.end(), dof);
    if (it == names.end())
      t.fail("blocked_dofs", "unknown degree of freedom \"" + dof + "\" (use x, y, z, rx, ry, rz)");
    const int k = static_cast<int>(it - names.begin());
    if (k < 3) {
      b.blocked_translation[k] = true;
    } else {
      b.blocked_rotation[k - 3] = true;
    }
  }
  if (motion != "servo" && t.has("servo"))
    t.fail("servo", "only a block with motion = \"servo\" takes a servo table");
  t.finish();
  return b;
}

/// The blocks of a file's [[blocks]] list, with their names and groups.
struct ListedBlocks {
  std::vector<Block> blocks;
  std::set<std::string> names, groups;
};

/// Reads one [[blocks]] table and appends its block, without world planes (see the end of
/// read_scenario).
void read_listed_block(const CheckedTable& bt, const std::map<std::string, double>& materials,
                       BoxCache& boxes, ListedBlocks& listed) {
  Block b = read_block(bt, materials, boxes);
  if (listed.names.count(b.name)) bt.fail("name", "block \"" + b.name + "\" is defined twice");
  listed.names.insert(b.name);
  listed.groups.insert(b.group());
  std::vector<Halfspace>().swap(b.world_planes);
  listed.blocks.push_back(std::move(b));
}

std::map<std::string, double> read_materials(const CheckedTable& t) {
  std::map<std::string, double> materials;
  for (const auto& m : t.tables("materials")) {
    const std::string name = m.string("name");
    if (materials.count(name)) m.fail("name", "material \"" + name + "\" is defined twice");
    materials[name] = m.positive("density", 0.0);
    m.finish();
  }
  return materials;
}

}  // namespace

void read_joint_law_tables(const CheckedTable& t, JointLaw& law) {
  {
    const CheckedTable n = t.table("normal");
    const std::string kind = n.string("law");
    const std::string preset = n.string("preset", "");
    try {
      law.normal = normal_law_from_params(kind, n.numbers_except({"law", "preset"}), preset);
    } catch (const std::invalid_argument& e) {
      n.fail("law", e.what());
    }
    n.finish();
  }
  {
    const CheckedTable s = t.table("shear");
    const std::string kind = s.string("law");
    try {
      law.shear = shear_law_from_params(kind, s.numbers_except({"law"}));
    } catch (const std::invalid_argument& e) {
      s.fail("law", e.what());
    }
    s.finish();
  }
}

void read_output(const CheckedTable& o, OutputSpec& output) {
  output.vtk = o.boolean("vtk", output.vtk);
  output.vtk_interval = o.integer("vtk_interval", output.vtk_interval);
  if (output.vtk_interval < 0) o.fail("vtk_interval", "must be 0 (stage ends only) or positive");
  output.history_interval = o.integer("history_interval", output.history_interval);
  if (output.history_interval <= 0) o.fail("history_interval", "must be a positive step count");
  output.history_interval_s = o.positive("history_interval_s", 0.0, true);
  output.history_max_rows = o.integer("history_max_rows", output.history_max_rows);
  if (output.history_max_rows < 2) o.fail("history_max_rows", "must be at least 2");
  if (o.has("history_blocks")) output.history_blocks = o.strings("history_blocks");
  if (o.has("history_bolts")) output.history_bolts = o.strings("history_bolts");
  o.finish();
}

namespace {

JointLaw read_joint_law(const CheckedTable& t) {
  JointLaw law;
  law.name = t.string("name");
  read_joint_law_tables(t, law);
  t.finish();
  return law;
}

// Checks what depends on the blocks' sizes, and warns of values off by orders of magnitude.
void check_block_scales(Scenario& sc) {
  const double r_round = sc.settings.boon2012.rounding_distance;
  for (const Block& b : sc.blocks) {
    // The rounded normal moves every face inward by r_round: the block must keep a core. The
    // smallest distance from the centroid to a face bounds the inscribed ball from below.
    double inner = std::numeric_limits<double>::infinity();
    for (const auto& p : b.shape.planes()) inner = std::min(inner, p.offset);
    if (!(r_round < inner)) {
      std::ostringstream s;
      s << "must be smaller than every block's half-thickness; block \"" << b.name
        << "\" has a face " << inner
        << " m from its centroid (the paper used 0.2 mm on 46 mm blocks)";
      throw ScenarioError(sc.file, "settings.rounding_distance", s.str());
    }
    if (b.motion == Motion::free && (b.density < 100.0 || b.density > 30000.0)) {
      std::ostringstream s;
      s << "block \"" << b.name << "\": density " << b.density
        << " kg/m^3 is far from any rock's (about 1000 to 5000 kg/m^3): check the unit";
      sc.warnings.push_back(s.str());
    }
    const double size = b.shape.bounding_radius();
    if (size < 1e-4 || size > 1e4) {
      std::ostringstream s;
      s << "block \"" << b.name << "\" is " << 2.0 * size
        << " m across: check the unit of its size (metres)";
      sc.warnings.push_back(s.str());
    }
  }
}

// True for a rectangular box in any orientation: six faces whose normals are pairwise opposite
// or perpendicular (to 1e-9).
bool is_box(const Polyhedron& shape) {
  const auto& planes = shape.planes();
  if (planes.size() != 6) return false;
  for (std::size_t i = 0; i < planes.size(); ++i) {
    for (std::size_t j = i + 1; j < planes.size(); ++j) {
      const double c = std::abs(planes[i].normal.dot(planes[j].normal));
      if (c > 1e-9 && c < 1.0 - 1e-9) return false;
    }
  }
  return true;
}

// A strength-reduction or collapse search in mode boon2012 on blocks other than boxes: the point
// contact puts the force of a contact patch of any other shape off the patch's centroid, which can
// jam a key block against a joint it would leave and overestimate its factor of safety, on the
// unsafe side (docs/stability.md, "Contact mode"). Warned once, naming the first such stage and
// block.
void warn_point_contact_searches(Scenario& sc) {
  if (sc.settings.contact_mode != ContactMode::boon2012) return;
  const auto search = std::find_if(sc.stages.begin(), sc.stages.end(), [](const Stage& st) {
    return st.kind == Stage::Kind::strength_reduction ||
           (st.find_collapse && st.kind == Stage::Kind::equilibrium);
  });
  if (search == sc.stages.end()) return;
  const auto block = std::find_if(sc.blocks.begin(), sc.blocks.end(), [](const Block& b) {
    return b.motion == Motion::free && !is_box(b.shape);
  });
  if (block == sc.blocks.end()) return;
  sc.warnings.push_back(
      "stage \"" + search->name + "\" searches for " +
      (search->kind == Stage::Kind::strength_reduction ? "a factor of safety" : "a collapse load") +
      " with contact_mode = \"boon2012\" on blocks that are not boxes (block \"" + block->name +
      "\"): the point contact can jam a key block against a joint it would leave and overestimate "
      "its stability; contact_mode = \"face_integrated\" integrates the joint law over the "
      "contact (docs/stability.md, \"Contact mode\")");
}

}  // namespace

namespace {

/// The [[joints]] rules: which law acts between which block groups (one law and no rules: it
/// acts between all blocks).
void read_joint_rules(const CheckedTable& t, const std::set<std::string>& groups,
                      const std::map<std::string, int>& law_index, Scenario& sc) {
  for (const auto& jt : t.tables("joints")) {
    JointRule r;
    const auto g = jt.strings("groups");
    if (g.size() != 2)
      jt.fail("groups", "must name two block groups, e.g. [\"beam\", \"abutment\"]");
    for (const auto& name : g) {
      if (!name.empty() && !groups.count(name))
        jt.fail("groups", "no block is in group \"" + name + "\"");
    }
    r.group_a = g[0];
    r.group_b = g[1];
    const std::string law = jt.string("law");
    auto it = law_index.find(law);
    if (it == law_index.end())
      jt.fail("law", "no joint law named \"" + law + "\" in [[joint_laws]]");
    r.law = it->second;
    jt.finish();
    sc.joint_rules.push_back(r);
  }
  if (sc.joint_rules.empty() && sc.joint_laws.size() == 1) {
    // One law and no rules: it acts between all blocks.
    sc.joint_rules.push_back(JointRule{"", "", 0});
  }
  if (sc.joint_rules.empty() && sc.blocks.size() > 1) {
    t.fail("joints",
           "several joint laws and no [[joints]] rule saying which acts between which groups");
  }
}

/// A strength-reduction stage's laws: each named one exists, and at least one chosen law has a
/// strength (friction) to divide.
void check_reduced_laws(const CheckedTable& st, const Stage& stage,
                        const std::map<std::string, int>& law_index,
                        const std::vector<JointLaw>& laws) {
  bool strength = false;
  for (const auto& name : stage.strength.laws) {
    if (!law_index.count(name)) {
      std::string known;
      for (const auto& [n, i] : law_index) known += (known.empty() ? "" : ", ") + n;
      st.fail("laws", "no joint law named \"" + name + "\" (known: " + known + ")");
    }
  }
  for (const auto& law : laws) {
    const bool chosen = stage.strength.laws.empty() ||
                        std::find(stage.strength.laws.begin(), stage.strength.laws.end(),
                                  law.name) != stage.strength.laws.end();
    if (chosen && has_strength(law)) strength = true;
  }
  if (!strength) st.fail("laws", "no chosen joint law has a friction or strength to reduce");
}

/// A scene at map coordinates (centre farther than 10 km from the origin) is simulated relative
/// to its centre rounded to the metre: subtracting it is exact (Sterbenz), and contacts keep the
/// precision they have at the origin. Outputs add it back. Scenes nearer keep origin 0.
void shift_to_local_origin(Scenario& sc) {
  if (sc.blocks.empty()) return;
  Eigen::Vector3d lo = sc.blocks[0].position, hi = lo;
  for (const auto& b : sc.blocks) {
    lo = lo.cwiseMin(b.position);
    hi = hi.cwiseMax(b.position);
  }
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  if (centre.cwiseAbs().maxCoeff() <= 1e4) return;
  sc.settings.origin = centre.array().round().matrix();
  if (sc.in_situ) sc.in_situ = sc.in_situ->shifted_by(sc.settings.origin);
  if (sc.settings.water)
    sc.settings.water->table = sc.settings.water->table.shifted_by(sc.settings.origin);
  for (Stage& st : sc.stages) {
    if (st.water) st.water->table = st.water->table.shifted_by(sc.settings.origin);
    for (BoltSpec& bolt : st.bolts) bolt.start -= sc.settings.origin;
  }
  for (auto& b : sc.blocks) {
    b.position -= sc.settings.origin;
    b.initial_position -= sc.settings.origin;
    b.update_world_geometry();
  }
}

/// Reads a scenario from the TOML tree of its file. `listed`: the blocks of its [[blocks]] list,
/// read already (the tree holds an empty list in their place), or null to read them from the tree.
Scenario read_scenario(const toml::table& root, const std::string& file,
                       const SceneBuilders& builders, ListedBlocks* listed) {
  const CheckedTable t(root, file, "");
  Scenario sc;
  sc.file = file;
  sc.title = t.string("title", "");
  if (t.has("settings")) read_settings(t.table("settings"), sc.settings, sc.allow_initial_overlap);

  // At most one scene builder; the keys it builds itself must not stand beside it.
  const SceneBuilder* builder = nullptr;
  for (const SceneBuilder* candidate : builders) {
    if (!t.has(candidate->table())) continue;
    if (builder)
      t.fail(candidate->table(),
             "a scenario takes one builder table; [" + builder->table() + "] is given too");
    builder = candidate;
  }
  if (builder) {
    for (const auto& key : builder->replaces()) {
      if (t.has(key))
        t.fail(key, "a [" + builder->table() +
                        "] scenario builds its own blocks, laws and stages; remove this");
    }
  }

  sc.materials = read_materials(t);
  // Before the scene is built: a rock mass's stress boundaries may take the field's traction.
  if (t.has("in_situ"))
    sc.in_situ = read_in_situ(t.table("in_situ"), sc.settings.gravity, sc.materials);

  std::map<std::string, int> law_index;
  for (const auto& l : t.tables("joint_laws")) {
    JointLaw law = read_joint_law(l);
    if (law_index.count(law.name))
      l.fail("name", "joint law \"" + law.name + "\" is defined twice");
    law_index[law.name] = static_cast<int>(sc.joint_laws.size());
    sc.joint_laws.push_back(std::move(law));
  }

  // One block's reader at a time, and without world planes (see the end): the set-up of a long
  // list holds its blocks, not a reader and six planes per block as well.
  ListedBlocks from_tree;
  if (!listed) {
    listed = &from_tree;
    BoxCache boxes;
    listed->blocks.reserve(t.table_count("blocks"));
    t.for_each_table("blocks", [&](const CheckedTable& bt) {
      read_listed_block(bt, sc.materials, boxes, *listed);
    });
  } else {
    t.for_each_table("blocks", [](const CheckedTable&) {});  // the empty list in their place
  }
  sc.blocks = std::move(listed->blocks);
  std::set<std::string> names = std::move(listed->names), groups = std::move(listed->groups);
  if (builder) {
    builder->build_from_root(t, sc);
    for (std::size_t i = 0; i < sc.blocks.size(); ++i) {
      names.insert(sc.blocks[i].name);
      groups.insert(sc.blocks[i].group());
    }
  }
  if (sc.blocks.empty()) t.fail("blocks", "a scenario needs at least one [[blocks]] entry");
  check_block_scales(sc);

  read_joint_rules(t, groups, law_index, sc);

  // The free blocks no stage has removed yet: with an automatic time step, a stage needs one.
  std::set<std::string> free_left;
  for (const auto& b : sc.blocks) {
    if (b.motion == Motion::free || b.motion == Motion::servo) free_left.insert(b.name);
  }
  for (const auto& st : t.tables("stages")) {
    sc.stages.push_back(read_stage(st, names, sc.excavations, {law_index, sc.joint_sets, groups}));
    const Stage& stage = sc.stages.back();
    const std::size_t free_before = free_left.size();
    for (const auto& name : stage.remove) free_left.erase(name);
    if (free_left.empty() && free_before > 0 && sc.settings.time_step == 0.0)
      st.fail("excavation",
              "removes every free block left (" + std::to_string(free_before) +
                  "): every block left is fixed or prescribed, so nothing can move "
                  "and no automatic time step exists (fix fewer region faces, excavate less, or "
                  "set [settings] time_step)");
    if (stage.kind != Stage::Kind::strength_reduction) continue;
    check_reduced_laws(st, stage, law_index, sc.joint_laws);
  }
  read_bolts(t, sc);
  add_elastic_twins(sc);
  warn_point_contact_searches(sc);
  finish_dynamic_stages(sc);
  if (sc.in_situ && sc.settings.contact_mode == ContactMode::boon2012)
    sc.warnings.push_back(
        "[in_situ] with contact_mode = \"boon2012\": the point contact carries each face's "
        "in-situ normal force at its analytic centre, off the centroid of an irregular face, so "
        "the blocks start with unbalanced moments; contact_mode = \"face_integrated\" carries "
        "the field exactly (docs/ground-stress.md)");
  if (t.has("output")) read_output(t.table("output"), sc.output);
  for (const auto& name : sc.output.history_bolts) {
    const bool known = std::any_of(sc.stages.begin(), sc.stages.end(), [&](const Stage& st) {
      return std::any_of(st.bolts.begin(), st.bolts.end(),
                         [&](const BoltSpec& b) { return b.name == name; });
    });
    if (!known) t.fail("output.history_bolts", "no bolt named '" + name + "'");
  }
  // Unknown keys first: a misspelt [[stages]] is named as such.
  t.finish();
  // A built scene without stages can be generated (blockdem generate), not run.
  if (sc.stages.empty() && !sc.built)
    t.fail("stages", "a scenario needs at least one [[stages]] entry");
  shift_to_local_origin(sc);
  // The scenario's blocks are the recipe of a world: World::add_block derives each block's world
  // planes again, so these copies do not keep theirs (the shapes are shared, not copied).
  for (auto& b : sc.blocks) std::vector<Halfspace>().swap(b.world_planes);
  return sc;
}

/// The offsets of the lines of `text` that are exactly "[[blocks]]" (a header of the list of
/// blocks, or a line inside a multi-line string or array: see read_listed_blocks_apart).
std::vector<std::size_t> block_header_lines(std::string_view text) {
  constexpr std::string_view header = "[[blocks]]";
  std::vector<std::size_t> lines;
  for (std::size_t at = text.find(header); at != std::string_view::npos;
       at = text.find(header, at + header.size())) {
    const std::size_t end = at + header.size();
    const bool line_start = at == 0 || text[at - 1] == '\n';
    const bool line_end = end == text.size() || text[end] == '\n' ||
                          (text[end] == '\r' && end + 1 < text.size() && text[end + 1] == '\n');
    if (line_start && line_end) lines.push_back(at);
  }
  return lines;
}

/// The [[blocks]] tables parsed into one TOML tree at a time: enough that a tree costs little
/// per table, few enough that the tree (~1.2 KB per table) is small beside the blocks.
constexpr std::size_t kBlocksPerTree = 1024;

/// Reads a file with a [[blocks]] list without holding the TOML tree of the whole list (~1.2 KB
/// per block, twice the block read from it): the text is parsed in pieces, the part before the
/// first "[[blocks]]" line and then a run of [[blocks]] tables at a time, each piece's blocks
/// read and its tree freed before the next is parsed. Keys other than `blocks` at a piece's top
/// level (a table after the list) are moved into the first piece's tree.
///
/// Each piece starts at a "[[blocks]]" line, which is a header of the list when no multi-line
/// string is open there (the text holds no three quotes in a row) and no multi-line array (the
/// piece before would not parse). A piece's keys are then its own tables', so when every piece
/// parses and no top-level key but `blocks` is in two pieces, the pieces' trees are the whole
/// file's tree cut apart. Returns nothing when the file does not qualify, and throws whatever
/// reading the pieces throws: the caller then reads the whole tree, which gives every error
/// exactly as before (its message, its line numbers, and which of several comes first).
std::optional<Scenario> read_listed_blocks_apart(std::string_view text, const std::string& file,
                                                 const SceneBuilders& builders) {
  const std::vector<std::size_t> headers = block_header_lines(text);
  if (headers.empty() || text.find("\"\"\"") != std::string_view::npos ||
      text.find("'''") != std::string_view::npos)
    return std::nullopt;
  toml::table root = toml::parse(text.substr(0, headers[0]), file);
  if (root.contains("blocks")) return std::nullopt;
  // The blocks need the [[materials]]. A later piece that brings some has a key of the first
  // piece when that holds materials; when it holds none, every block naming one fails here.
  const std::map<std::string, double> materials = read_materials(CheckedTable(root, file, ""));
  ListedBlocks listed;
  listed.blocks.reserve(headers.size());
  BoxCache boxes;
  for (std::size_t first = 0; first < headers.size(); first += kBlocksPerTree) {
    const std::size_t begin = headers[first];
    const std::size_t end =
        first + kBlocksPerTree < headers.size() ? headers[first + kBlocksPerTree] : text.size();
    toml::table piece = toml::parse(text.substr(begin, end - begin), file);
    for (auto&& [key, node] : piece) {
      if (key == "blocks") continue;
      if (root.contains(key.str())) return std::nullopt;
      root.insert(key, std::move(node));
    }
    CheckedTable(piece, file, "").for_each_table("blocks", [&](const CheckedTable& bt) {
      read_listed_block(bt, materials, boxes, listed);
    });
  }
  root.insert("blocks", toml::array{});
  return read_scenario(root, file, builders, &listed);
}

/// parse_scenario's reading (Scenario::text apart).
Scenario parse_scenario_text(const std::string& text, const std::string& file,
                             const SceneBuilders& builders) {
  try {
    if (auto sc = read_listed_blocks_apart(text, file, builders)) return std::move(*sc);
  } catch (...) {
    // The whole tree is read below: its error is the file's.
  }
  toml::table root;
  try {
    root = toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    std::ostringstream where;
    where << "line " << e.source().begin.line << ", column " << e.source().begin.column;
    throw ScenarioError(
        file, "", "TOML syntax error at " + where.str() + ": " + std::string(e.description()));
  }
  return read_scenario(root, file, builders, nullptr);
}

}  // namespace

Scenario parse_scenario(const std::string& text, const std::string& file,
                        const SceneBuilders& builders) {
  Scenario sc = parse_scenario_text(text, file, builders);
  if (text.size() <= kKeptScenarioText) sc.text = text;
  return sc;
}

Scenario load_scenario(const std::string& path, const SceneBuilders& builders) {
  std::ifstream in(path);
  if (!in) throw ScenarioError(path, "", "cannot open the file");
  // A listed block costs about 120 bytes of TOML: 64 MiB is half a million listed blocks. Larger
  // models are described by joint sets ([rock_mass]), which the builder cuts in memory.
  constexpr std::uintmax_t kMaxFileBytes = 64ull << 20;
  std::error_code error;
  const std::uintmax_t bytes = std::filesystem::file_size(path, error);
  if (!error && bytes > kMaxFileBytes) {
    throw ScenarioError(
        path, "",
        "the file has " + std::to_string(bytes >> 20) +
            " MiB, more than the 64 MiB limit of a scenario file (describe a "
            "large rock mass by joint sets, [rock_mass], instead of listing blocks)");
  }
  // Read straight into one string of the file's size (a stringstream and its str() would hold
  // the text twice, and more while the stream's buffer grows).
  std::string text;
  if (!error) {
    text.resize(static_cast<std::size_t>(bytes));
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    text.resize(static_cast<std::size_t>(in.gcount()));
  }
  // Whatever the size did not cover (unknown, or the file grew).
  if (in) text.append(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return parse_scenario(text, path, builders);
}

}  // namespace blockdem
