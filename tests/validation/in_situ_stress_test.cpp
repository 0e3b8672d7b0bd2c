// In-situ stress: the traction of a field linear in depth over a face against quadrature, the
// closure that carries it against the law evaluated pointwise, and the equilibrium identity of a
// rock mass cut by three oblique joint sets: under a field in equilibrium with gravity and the
// field's traction on its outer faces, every block starts balanced and stays still.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "blockdem/contact/normal_laws.hpp"
#include "blockdem/response/in_situ.hpp"
#include "blockdem/run/scene_builders.hpp"
#include "blockdem/world/motion_monitor.hpp"
#include "blockdem/world/stage.hpp"

namespace blockdem {
namespace in_situ_test {
namespace {

// A convex pentagon in an oblique plane (dip 50 towards 120), about 3 m across.
std::vector<Eigen::Vector3d> pentagon(Eigen::Vector3d& n) {
  const double dip = 50.0 * M_PI / 180.0, dir = 120.0 * M_PI / 180.0;
  n = Eigen::Vector3d(std::sin(dip) * std::sin(dir), std::sin(dip) * std::cos(dir), std::cos(dip));
  const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
  const Eigen::Vector3d c(10.0, -4.0, 37.0);
  const std::array<std::array<double, 2>, 5> p{
      {{-1.5, -1.0}, {1.2, -1.4}, {1.9, 0.3}, {0.2, 1.6}, {-1.4, 0.9}}};
  std::vector<Eigen::Vector3d> out;
  for (const auto& q : p) out.push_back(c + q[0] * u + q[1] * v);
  return out;
}

StressField oblique_field() {
  StressField f;
  f.stress << 7.5e6, 1.2e6, -0.8e6, 1.2e6, 5.0e6, 0.6e6, -0.8e6, 0.6e6, 6.0e6;
  f.reference_z = 30.0;
  f.gradient_z << -4.0e4, 3.0e3, 1.0e3, 3.0e3, -2.65e4, -2.0e3, 1.0e3, -2.0e3, -2.65e4;
  return f;
}

// The integral over a fan of triangles by the three-edge-midpoint rule, exact for quadratic
// integrands (the field's traction is linear, its moment quadratic), each triangle split into
// `depth` levels of four.
template <class F>
void quadrature(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                int depth, const Eigen::Vector3d& n, F&& f) {
  if (depth > 0) {
    const Eigen::Vector3d ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
    quadrature(a, ab, ca, depth - 1, n, f);
    quadrature(ab, b, bc, depth - 1, n, f);
    quadrature(ca, bc, c, depth - 1, n, f);
    quadrature(ab, bc, ca, depth - 1, n, f);
    return;
  }
  const double area = 0.5 * (b - a).cross(c - a).dot(n);
  const std::array<Eigen::Vector3d, 3> mids{0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a)};
  for (const Eigen::Vector3d& x : mids) f(x, area / 3.0);
}

TEST(InSituStress, FaceTractionIsTheIntegralOfTheFieldOverThePolygon) {
  Eigen::Vector3d n;
  const auto poly = pentagon(n);
  const StressField field = oblique_field();
  const FaceTraction t = face_traction(field, poly, n);
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
  for (std::size_t i = 1; i + 1 < poly.size(); ++i) {
    quadrature(poly[0], poly[i], poly[i + 1], 0, n, [&](const Eigen::Vector3d& x, double w) {
      const Eigen::Vector3d tr = field.at(x) * n;
      force += w * tr;
      moment += w * (x - t.centroid).cross(tr);
    });
  }
  EXPECT_LT((t.force - force).norm(), 1e-12 * force.norm());
  EXPECT_LT((t.moment - moment).norm(), 1e-10 * force.norm());
  // A gradient makes a moment; the shear part about n is the twisting moment.
  EXPECT_GT(moment.norm(), 1e-6 * force.norm());
  EXPECT_NEAR(t.twisting_moment(n), n.dot(moment), 1e-10 * force.norm());
  // σ_n at every vertex from the tensor.
  for (const Eigen::Vector3d& x : poly) {
    EXPECT_NEAR(t.normal_stress + t.normal_stress_gradient.dot(x - t.centroid),
                n.dot(field.at(x) * n), 1e-9 * t.normal_stress);
  }
}

// The normal force and the moment in the face of the law over the polygon under closure c,
// by quadrature of the law pointwise (independent of the closed-form integrals of the code).
void law_resultant(const NormalLaw& law, const std::vector<Eigen::Vector3d>& poly,
                   const Eigen::Vector3d& n, const LinearClosure& c, const Eigen::Vector3d& about,
                   double& force, Eigen::Vector3d& moment) {
  force = 0.0;
  moment.setZero();
  for (std::size_t i = 1; i + 1 < poly.size(); ++i) {
    quadrature(poly[0], poly[i], poly[i + 1], 6, n, [&](const Eigen::Vector3d& x, double w) {
      const double s = normal_stress(law, c.at(x));
      force += w * s;
      moment += w * (x - about).cross(s * n);
    });
  }
}

TEST(InSituStress, ClosureCarriesTheNormalTractionForTheLinearAndExponentialLaws) {
  Eigen::Vector3d n;
  const auto poly = pentagon(n);
  const StressField field = oblique_field();
  const FaceTraction t = face_traction(field, poly, n);
  const Eigen::Vector3d normal_moment = t.moment - n.dot(t.moment) * n;
  // Linear law: the closure is σ_n / k_n pointwise.
  const LinearNormal linear{2e10};
  const LinearClosure cl = closure_for_traction(linear, poly, n, t);
  for (const Eigen::Vector3d& x : poly) EXPECT_NEAR(cl.at(x), n.dot(field.at(x) * n) / 2e10, 1e-15);
  // Exponential law (eq 3): not linear pointwise, but the force and moments are the field's.
  const NormalLaw exponential = ExponentialNormal::eq3();
  const LinearClosure ce = closure_for_traction(exponential, poly, n, t);
  double force = 0.0;
  Eigen::Vector3d moment;
  law_resultant(exponential, poly, n, ce, t.centroid, force, moment);
  EXPECT_NEAR(force, n.dot(t.force), 1e-8 * force);
  EXPECT_LT((moment - normal_moment).norm(), 1e-7 * force);
  EXPECT_GT(normal_moment.norm(), 1e-4 * force);  // the moment is not trivially zero
}

TEST(InSituStress, TensionOnAFaceIsRefused) {
  Eigen::Vector3d n;
  const auto poly = pentagon(n);
  StressField f;
  f.stress = Eigen::Matrix3d::Identity() * -1e5;
  const FaceTraction t = face_traction(f, poly, n);
  EXPECT_THROW(closure_for_traction(LinearNormal{}, poly, n, t), std::invalid_argument);
}

// A 12 x 10 x 10 m box cut by three oblique joint sets at 500 m depth, density 2700, under the
// shorthand field (σ_v = ρ g (510 - z), K_x = 1.5, K_y = 0.8, trend 20) or a uniform field
// without gravity, the field's traction on all six region faces, no damping.
std::string rock_mass(const std::string& mode, bool gravity) {
  std::ostringstream s;
  s << "[settings]\ncontact_mode = \"" << mode << "\"\ndamping = 0.0\n"
    << "gravity = " << (gravity ? "[0, 0, -9.81]" : "[0, 0, 0]") << "\n"
    << R"([[joint_laws]]
name = "joint"
normal = { law = "linear", stiffness = 2e10 }
shear = { law = "linear", stiffness = 5e9, friction_deg = 35 }
[rock_mass]
region = { min = [0, 0, 0], max = [12, 10, 10] }
density = 2700
law = "joint"
[[joint_sets]]
name = "J1"
dip_deg = 35
dip_direction_deg = 120
spacing = 4.5
[[joint_sets]]
name = "J2"
dip_deg = 70
dip_direction_deg = 240
spacing = 5.0
[[joint_sets]]
name = "J3"
dip_deg = 80
dip_direction_deg = 10
spacing = 5.5
[[boundaries]]
faces = ["x_min", "x_max", "y_min", "y_max", "z_min", "z_max"]
condition = "stress"
)";
  if (gravity) {
    s << "[in_situ]\nground_z = 510\ndensity = 2700\nk_x = 1.5\nk_y = 0.8\ntrend_deg = 20\n";
  } else {
    s << "[in_situ]\nstress = { xx = 2e7, yy = 1.1e7, zz = 1.3e7, xy = 2e6, yz = -1e6, xz = "
         "3e6 }\n";
  }
  s << "[[stages]]\nname = \"hold\"\nkind = \"duration\"\nduration = 1.0\n";
  return s.str();
}

// The largest unbalanced force and moment over the blocks after the first step, relative to
// σ A and σ A L of each block (A = V^(2/3), L = V^(1/3)), and the largest displacement after
// `steps` more.
struct Balance {
  double force = 0.0, moment = 0.0, displacement = 0.0;
  std::size_t blocks = 0, preloaded = 0;
};
Balance balance(const std::string& mode, bool gravity, int steps) {
  const Scenario sc = parse_scenario(rock_mass(mode, gravity), "in_situ.toml");
  World w = build_world(sc);
  Balance b;
  b.blocks = w.blocks().size();
  b.preloaded = w.preloads().size();
  const double sigma = 2e7;  // about the largest principal stress of either field
  w.step();
  for (const Block& k : w.blocks()) {
    const double volume = k.mass / k.density;
    const double area = std::pow(volume, 2.0 / 3.0), length = std::cbrt(volume);
    b.force = std::max(b.force, k.force.norm() / (sigma * area));
    b.moment = std::max(b.moment, k.torque.norm() / (sigma * area * length));
  }
  for (int i = 0; i < steps; ++i) w.step();
  for (const Block& k : w.blocks())
    b.displacement = std::max(b.displacement, (k.position - k.initial_position).norm());
  return b;
}

TEST(InSituStress, RockMassUnderAFieldInEquilibriumWithGravityStartsAndStaysBalanced) {
  const Balance b = balance("face_integrated", true, 1000);
  ASSERT_GT(b.blocks, 20u);
  EXPECT_GT(b.preloaded, b.blocks);  // every shared face
  EXPECT_LT(b.force, 1e-9);
  EXPECT_LT(b.moment, 1e-9);
  EXPECT_LT(b.displacement, 1e-9);
}

TEST(InSituStress, RockMassUnderAUniformFieldStartsAndStaysBalanced) {
  const Balance b = balance("face_integrated", false, 1000);
  EXPECT_LT(b.force, 1e-9);
  EXPECT_LT(b.moment, 1e-9);
  EXPECT_LT(b.displacement, 1e-9);
}

// The point contact carries each face's normal force at its analytic centre x_c, which is the
// face's centroid only on a symmetric face: the forces balance, the moments do not where the
// region's planes cut the faces into irregular polygons (docs/ground-stress.md).
TEST(InSituStress, PointContactBalancesTheForcesOfAUniformField) {
  const Balance b = balance("boon2012", false, 0);
  EXPECT_LT(b.force, 1e-9);
  EXPECT_GT(b.moment, 1e-3);
}

// The ScenarioError of a rock-mass scenario with `in_situ` for its [in_situ] table (and
// `boundary` for its [[boundaries]] entry), or an empty one when it builds.
ScenarioError error_of(const std::string& in_situ, const std::string& boundary) {
  std::string text = rock_mass("face_integrated", true);
  text = text.substr(0, text.find("[[boundaries]]")) + boundary + in_situ +
         "[[stages]]\nname = \"hold\"\n";
  try {
    const Scenario sc = parse_scenario(text, "bad.toml");
    build_world(sc);
  } catch (const ScenarioError& e) {
    return e;
  }
  return ScenarioError("", "", "");
}

const char* kStressSides =
    "[[boundaries]]\nfaces = [\"x_min\", \"x_max\"]\ncondition = \"stress\"\n";

TEST(InSituStress, BadFieldsAreInputErrorsNamingTheKey) {
  const auto expect = [](const ScenarioError& e, const std::string& key, const std::string& why) {
    EXPECT_EQ(e.file(), "bad.toml");
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_NE(e.reason().find(why), std::string::npos) << e.what();
  };
  expect(error_of("[in_situ]\nstress = { xx = 1e6 }\nground_z = 10\n", kStressSides),
         "in_situ.ground_z", "either stress");
  expect(error_of("[in_situ]\nstress = [[1e6, 2e5, 0], [0, 1e6, 0], [0, 0, 1e6]]\n", kStressSides),
         "in_situ.stress", "not symmetric");
  expect(error_of("[in_situ]\nstress = { xx = nan, yy = 1e6, zz = 1e6 }\n", kStressSides),
         "in_situ.stress.xx", "finite");
  expect(error_of("[in_situ]\nground_z = 510\n", kStressSides), "in_situ.density", "required");
  expect(error_of("[in_situ]\nground_z = 510\ndensity = 2700\nk_z = 1\n", kStressSides),
         "in_situ.k_z", "");
  // Tension on the joints: named by the blocks, the law and the point.
  expect(error_of("[in_situ]\nstress = { xx = -1e7, yy = 1e6, zz = 1e6 }\n", kStressSides),
         "in_situ", "not compressive");
  // A stress boundary needs a field.
  expect(error_of("", kStressSides), "boundaries[1].condition", "[in_situ]");
  expect(error_of("", "[[boundaries]]\nfaces = [\"x_min\"]\nstress = { xx = 1e6 }\n"),
         "boundaries[1].stress", "condition");
}

// Stress relief: the rock mass under the uniform field with no traction on its outer faces (no
// gravity, no damping) springs apart on the energy its joints store from the first step. With
// no load to do work, that energy is the stage's whole budget: the kinetic energy stays within
// it, and a stage cut short is not a numerical blow-up (its monitor counted none of that energy
// before: the joints take their forces in the first step, after the stage starts).
TEST(InSituStress, RelievedRockMassMovesOnItsStoredEnergyNotAsABlowUp) {
  std::string text = rock_mass("face_integrated", false);
  text = text.substr(0, text.find("[[boundaries]]")) + text.substr(text.find("[in_situ]"));
  World w = build_world(parse_scenario(text, "relief.toml"));
  ASSERT_GT(w.preloads().size(), w.blocks().size());
  Stage st;
  st.name = "relief";
  st.max_steps = 300;
  std::optional<MotionMonitor> monitor;
  const StageResult r = run_stage(w, st, {}, &monitor);
  ASSERT_FALSE(r.converged);
  const MotionReport& m = monitor->report();
  const EnergyBudget& e = w.energy_budget();
  // What the joints stored after the first step (the blocks at rest then): all of it available.
  EXPECT_EQ(m.elastic_energy_start, e.initial);
  EXPECT_GT(e.initial, 0.0);
  EXPECT_EQ(m.load_work, 0.0);
  EXPECT_GT(m.kinetic_energy, 1e-3 * e.initial);  // the blocks did move on it
  EXPECT_LE(m.kinetic_energy, e.initial);
  EXPECT_FALSE(monitor->energy_created());
  EXPECT_EQ(classify_failure(*monitor, false), FailureKind::not_converged);

  // A monitor saved before the first step (a checkpoint then) takes the same energy once read.
  World fresh = build_world(parse_scenario(text, "relief.toml"));
  StateWriter out;
  MotionMonitor(fresh, MechanismCriteria{}).save_state(out);
  const std::vector<std::uint8_t> bytes = out.bytes();
  StateReader in(bytes.data(), bytes.size());
  MotionMonitor read(in);
  EXPECT_TRUE(in.done());
  fresh.step();
  read.observe(fresh, false);
  EXPECT_EQ(read.report().elastic_energy_start, e.initial);
}

TEST(InSituStress, ADeliberateInitialOverlapIsAllowedAndCarried) {
  // A 0.1 m cube 1 mm into a fixed base, k_n = 1e10 Pa/m: 1e7 Pa, refused by default.
  const auto scene = [](const std::string& settings) {
    return settings +
           "[[joint_laws]]\nname = \"j\"\nnormal = { law = \"linear\", stiffness = 1e10 }\n"
           "shear = { law = \"linear\", stiffness = 1e9, friction_deg = 35 }\n"
           "[[blocks]]\nname = \"base\"\ndensity = 2600\nsize = [1, 1, 0.05]\n"
           "position = [0, 0, -0.025]\nmotion = \"fixed\"\n"
           "[[blocks]]\nname = \"cube\"\ndensity = 2600\nsize = [0.1, 0.1, 0.1]\n"
           "position = [0, 0, 0.049]\n[[stages]]\nname = \"s\"\n";
  };
  EXPECT_THROW(build_world(parse_scenario(scene(""), "o.toml")), ScenarioError);
  World w =
      build_world(parse_scenario(scene("[settings]\ninitial_overlap = \"allow\"\n"), "o.toml"));
  w.step();
  ASSERT_EQ(w.contact_count(), 1u);
  // σ_n = k_n δ over the 0.1 x 0.1 m face.
  EXPECT_NEAR(w.contacts()[0]->normal_force, 1e10 * 1e-3 * 0.01, 1e-6 * 1e5);
}

}  // namespace
}  // namespace in_situ_test
}  // namespace blockdem
