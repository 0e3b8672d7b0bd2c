// Reading a scenario's [[stages]]: kind, loading, convergence and stability keys, servo commands,
// and the joint laws a stage gives anew.
#include "blockdem/scenario/stage_input.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <variant>

#include "blockdem/numerics/number_text.hpp"
#include "blockdem/numerics/units.hpp"
#include "blockdem/scenario/base_motion_input.hpp"
#include "blockdem/scenario/water_input.hpp"
#include "blockdem/world/stability.hpp"

namespace blockdem {

namespace {

// Mechanism criteria, collapse search and strength reduction keys (docs/stability.md).
void read_stability_keys(const CheckedTable& t, Stage& s) {
  s.mechanism.displacement_limit = t.positive("displacement_limit", 0.0, true);
  s.mechanism.growth_checks = t.integer("growth_checks", s.mechanism.growth_checks);
  if (s.mechanism.growth_checks < 2) t.fail("growth_checks", "must be at least 2");
  s.find_collapse = t.boolean("find_collapse", false);
  s.stop_on_mechanism = s.find_collapse;
  if (s.find_collapse) {
    if (s.kind != Stage::Kind::equilibrium)
      t.fail("find_collapse", "only an equilibrium stage can search for a collapse load");
    if (!s.gravity && !(s.seismic && s.seismic->horizontal > 0.0))
      t.fail("find_collapse",
             "the collapse search raises gravity or the seismic coefficient: this stage needs a "
             "gravity or a seismic_kh > 0");
    if (s.gravity && s.seismic)
      t.fail("find_collapse",
             "the collapse search raises either gravity or the seismic coefficient: this stage "
             "gives both (set the gravity in an earlier stage)");
  }
  if (t.has("collapse_tolerance")) {
    if (!s.find_collapse) t.fail("collapse_tolerance", "only with find_collapse = true");
    const double tol = t.number("collapse_tolerance");
    if (!(tol > 0.0)) t.fail("collapse_tolerance", "must be > 0 (g)");
    s.collapse_tolerance = tol;
  }
  if (s.find_collapse) {
    // The bracket ends below the stage's gravity (or k_h): a width doubles cannot resolve there
    // would repeat the same trial.
    const double g = s.gravity ? s.gravity->norm() / kOneG : s.seismic->horizontal;
    if (s.collapse_tolerance < kNarrowestRelativeBracket * g)
      t.fail("collapse_tolerance",
             "must be at least " + number_text(kNarrowestRelativeBracket * g) +
                 " g (1e-12 of the stage's gravity, " + number_text(g) +
                 " g: a narrower bracket is below the resolution of the search), got " +
                 number_text(s.collapse_tolerance));
  }
  const bool sr = s.kind == Stage::Kind::strength_reduction;
  for (const char* key : {"laws", "factor_bounds", "tolerance", "trial_start", "factor_search"}) {
    if (!sr && t.has(key)) t.fail(key, "only a stage of kind \"strength_reduction\" takes this");
  }
  if (!sr) return;
  s.strength.laws = t.strings("laws");
  if (t.has("factor_bounds")) {
    const std::vector<double> b = t.numbers("factor_bounds");
    if (b.size() != 2) t.fail("factor_bounds", "needs two factors [lo, hi]");
    if (!(b[0] > 0.0 && b[1] > b[0]))
      t.fail("factor_bounds", "needs 0 < lo < hi (lo must be stable, hi must fail)");
    s.strength.lower = b[0];
    s.strength.upper = b[1];
  }
  s.strength.from_last_stable =
      t.choice("trial_start", "stage_start", {"stage_start", "last_stable"}) == "last_stable";
  s.strength.extrapolate =
      t.choice("factor_search", "extrapolate", {"extrapolate", "bisect"}) == "extrapolate";
  if (t.has("tolerance")) {
    const double tol = t.number("tolerance");
    if (!(tol > 0.0)) t.fail("tolerance", "must be > 0 (a width of the factor's bracket)");
    s.strength.tolerance = tol;
  }
  if (s.strength.tolerance < kNarrowestRelativeBracket * s.strength.upper)
    t.fail("tolerance", "must be at least " +
                            number_text(kNarrowestRelativeBracket * s.strength.upper) +
                            " (1e-12 of the upper factor bound, " + number_text(s.strength.upper) +
                            ": a narrower bracket is below the resolution of the search), got " +
                            number_text(s.strength.tolerance));
}

}  // namespace

/// A stage's `set_laws`: [{ joint_set = "J1", law = "J1_peak" }, { group = "rock", law =
/// "elastic" }, ...]. "elastic" (unless a law has that name) is each face's elastic twin.
std::vector<LawChange> read_law_changes(const CheckedTable& t, const StageNames& known) {
  std::vector<LawChange> out;
  const auto list_of = [](const auto& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
  };
  for (const auto& e : t.tables("set_laws")) {
    LawChange c;
    if (e.has("joint_set") == e.has("group"))
      e.fail("joint_set", "name either a joint_set or a group whose faces take the law");
    if (e.has("joint_set")) {
      const std::string name = e.string("joint_set");
      const auto it = std::find(known.joint_sets.begin(), known.joint_sets.end(), name);
      if (it == known.joint_sets.end())
        e.fail("joint_set",
               "no joint set named \"" + name + "\" (known: " + list_of(known.joint_sets) + ")");
      c.joint_set = static_cast<int>(it - known.joint_sets.begin());
    } else {
      c.group = e.string("group");
      if (!known.groups.count(c.group)) e.fail("group", "no block is in group \"" + c.group + "\"");
    }
    const std::string law = e.string("law");
    const auto it = known.laws.find(law);
    if (it != known.laws.end()) {
      c.law = it->second;
    } else if (law == "elastic") {
      c.elastic = true;
    } else {
      std::vector<std::string> names;
      for (const auto& [n, i] : known.laws) names.push_back(n);
      e.fail("law",
             "no joint law named \"" + law + "\" (known: " + list_of(names) + ", or \"elastic\")");
    }
    e.finish();
    out.push_back(c);
  }
  return out;
}

Stage read_stage(const CheckedTable& t, const std::set<std::string>& block_names,
                 const std::map<std::string, std::vector<std::string>>& excavations,
                 const StageNames& known) {
  Stage s;
  s.name = t.string("name");
  const std::string kind =
      t.choice("kind", "equilibrium",
               {"equilibrium", "steps", "duration", "excavation", "strength_reduction", "dynamic"});
  // An excavation stage removes the blocks inside an excavation, then runs to equilibrium.
  if (kind == "excavation" && !t.has("excavation"))
    t.fail("excavation", "a stage of kind \"excavation\" names the excavation to remove");
  if (t.has("excavation")) {
    const std::string name = t.string("excavation");
    const auto it = excavations.find(name);
    if (it == excavations.end())
      t.fail("excavation", "no excavation named \"" + name + "\" in [[excavations]]");
    s.remove = it->second;
  }
  s.kind = kind == "steps"                ? Stage::Kind::steps
           : kind == "duration"           ? Stage::Kind::duration
           : kind == "strength_reduction" ? Stage::Kind::strength_reduction
           : kind == "dynamic"            ? Stage::Kind::dynamic
                                          : Stage::Kind::equilibrium;
  if (t.has("gravity")) s.gravity = t.vec3("gravity");
  if (t.has("damping")) {
    s.damping = t.number("damping");
    if (!(*s.damping >= 0.0 && *s.damping < 1.0)) t.fail("damping", "must be in [0, 1)");
  }
  // Ground water and a pseudo-static earthquake from this stage on.
  const WaterInput water = read_water(t, true);
  s.water = water.water;
  s.dry = water.dry;
  s.seismic = read_seismic(t);
  s.unbalanced_tolerance = t.positive("unbalanced_tolerance", s.unbalanced_tolerance);
  s.kinetic_tolerance = t.positive("kinetic_tolerance", s.kinetic_tolerance);
  s.ramp_steps = t.integer("ramp_steps", s.ramp_steps);
  if (s.ramp_steps < 0 || s.ramp_steps > 1000000000000)
    t.fail("ramp_steps", "must be between 0 and 1e12");
  if (s.ramp_steps > 0 && !s.gravity && !s.seismic && !s.water && !s.dry)
    t.fail("ramp_steps",
           "a ramp needs a new gravity, seismic coefficients or water table in this stage");
  s.max_steps = t.integer("max_steps", s.max_steps);
  if (s.max_steps <= 0 || s.max_steps > 1000000000000)
    t.fail("max_steps", "must be between 1 and 1e12");
  s.min_steps = t.integer("min_steps", s.min_steps);
  if (s.min_steps < 0) t.fail("min_steps", "must be zero or positive");
  if (s.min_steps > s.max_steps)
    t.fail("min_steps", "must not exceed max_steps (" + std::to_string(s.max_steps) + ")");
  s.check_interval = t.integer("check_interval", s.check_interval);
  if (s.check_interval <= 0) t.fail("check_interval", "must be positive");
  if (s.kind == Stage::Kind::steps) {
    s.steps = t.integer("steps", 0);
    if (s.steps <= 0) t.fail("steps", "a stage of kind \"steps\" needs steps > 0");
    if (s.steps > s.max_steps)
      t.fail("steps", "must not exceed max_steps (" + std::to_string(s.max_steps) +
                          "); raise max_steps for a longer stage");
  }
  if (s.kind == Stage::Kind::duration) s.duration = t.positive("duration", 0.0);
  if (t.has("density_scaling")) {
    s.density_scaling = t.boolean("density_scaling", false);
    if (s.kind == Stage::Kind::duration && *s.density_scaling)
      t.fail("density_scaling",
             "a \"duration\" stage runs in time, which density scaling distorts (it is exact "
             "only at static equilibrium): use an equilibrium stage, or leave it off");
  }
  read_dynamic_stage(t, known.groups, s);
  read_stability_keys(t, s);
  auto check_block = [&](const std::string& key, const std::string& name) {
    if (!block_names.count(name)) t.fail(key, "no block named \"" + name + "\"");
  };
  for (const auto& st : t.tables("servos")) {
    ServoCommand c;
    c.block = st.string("block");
    check_block("servos", c.block);
    c.target_force = st.positive("target_force", 0.0, true);
    if (st.has("axis")) {
      const Eigen::Vector3d a = st.vec3("axis");
      if (!(a.norm() > 0.0) || !std::isfinite(a.norm()))
        st.fail("axis", "must be a non-zero vector of finite length");
      c.axis = a.normalized();
    }
    st.finish();
    s.servos.push_back(c);
  }
  s.hold = t.strings("hold");
  for (const auto& h : s.hold) check_block("hold", h);
  s.hold_servos_after = t.boolean("hold_servos_after", false);
  s.set_laws = read_law_changes(t, known);
  s.reset_displacements = t.boolean("reset_displacements", false);
  if (t.has("relax_steps")) {
    s.relax_steps = t.integer("relax_steps", 0);
    if (s.relax_steps <= 0 || s.relax_steps > 1000000000000)
      t.fail("relax_steps", "must be between 1 and 1e12 steps");
    if (s.remove.empty())
      t.fail("relax_steps", "a gradual excavation needs excavation = \"NAME\" in this stage");
  }
  t.finish();
  return s;
}

JointLaw elastic_twin(const JointLaw& law) {
  JointLaw twin = law;
  twin.name += std::string(kElasticSuffix);
  std::visit(
      [](auto& l) {
        l.strength.cohesion = 1e30;
        l.strength.tensile_strength = 1e30;
      },
      twin.shear);
  return twin;
}

/// When a stage makes laws elastic: every joint law gets its twin (elastic_twin).
void add_elastic_twins(Scenario& sc) {
  bool elastic = false;
  for (const Stage& st : sc.stages) {
    for (const LawChange& c : st.set_laws) elastic |= c.elastic;
  }
  if (!elastic) return;
  const std::size_t n = sc.joint_laws.size();
  for (std::size_t i = 0; i < n; ++i) sc.joint_laws.push_back(elastic_twin(sc.joint_laws[i]));
}

}  // namespace blockdem
