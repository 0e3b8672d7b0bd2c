// Bonded joints in tension in the world (the tension branch of the Coulomb slip model with a
// tension cut-off): a block hung from a fixed block by the face they share. Closed forms: an
// intact bond in equilibrium stretches by W / (k_n A) and carries F_n = -W; a bond with
// sigma_t A < W breaks in tension at once and the block falls freely (v = -g t). A contact that
// forms after the start has never been bonded and carries no tension. A bond is on a face the
// blocks share at the start: two blocks that meet only along an edge carry none, however strong
// their law, and the free one falls freely (v = -g t).
#include <gtest/gtest.h>

#include <cmath>

#include "blockdem/run/run_summary.hpp"
#include "scenes.hpp"

namespace blockdem {
namespace {

constexpr double kG = 9.81;
constexpr double kRho = 2600.0;  // rock (kg/m^3)
constexpr double kKn = 10e9;     // Pa/m
constexpr double kKs = 1e9;      // Pa/m
const Eigen::Vector3d kSize(0.2, 0.2, 0.1);

JointLaw bonded_law(double tensile_strength) {
  JointLaw law;
  law.name = "bonded";
  law.normal = LinearNormal{kKn};
  LinearShear shear{kKs, JointStrength::from_friction_deg(35.0)};
  shear.strength.cohesion = 1e5;
  shear.strength.tensile_strength = tensile_strength;
  law.shear = shear;
  return law;
}

/// A fixed block above z = 0 and a free block below it, sharing the face z = 0 (`gap` = 0), or
/// `gap` metres lower.
World hanging_block(double tensile_strength, ContactMode mode, double gap = 0.0) {
  WorldSettings s;
  s.contact_mode = mode;
  s.gravity = Eigen::Vector3d(0, 0, -kG);
  s.damping = 0.7;
  World w(s);
  w.add_joint_law(bonded_law(tensile_strength));
  w.add_joint_rule(JointRule{"", "", 0});
  w.add_block(test::box_block({0.4, 0.4, 0.1}, {0, 0, 0.05}, kRho, Motion::fixed, "roof"));
  w.add_block(test::box_block(kSize, {0, 0, -0.05 - gap}, kRho));
  return w;
}

double weight() {
  return kRho * kSize.prod() * kG;
}
double area() {
  return kSize.x() * kSize.y();
}

class BondedTensionTest : public ::testing::TestWithParam<ContactMode> {};

TEST_P(BondedTensionTest, IntactBondHoldsTheBlockWithTheElasticStretch) {
  // sigma_t A = 4 W: the bond holds.
  World w = hanging_block(4.0 * weight() / area(), GetParam());
  for (int i = 0; i < 6000; ++i) w.step();
  const double stretch = weight() / (kKn * area());  // closed form (m)
  ASSERT_EQ(w.contact_count(), 1u);
  const Contact& c = *w.contacts().front();
  EXPECT_EQ(c.shear.bond, BondState::intact);
  EXPECT_EQ(w.broken_bond_count(), 0);
  EXPECT_NEAR(c.normal_force, -weight(), 1e-3 * weight()) << "the bond carries the weight";
  EXPECT_NEAR(c.geometry.overlap, -stretch, 1e-3 * stretch);
  EXPECT_NEAR(w.blocks()[1].position.z(), -0.05 - stretch, 1e-3 * stretch);
  EXPECT_LT(w.blocks()[1].velocity.norm(), 1e-5);
}

TEST_P(BondedTensionTest, WeakBondBreaksInTensionAndTheBlockFalls) {
  // sigma_t A = W / 2: the bond breaks while the block starts to fall, once.
  World w = hanging_block(0.5 * weight() / area(), GetParam());
  w.settings().damping = 0.0;
  const int steps = 4000;
  for (int i = 0; i < steps; ++i) w.step();
  EXPECT_EQ(w.broken_bond_count(), 1) << "one bond, broken once";
  // In tension, on a face of no joint set (blocks added by hand): row 0, column 0.
  ASSERT_EQ(w.broken_bonds_by_set().size(), 1u);
  EXPECT_EQ(w.broken_bonds_by_set()[0][0], 1);
  EXPECT_EQ(w.broken_bonds_by_set()[0][1], 0);
  // summary.json's table: that row as "other faces", then a row for each joint set named.
  const nlohmann::json table = broken_bonds_by_set(w, {"J1"});
  EXPECT_EQ(table.size(), 2u) << table.dump();
  EXPECT_EQ(table["other faces"]["tension"], 1) << table.dump();
  EXPECT_EQ(table["other faces"]["shear"], 0) << table.dump();
  EXPECT_EQ(table["J1"]["tension"], 0) << table.dump();
  EXPECT_EQ(w.contact_count(), 0u);
  // Free fall from the break, a stretch of at most sigma_t / k_n after the start: v = -g t.
  const double t = w.time();
  EXPECT_NEAR(w.blocks()[1].velocity.z(), -kG * t, 1e-2 * kG * t);
}

TEST_P(BondedTensionTest, AContactFormedLaterIsNotBonded) {
  // The block starts 1 mm below the roof, out of reach of the broad phase, and is pushed up
  // against it; then pulled down with half its weight beyond gravity: an unbonded joint opens.
  World w = hanging_block(4.0 * weight() / area(), GetParam(), 1e-3);
  w.settings().gravity = Eigen::Vector3d(0, 0, kG);  // "falls" upwards onto the roof
  for (int i = 0; i < 3000 && w.contact_count() == 0; ++i) w.step();
  ASSERT_EQ(w.contact_count(), 1u) << "the block must reach the roof";
  EXPECT_EQ(w.contacts().front()->shear.bond, BondState::unbonded);
  w.settings().gravity = Eigen::Vector3d(0, 0, -kG);
  for (int i = 0; i < 3000; ++i) w.step();
  EXPECT_EQ(w.contact_count(), 0u) << "no tension across a joint that was never bonded";
  EXPECT_EQ(w.broken_bond_count(), 0);
  EXPECT_LT(w.blocks()[1].velocity.z(), 0.0);
}

/// The fixed roof of hanging_block and a free block beside and below it, meeting it only along
/// the edge x = 0.2, z = 0 (`pressed` m into it towards the roof's corner), bonded by a law whose
/// cohesion and tensile strength would hold the block on any sliver of face.
World edge_hung_block(ContactMode mode, double pressed) {
  WorldSettings s;
  s.contact_mode = mode;
  s.gravity = Eigen::Vector3d(0, 0, -kG);
  s.damping = 0.0;
  World w(s);
  JointLaw strong = bonded_law(1e12 * weight() / area());
  std::get<LinearShear>(strong.shear).strength.cohesion = 1e12 * weight() / area();
  w.add_joint_law(strong);
  w.add_joint_rule(JointRule{"", "", 0});
  w.add_block(test::box_block({0.4, 0.4, 0.1}, {0, 0, 0.05}, kRho, Motion::fixed, "roof"));
  w.add_block(test::box_block(kSize, {0.3 - pressed, 0, -0.05 + pressed}, kRho));
  return w;
}

TEST_P(BondedTensionTest, BlocksMeetingAlongAnEdgeAreNotBonded) {
  World w = edge_hung_block(GetParam(), 0.0);
  const int steps = 2000;
  for (int i = 0; i < steps; ++i) w.step();
  EXPECT_EQ(w.contact_count(), 0u);
  EXPECT_EQ(w.broken_bond_count(), 0) << "no bond to break";
  // Free fall from the start (no force ever acted): v = -g t to round-off.
  const double t = w.time();
  EXPECT_NEAR(w.blocks()[1].velocity.z(), -kG * t, 1e-9 * kG * t);
  EXPECT_EQ(w.blocks()[1].velocity.x(), 0.0);
}

TEST_P(BondedTensionTest, BlocksPressedTogetherAlongAnEdgeAreNotBonded) {
  // 1 mm into the roof's edge: a contact from the first step, but no face, so no bond.
  World w = edge_hung_block(GetParam(), 1e-3);
  w.step();
  ASSERT_EQ(w.contact_count(), 1u);
  EXPECT_EQ(w.contacts().front()->shear.bond, BondState::unbonded);
  for (int i = 0; i < 4000; ++i) w.step();
  EXPECT_EQ(w.contact_count(), 0u) << "pushed out and falling";
  EXPECT_LT(w.blocks()[1].position.z(), -0.05 - 0.01);
}

TEST_P(BondedTensionTest, BlocksPressedTogetherFaceToFaceAreBonded) {
  // 0.1 um up into the roof over the whole shared face (far beyond the tolerance of coincident
  // faces, 5e-10 m here): the bond is on that face; once the block has settled it hangs from it
  // at the elastic stretch W / (k_n A).
  World w = hanging_block(4.0 * weight() / area(), GetParam(), -1e-7);
  for (int i = 0; i < 8000; ++i) w.step();
  ASSERT_EQ(w.contact_count(), 1u);
  EXPECT_EQ(w.contacts().front()->shear.bond, BondState::intact);
  const double stretch = weight() / (kKn * area());
  EXPECT_NEAR(w.blocks()[1].position.z(), -0.05 - stretch, 1e-3 * stretch);
}

TEST_P(BondedTensionTest, RollbackKeepsAnOpenBond) {
  // The divergence checkpoint keeps an open bond's closure, area and point: a restore gives the
  // same tension as before.
  World w = hanging_block(4.0 * weight() / area(), GetParam());
  for (int i = 0; i < 3000; ++i) w.step();
  w.save_checkpoint();
  const double force = w.contacts().front()->normal_force;
  for (int i = 0; i < 50; ++i) w.step();
  w.restore_checkpoint();
  ASSERT_EQ(w.contact_count(), 1u);
  EXPECT_EQ(w.contacts().front()->normal_force, force);
}

INSTANTIATE_TEST_SUITE_P(Modes, BondedTensionTest,
                         ::testing::Values(ContactMode::boon2012, ContactMode::face_integrated),
                         [](const ::testing::TestParamInfo<ContactMode>& p) {
                           return to_string(p.param);
                         });

}  // namespace
}  // namespace blockdem
