// Reading [[bolts]] and [[bolt_patterns]]: every key checked, and each line checked against the
// rock it is put in.
#include "blockdem/scenario/bolt_input.hpp"

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include "blockdem/collision/shared_face.hpp"

namespace blockdem {

namespace {

/// The tendon's, grout's and dowel's keys and the length (everything but the line and the
/// stage); `b`'s start and direction are set already (validate() checks them too).
void read_element(const CheckedTable& t, BoltSpec& b) {
  const double inf = std::numeric_limits<double>::infinity();
  b.length = t.positive("length", 0.0);
  if (t.has("axial_stiffness")) {
    if (t.has("modulus") || t.has("area"))
      t.fail("axial_stiffness", "give either axial_stiffness or modulus and area, not both");
    b.axial_stiffness = t.positive("axial_stiffness", 0.0);
  } else {
    if (!t.has("modulus") && !t.has("area"))
      t.fail("axial_stiffness",
             "is required (N/m, E A / L of the whole tendon), or modulus and area");
    const double modulus = t.positive("modulus", 0.0);
    const double area = t.positive("area", 0.0);
    b.axial_stiffness = modulus * area / b.length;
  }
  b.yield_force = t.positive("yield_force", inf);
  b.rupture_strain = t.positive("rupture_strain", inf);
  if (t.has("bond_stiffness")) {
    b.bond_stiffness = t.positive("bond_stiffness", 0.0);
    b.bond_strength = t.positive("bond_strength", inf);
  } else if (t.has("bond_strength")) {
    t.fail("bond_strength",
           "needs bond_stiffness (a grout annulus); without it the bolt is "
           "anchored at its ends only");
  }
  b.shear_stiffness = t.positive("shear_stiffness", 0.0, true);
  b.shear_capacity = t.positive("shear_capacity", inf);
  b.shear_rupture_displacement = t.positive("shear_rupture_displacement", inf);
  b.pretension = t.positive("pretension", 0.0, true);
  try {
    b.validate();
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    const auto colon = what.find(": ");
    t.fail(what.substr(0, colon), what.substr(colon + 2));
  }
}

/// The index of the stage `install_stage` names.
std::size_t install_stage(const CheckedTable& t, const Scenario& sc) {
  const std::string stage = t.string("install_stage");
  for (std::size_t s = 0; s < sc.stages.size(); ++s) {
    if (sc.stages[s].name == stage) return s;
  }
  std::string known;
  for (const Stage& s : sc.stages) known += (known.empty() ? "" : ", ") + ("\"" + s.name + "\"");
  t.fail("install_stage", "no stage named \"" + stage + "\" (stages: " + known + ")");
}

/// The blocks left when stage `at` starts: none that it or an earlier stage removes.
std::vector<Block> blocks_left(const Scenario& sc, std::size_t at) {
  std::set<std::string> removed;
  for (std::size_t s = 0; s <= at; ++s)
    removed.insert(sc.stages[s].remove.begin(), sc.stages[s].remove.end());
  std::vector<Block> left;
  for (const Block& block : sc.blocks) {
    if (!removed.count(block.name)) left.push_back(block);
  }
  return left;
}

/// The collars of a pattern on one face of the excavation's surface: a lattice of spacing
/// (along, around) in the face's plane, `along` horizontal (the axis of a horizontal tunnel, or
/// east on a horizontal face), kept where it lies inside the polygon by at least a tenth of
/// the smaller spacing.
std::vector<Eigen::Vector3d> face_collars(const SharedFace& face, double along, double around) {
  const Eigen::Vector3d n = face.normal;
  Eigen::Vector3d a = n.cross(Eigen::Vector3d::UnitZ());
  if (a.norm() < 1e-6) a = Eigen::Vector3d::UnitX() - n.x() * n;
  a.normalize();
  const Eigen::Vector3d b = n.cross(a);
  const double inf = std::numeric_limits<double>::infinity();
  double a0 = inf, a1 = -inf, b0 = inf, b1 = -inf;
  for (const auto& p : face.polygon) {
    a0 = std::min(a0, p.dot(a));
    a1 = std::max(a1, p.dot(a));
    b0 = std::min(b0, p.dot(b));
    b1 = std::max(b1, p.dot(b));
  }
  const double margin = 0.1 * std::min(along, around);
  const double offset = n.dot(face.centroid);
  std::vector<Eigen::Vector3d> out;
  for (double u = (std::floor(a0 / along) + 0.5) * along; u <= a1; u += along) {
    for (double v = (std::floor(b0 / around) + 0.5) * around; v <= b1; v += around) {
      const Eigen::Vector3d x = u * a + v * b + offset * n;
      // Inside the convex polygon, `margin` from every edge.
      bool inside = true;
      const std::size_t m = face.polygon.size();
      for (std::size_t k = 0; k < m && inside; ++k) {
        const Eigen::Vector3d& p = face.polygon[k];
        const Eigen::Vector3d& q = face.polygon[(k + 1) % m];
        Eigen::Vector3d inward = n.cross(q - p).normalized();
        if (inward.dot(face.centroid - p) < 0.0) inward = -inward;
        inside = inward.dot(x - p) >= margin;
      }
      if (inside) out.push_back(x);
    }
  }
  return out;
}

/// One [[bolt_patterns]] entry's bolts: on every face where a block of the excavation touches a
/// block that stays, collars on a lattice, each bolt normal to the face into the rock. Bolts
/// whose line crosses no joint or leaves the model are left out (counted in a warning).
void read_pattern(const CheckedTable& t, std::size_t k, Scenario& sc) {
  BoltSpec element;
  const std::string name = t.string("name", "pattern " + std::to_string(k + 1));
  const std::vector<double> spacing = t.numbers("spacing");
  if (spacing.size() != 2 || !(spacing[0] > 0.0) || !(spacing[1] > 0.0) ||
      !std::isfinite(spacing[0]) || !std::isfinite(spacing[1]))
    t.fail("spacing", "must be two positive spacings [along, around] (m)");
  const std::string excavation = t.string("excavation");
  const auto ex = sc.excavations.find(excavation);
  if (ex == sc.excavations.end()) {
    std::string known;
    for (const auto& [n, blocks] : sc.excavations) known += (known.empty() ? "" : ", ") + n;
    t.fail("excavation",
           "no excavation named \"" + excavation + "\"" +
               (known.empty() ? " (the scenario has none)" : " (known: " + known + ")"));
  }
  read_element(t, element);
  const std::size_t at = install_stage(t, sc);
  t.finish();
  const std::set<std::string> removed(ex->second.begin(), ex->second.end());
  const std::vector<Block> left = blocks_left(sc, at);
  std::vector<BoltSpec> bolts;
  std::size_t idle = 0;
  for (const Block& r : sc.blocks) {
    if (!removed.count(r.name)) continue;
    const PosedBlock pr = posed_block(r);
    for (const Block& rock : left) {
      if (removed.count(rock.name)) continue;
      const double reach = r.shape.bounding_radius() + rock.shape.bounding_radius();
      if ((r.position - rock.position).norm() > reach) continue;
      const PosedBlock pk = posed_block(rock);
      const double tolerance = 1e-9 * reach;
      const auto face = shared_face(r.shape, pr.vertices, pr.planes, pk.planes, tolerance);
      if (!face) continue;
      for (const Eigen::Vector3d& collar : face_collars(*face, spacing[0], spacing[1])) {
        BoltSpec b = element;
        b.name = name + "-" + std::to_string(bolts.size() + 1);
        b.start = collar;
        b.direction = face->normal;  // from the excavation into the rock
        // A bolt that crosses no joint holds nothing; one that leaves the model (the floor of
        // a tunnel near the region's bottom) cannot be put in: both are left out.
        if (!bolt_span_problem(b, bolt_spans(b, left), left).empty()) {
          ++idle;
          continue;
        }
        bolts.push_back(std::move(b));
      }
    }
  }
  if (bolts.empty())
    t.fail("spacing", "no bolt of the pattern crosses a joint inside the model (" +
                          std::to_string(idle) + " collars on the excavation's surface)");
  if (idle > 0)
    sc.warnings.push_back("bolt_patterns[" + std::to_string(k + 1) + "]: " + std::to_string(idle) +
                          " of " + std::to_string(idle + bolts.size()) +
                          " bolts cross no joint within their length or leave the model, and "
                          "are left out");
  for (BoltSpec& b : bolts) sc.stages[at].bolts.push_back(std::move(b));
}

}  // namespace

void read_bolts(const CheckedTable& root, Scenario& sc) {
  const auto tables = root.tables("bolts");
  std::set<std::string> names;
  for (std::size_t k = 0; k < tables.size(); ++k) {
    const CheckedTable& t = tables[k];
    BoltSpec b;
    b.name = t.string("name", "bolt " + std::to_string(k + 1));
    if (!names.insert(b.name).second) t.fail("name", "bolt \"" + b.name + "\" is given twice");
    b.start = t.vec3("start");
    if (!b.start.allFinite()) t.fail("start", "must be a finite point (m)");
    const Eigen::Vector3d d = t.vec3("direction");
    if (!d.allFinite() || !(d.norm() > 0.0))
      t.fail("direction", "must be a nonzero vector pointing into the rock");
    b.direction = d.normalized();
    read_element(t, b);
    const std::size_t at = install_stage(t, sc);
    t.finish();
    const std::vector<Block> left = blocks_left(sc, at);
    const std::string problem = bolt_span_problem(b, bolt_spans(b, left), left);
    if (!problem.empty()) t.fail("start", problem);
    sc.stages[at].bolts.push_back(std::move(b));
  }
  const auto patterns = root.tables("bolt_patterns");
  for (std::size_t k = 0; k < patterns.size(); ++k) read_pattern(patterns[k], k, sc);
}

}  // namespace blockdem
