// The first step of a world from build_world takes the set-up check's narrow phase instead of
// solving the same pairs again: its results are those of a world built without the check, bit
// for bit, over several steps, also when a block moved between the set-up and the first step
// (its pairs are solved again), and with twist on (contacts are solved again, pairs without
// contact are taken).
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <sstream>
#include <string>

#include "blockdem/run/scene_builders.hpp"

namespace blockdem::test {
namespace {

// Two layers of 46 mm cubes in running bond on a fixed base, the layers pre-closed by 50 nm and
// side faces exactly touching (bench/make_pile.py's pile, 3 x 3 and 2 x 2), one cube tilted.
Scenario pile(const std::string& mode) {
  std::ostringstream s;
  s.precision(17);
  s << "[settings]\ndamping = 0.7\ncontact_mode = \"" << mode << "\"\n"
    << "[[materials]]\nname = \"gypsum\"\ndensity = 1207.0\n"
       "[[joint_laws]]\nname = \"joint\"\nnormal = { law = \"linear\", stiffness = 10e9 }\n"
       "shear = { law = \"linear\", stiffness = 1e9, friction_deg = 40 }\n"
       "[[blocks]]\nname = \"base\"\nmaterial = \"gypsum\"\nsize = [0.23, 0.23, 0.046]\n"
       "position = [0.069, 0.069, -0.023]\nmotion = \"fixed\"\n";
  const double side = 0.046, pre = 5e-8;
  int k = 0;
  for (int layer = 0; layer < 2; ++layer) {
    const int m = layer == 0 ? 3 : 2;
    const double shift = layer == 0 ? 0.0 : 0.5 * side;
    const double z = (layer + 0.5) * side - (layer + 1) * pre;
    for (int i = 0; i < m; ++i) {
      for (int j = 0; j < m; ++j) {
        s << "[[blocks]]\nname = \"c" << k << "\"\nmaterial = \"gypsum\"\nsize = [" << side << ", "
          << side << ", " << side << "]\nposition = [" << shift + (i + 0.5) * side << ", "
          << shift + (j + 0.5) * side << ", " << z << "]\n";
        if (k == 4) s << "rotation_deg = 0.01\nrotation_axis = [1.0, 0.0, 0.0]\n";
        ++k;
      }
    }
  }
  s << "[[stages]]\nname = \"settle\"\ngravity = [0.0, 0.0, -9.81]\n";
  return parse_scenario(s.str(), "pile.toml");
}

// The world build_world makes, without the set-up's check (and so without its results).
World unchecked_world(const Scenario& sc) {
  World w(sc.settings);
  for (const auto& law : sc.joint_laws) w.add_joint_law(law);
  for (const auto& r : sc.joint_rules) w.add_joint_rule(r);
  for (const auto& b : sc.blocks) w.add_block(b);
  return w;
}

bool same(double x, double y) {
  return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y);
}

bool same(const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
  return same(x.x(), y.x()) && same(x.y(), y.y()) && same(x.z(), y.z());
}

// Steps both worlds and compares blocks and contacts bit for bit after every step.
void expect_same_steps(World& primed, World& reference, int steps) {
  for (int step = 1; step <= steps; ++step) {
    primed.step();
    reference.step();
    const auto ca = primed.contacts();
    const auto cb = reference.contacts();
    ASSERT_EQ(ca.size(), cb.size()) << "step " << step;
    ASSERT_GT(ca.size(), 20u);
    for (std::size_t k = 0; k < ca.size(); ++k) {
      const Contact& a = *ca[k];
      const Contact& b = *cb[k];
      ASSERT_EQ(a.a, b.a);
      ASSERT_EQ(a.b, b.b);
      EXPECT_TRUE(same(a.geometry.point, b.geometry.point)) << "step " << step << " contact " << k;
      EXPECT_TRUE(same(a.geometry.normal, b.geometry.normal)) << "step " << step;
      EXPECT_TRUE(same(a.geometry.overlap, b.geometry.overlap)) << "step " << step;
      EXPECT_TRUE(same(a.geometry.area, b.geometry.area)) << "step " << step;
      EXPECT_TRUE(same(a.normal_force, b.normal_force)) << "step " << step;
      EXPECT_TRUE(same(a.shear.force, b.shear.force)) << "step " << step;
    }
    for (std::size_t i = 0; i < primed.blocks().size(); ++i) {
      EXPECT_TRUE(same(primed.blocks()[i].position, reference.blocks()[i].position))
          << "step " << step << " block " << i;
      EXPECT_TRUE(same(primed.blocks()[i].angular_velocity, reference.blocks()[i].angular_velocity))
          << "step " << step << " block " << i;
    }
  }
}

TEST(PrimedFirstStep, StepsAreThoseOfAWorldBuiltWithoutTheCheck) {
  const Scenario sc = pile("boon2012");
  World primed = build_world(sc);
  World reference = unchecked_world(sc);
  expect_same_steps(primed, reference, 4);
}

TEST(PrimedFirstStep, ABlockMovedBeforeTheFirstStepHasItsPairsSolvedAgain) {
  const Scenario sc = pile("boon2012");
  World primed = build_world(sc);
  World reference = unchecked_world(sc);
  // Cube c0 (block 1, a corner of the first layer) pressed 20 nm deeper into the base.
  for (World* w : {&primed, &reference}) w->blocks()[1].position.z() -= 2e-8;
  expect_same_steps(primed, reference, 1);
  // The kept result of the old pose would have given the old closure: the moved cube's contact
  // with the base closes by 70 nm at the first step.
  int found = 0;
  for (const Contact* c : primed.contacts()) {
    if (c->a != 0 || c->b != 1) continue;
    ++found;
    EXPECT_NEAR(c->geometry.overlap, 7e-8, 1e-9);
  }
  EXPECT_EQ(found, 1);
  expect_same_steps(primed, reference, 2);
}

TEST(PrimedFirstStep, WithTwistStepsAreThoseOfAWorldBuiltWithoutTheCheck) {
  const Scenario sc = pile("face_integrated");
  ASSERT_TRUE(sc.settings.twist_enabled());
  World primed = build_world(sc);
  World reference = unchecked_world(sc);
  expect_same_steps(primed, reference, 3);
}

}  // namespace
}  // namespace blockdem::test
