// Bolts holding a block on an incline, in both contact modes, against limit equilibrium
// (Hudson & Harrison 1997, Engineering Rock Mechanics, the bolted block on an inclined plane;
// Hoek & Bray, Rock Slope Engineering, ch. 7, reinforcement). A block of weight W on a plane
// dipping ψ, joint friction φ < ψ (it slides without support):
// - held by a point-anchored elastic bolt at β to the plane (up-dip and into the base): at rest
//   the bolt carries T = W (sin ψ - cos ψ tan φ) / (cos β + sin β tan φ) after a slide
//   s = T / (k cos β), k the bolt's axial stiffness (its extension is s cos β for s ≪ L);
// - held by a dowel normal to the plane (β = 90°, the bolt's shear): the dowel carries
//   D = W (sin ψ - cos ψ tan φ) after a slip D / k_s, and with a shear capacity below D it
//   yields, the block slides on, and the tendon ruptures once its strain reaches the rupture
//   strain: a slip of L sqrt((1 + ε_r)^2 - 1) normal to a bolt of length L.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "blockdem/run/scene_builders.hpp"
#include "blockdem/world/stage.hpp"

namespace blockdem {
namespace bolt_incline_test {
namespace {

constexpr double kG = 9.81;
constexpr double kDensity = 2500.0;
constexpr double kPsiDeg = 30.0, kPhiDeg = 20.0;
constexpr double kDegree = std::numbers::pi / 180.0;
// The 0.2 x 0.1 x 0.1 m block's weight (N).
constexpr double kWeight = kDensity * 0.2 * 0.1 * 0.1 * kG;

// A block of 0.2 (down the dip) x 0.1 x 0.1 m on a fixed base 2 m long and 0.3 m thick, its joint
// linear (k_n = 1e9 Pa/m, k_s = 1e8 Pa/m) with friction φ; gravity g (sin ψ, 0, -cos ψ) (a plane
// dipping ψ towards +x). It settles under vertical gravity; then the stage `tilt` (of `kind`)
// installs the bolt (keys `bolt`) and turns gravity to ψ over `ramp` steps: slowly against the
// bolt's natural period, so that the block creeps to rest with friction at its limit instead of
// overshooting and stopping anywhere within the friction's range.
std::string incline(const std::string& bolt, const std::string& kind, std::int64_t ramp) {
  const double psi = kPsiDeg * kDegree;
  std::ostringstream s;
  s.precision(17);
  s << "[settings]\ndamping = 0.7\ncontact_mode = \"face_integrated\"\n"
    << "[[joint_laws]]\nname = \"joint\"\nnormal = { law = \"linear\", stiffness = 1e9 }\n"
    << "shear = { law = \"linear\", stiffness = 1e8, friction_deg = " << kPhiDeg << " }\n"
    << "[[blocks]]\nname = \"base\"\ndensity = 2500\nsize = [2.0, 0.3, 0.3]\n"
    << "position = [0, 0, -0.15]\nmotion = \"fixed\"\n"
    << "[[blocks]]\nname = \"block\"\ndensity = 2500\nsize = [0.2, 0.1, 0.1]\n"
    << "position = [0, 0, 0.05]\n"
    << "[[stages]]\nname = \"settle\"\ngravity = [0, 0, -9.81]\n"
    << "[[stages]]\nname = \"tilt\"\nkind = \"" << kind << "\"\ngravity = [" << kG * std::sin(psi)
    << ", 0, " << -kG * std::cos(psi) << "]\nramp_steps = " << ramp << "\n"
    << (kind == "steps" ? "steps = " + std::to_string(ramp) + "\n"
                        : "max_steps = 600000\nunbalanced_tolerance = 1e-7\n"
                          "kinetic_tolerance = 1e-14\n")
    << "[[bolts]]\nname = \"B1\"\ninstall_stage = \"tilt\"\n"
    << bolt;
  return s.str();
}

// The driving force less the friction on the unbolted block, W (sin ψ - cos ψ tan φ) (N).
double unbalanced() {
  return kWeight *
         (std::sin(kPsiDeg * kDegree) - std::cos(kPsiDeg * kDegree) * std::tan(kPhiDeg * kDegree));
}

class BoltOnAnIncline : public ::testing::TestWithParam<ContactMode> {
 protected:
  // The world after the settle stage; stage 1 (tilt) is left to the test.
  World settled(const std::string& text) {
    Scenario sc = parse_scenario(text, "incline.toml");
    sc.settings.contact_mode = GetParam();
    stages_ = sc.stages;
    World w = build_world(sc);
    EXPECT_TRUE(run_stage(w, stages_[0]).converged);
    return w;
  }
  std::vector<Stage> stages_;
};

// The block's material point at a bolt's tie: its displacement since the installation (m).
Eigen::Vector3d moved(const World& w, const BoltTie& t) {
  return w.blocks()[static_cast<std::size_t>(t.block)].to_world(t.body_point) - t.installed;
}

// A point-anchored axial bolt at β to the plane: collar on the block's top face at x = 0.08,
// running up-dip and down into the base at β, anchored 0.3 m below the plane, no dowel. At rest
// the block has slid: friction is fully mobilised, up the slope, and the bolt's pull T (up the
// slope T cos β, into the plane T sin β) balances the rest of the weight's down-dip component:
// W sin ψ = T cos β + (W cos ψ + T sin β) tan φ, the limiting-equilibrium T of the header. Its
// stiffness k = 3e4 N/m keeps the slide (about 0.3-0.7 mm) small against the bolt's length, so
// the bolt turns by less than 3e-3 rad (T changes by less than 0.3 %). Tolerance 1 % on T and
// on s.
TEST_P(BoltOnAnIncline, AxialBoltAtAnAngleCarriesTheLimitEquilibriumForce) {
  const double k = 3e4;
  for (const double beta_deg : {30.0, 60.0}) {
    const double beta = beta_deg * kDegree, phi = kPhiDeg * kDegree;
    const double length = (0.1 + 0.3) / std::sin(beta);  // top face to 0.3 m below the plane
    std::ostringstream bolt;
    bolt.precision(17);
    bolt << "start = [0.08, 0, 0.1]\ndirection = [" << -std::cos(beta) << ", 0, " << -std::sin(beta)
         << "]\nlength = " << length << "\naxial_stiffness = " << k << "\n";
    World w = settled(incline(bolt.str(), "equilibrium", 200000));
    ASSERT_TRUE(run_stage(w, stages_[1]).converged);
    ASSERT_EQ(w.bolts().size(), 1u);
    const Bolt& b = w.bolts()[0];
    ASSERT_EQ(b.crossings.size(), 1u);
    EXPECT_EQ(b.state, Bolt::State::intact);
    const double t = unbalanced() / (std::cos(beta) + std::sin(beta) * std::tan(phi));
    const double s = t / (k * std::cos(beta));
    const double slide = moved(w, b.ties[0]).x();  // the collar's, down the dip
    EXPECT_NEAR(b.axial_force, t, 0.01 * t) << "beta " << beta_deg;
    EXPECT_NEAR(slide, s, 0.01 * s) << "beta " << beta_deg;
    std::printf(
        "axial bolt at beta = %g deg (%s): T %.6g N against %.6g N (%.2e), slide %.6g mm "
        "against %.6g mm (%.2e)\n",
        beta_deg, to_string(GetParam()), b.axial_force, t, b.axial_force / t - 1.0, 1e3 * slide,
        1e3 * s, slide / s - 1.0);
  }
}

// A dowel normal to the plane (its tendon soft, 1e3 N/m: a slip of 0.1 mm stretches it by
// 4e-8 m), of shear stiffness k_s = 1e5 N/m and a capacity 5 % above D: at rest it carries D,
// the block's slip at the bolt is D / k_s, and the dowel has not yielded. Tolerance 1 %.
TEST_P(BoltOnAnIncline, DowelCarriesTheDrivingForceLessFrictionBelowItsCapacity) {
  const double ks = 1e5, d = unbalanced();
  std::ostringstream bolt;
  bolt.precision(17);
  bolt << "start = [0, 0, 0.1]\ndirection = [0, 0, -1]\nlength = 0.14\naxial_stiffness = 1e3\n"
       << "shear_stiffness = " << ks << "\nshear_capacity = " << 1.05 * d << "\n";
  World w = settled(incline(bolt.str(), "equilibrium", 200000));
  ASSERT_TRUE(run_stage(w, stages_[1]).converged);
  const Bolt& b = w.bolts()[0];
  ASSERT_EQ(b.crossings.size(), 1u);
  EXPECT_EQ(b.state, Bolt::State::intact);
  // On the base (block_b) down the slope; on the block, up it.
  const BoltCrossing& c = b.crossings[0];
  EXPECT_NEAR(c.force.x(), d, 0.01 * d);
  // The block's slip at the crossing (its centroid moves a little more: it also tilts forward).
  const double slip = (w.blocks()[1].to_world(c.body_a) - Eigen::Vector3d(0, 0, 0.1 - c.at)).x();
  EXPECT_NEAR(slip, d / ks, 0.01 * d / ks);
  std::printf(
      "dowel (%s): shear %.6g N against %.6g N (%.2e), slip %.6g mm against %.6g mm (%.2e)\n",
      to_string(GetParam()), c.force.x(), d, c.force.x() / d - 1.0, 1e3 * slip, 1e3 * d / ks,
      slip * ks / d - 1.0);
}

// The same dowel with a capacity 5 % below D cannot hold the block: the dowel's shear rises as
// k_s times the slip until it reaches its capacity, then stays there while the block slides on
// (state `yielded`); the head-anchor line (L = 0.14 m, rupture strain ε_r = 2 %) stretches as
// sqrt(L^2 + u^2) - L with the slip u, and the tendon ruptures (the bolt is removed, counted)
// at u = L sqrt((1 + ε_r)^2 - 1) = 28.1 mm. Tolerances: the elastic branch 1 % of k_s u, the
// capacity 1e-9, the slip at rupture 1 % (the block's travel in a step is far below).
TEST_P(BoltOnAnIncline, DowelYieldsAtItsCapacityAndTheTendonRupturesAsTheBlockSlides) {
  const double ks = 1e5, d = unbalanced(), capacity = 0.95 * d, length = 0.14, rupture = 0.02;
  std::ostringstream bolt;
  bolt.precision(17);
  bolt << "start = [0, 0, 0.1]\ndirection = [0, 0, -1]\nlength = " << length
       << "\naxial_stiffness = 1e-3\nshear_stiffness = " << ks << "\nshear_capacity = " << capacity
       << "\nrupture_strain = " << rupture << "\n";
  World w = settled(incline(bolt.str(), "steps", 200000));
  // Through the ramp, watching the dowel's elastic branch: its shear against k_s times the slip
  // at the crossing, while below the capacity.
  double worst_elastic = 0.0, largest = 0.0, head = 0.0, slip_at_rupture = 0.0;
  bool yielded_seen = false;
  const auto watch = [&](const World& world) {
    const Bolt& b = world.bolts()[0];
    if (!b.active()) return;
    const BoltCrossing& c = b.crossings[0];
    // The block's material point at the crossing (its top moves a little more: it tilts).
    const double slip =
        (world.blocks()[1].to_world(c.body_a) - Eigen::Vector3d(0, 0, 0.1 - c.at)).x();
    head = moved(world, b.ties[0]).x();  // the collar's, which stretches the tendon
    const double f = c.force.norm();
    largest = std::max(largest, f);
    if (b.state == Bolt::State::intact && f > 0.2 * capacity)
      worst_elastic = std::max(worst_elastic, std::abs(f - ks * slip) / (ks * slip));
    yielded_seen |= b.state == Bolt::State::yielded;
  };
  run_stage(w, stages_[1], {}, nullptr, {}, nullptr,
            [&](const World& world, const Stage&, std::int64_t) { watch(world); });
  for (int k = 0; k < 2000000 && w.bolts()[0].active(); ++k) {
    w.step();
    if (w.bolts()[0].active()) watch(w);
    slip_at_rupture = head;
  }
  const Bolt& b = w.bolts()[0];
  ASSERT_EQ(b.state, Bolt::State::ruptured);
  EXPECT_TRUE(yielded_seen);
  EXPECT_LT(worst_elastic, 0.01);
  EXPECT_NEAR(largest, capacity, 1e-9 * capacity);
  const double expected = length * std::sqrt((1.0 + rupture) * (1.0 + rupture) - 1.0);
  EXPECT_NEAR(slip_at_rupture, expected, 0.01 * expected);
  EXPECT_EQ(w.bolt_count(Bolt::State::ruptured), 1);
  std::printf(
      "dowel at capacity (%s): largest shear %.6g N against %.6g N, elastic branch within %.2e, "
      "slip at rupture %.6g mm against %.6g mm (%.2e)\n",
      to_string(GetParam()), largest, capacity, worst_elastic, 1e3 * slip_at_rupture,
      1e3 * expected, slip_at_rupture / expected - 1.0);
}

// The same yielding dowel with a shear rupture displacement δ_r = 5 mm (and a tendon that does
// not rupture): the bolt breaks in shear once the dowel's shear across it reaches δ_r, is
// removed and counted as ruptured, and the block slides on unheld. The slip at the crossing when
// it breaks is δ_r, within 1 % (the block's travel in a step is far below).
TEST_P(BoltOnAnIncline, DowelBreaksInShearAtItsRuptureDisplacement) {
  const double ks = 1e5, capacity = 0.95 * unbalanced(), rupture = 0.005;
  std::ostringstream bolt;
  bolt.precision(17);
  bolt << "start = [0, 0, 0.1]\ndirection = [0, 0, -1]\nlength = 0.14\naxial_stiffness = 1e-3"
       << "\nshear_stiffness = " << ks << "\nshear_capacity = " << capacity
       << "\nshear_rupture_displacement = " << rupture << "\n";
  World w = settled(incline(bolt.str(), "steps", 200000));
  // The shear at the positions of the step in which the bolt broke (its forces are computed
  // there), and at those of the step before.
  double slip = 0.0, slip_before = 0.0;
  // The shear across the bolt: the crossing's relative displacement less its part along the
  // head-anchor line (docs/support.md, "Dowel action").
  const auto crossing_slip = [](const World& world) {
    const Bolt& b = world.bolts()[0];
    const BoltCrossing& c = b.crossings[0];
    const auto at = [&](int block, const Eigen::Vector3d& body) {
      return world.blocks()[static_cast<std::size_t>(block)].to_world(body);
    };
    const Eigen::Vector3d line =
        (at(b.ties[1].block, b.ties[1].body_point) - at(b.ties[0].block, b.ties[0].body_point))
            .normalized();
    const Eigen::Vector3d d = at(c.block_b, c.body_b) - at(c.block_a, c.body_a);
    return (d - d.dot(line) * line).norm();
  };
  EXPECT_TRUE(run_stage(w, stages_[1]).converged);
  ASSERT_TRUE(w.bolts()[0].active()) << "the bolt broke during the ramp";
  for (int k = 0; k < 2000000 && w.bolts()[0].active(); ++k) {
    slip_before = slip;
    slip = crossing_slip(w);
    w.step();
  }
  ASSERT_EQ(w.bolts()[0].state, Bolt::State::ruptured);
  EXPECT_EQ(w.bolt_count(Bolt::State::ruptured), 1);
  // It broke at the first positions whose shear reached δ_r.
  EXPECT_LT(slip_before, rupture);
  EXPECT_GE(slip, rupture);
  EXPECT_NEAR(slip, rupture, 0.01 * rupture);
  // Unheld, the block slides on: its speed grows.
  const double v0 = w.blocks()[1].velocity.norm();
  for (int k = 0; k < 2000; ++k) w.step();
  EXPECT_GT(w.blocks()[1].velocity.norm(), v0);
  std::printf("dowel breaks in shear (%s): at %.6g mm of shear against %.6g mm (%.2e)\n",
              to_string(GetParam()), 1e3 * slip, 1e3 * rupture, slip / rupture - 1.0);
}

INSTANTIATE_TEST_SUITE_P(BoltSupport, BoltOnAnIncline,
                         ::testing::Values(ContactMode::face_integrated, ContactMode::boon2012),
                         [](const ::testing::TestParamInfo<ContactMode>& mode) {
                           return std::string(to_string(mode.param));
                         });

}  // namespace
}  // namespace bolt_incline_test
}  // namespace blockdem
