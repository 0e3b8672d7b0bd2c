// A block's rarely set fields (servo, applied loads, group) live apart from its record: they
// must read back with the bits that were set, and survive copies, moves, the growth of the
// world's block vector, world copies and a saved state.
#include <gtest/gtest.h>

#include <cmath>

#include "validation/scenes.hpp"

namespace blockdem::test {
namespace {

Block cube(const std::string& name) {
  return box_block(Eigen::Vector3d::Constant(0.046), {0, 0, 0.023}, 1207.0, Motion::free, name);
}

TEST(BlockExtras, DefaultsWithoutExtras) {
  Block b = cube("a");
  EXPECT_FALSE(b.has_extras());
  EXPECT_TRUE(same_bits(b.servo(), Servo{}));
  EXPECT_EQ(b.external_force(), Eigen::Vector3d::Zero());
  EXPECT_EQ(b.external_torque(), Eigen::Vector3d::Zero());
  EXPECT_EQ(b.group(), "");
  // Values with the defaults' bits leave the block without extras.
  b.set_servo(Servo{});
  b.set_external_force(Eigen::Vector3d::Zero());
  b.set_external_torque(Eigen::Vector3d::Zero());
  b.set_group("");
  EXPECT_FALSE(b.has_extras());
}

TEST(BlockExtras, NegativeZeroIsKept) {
  Block b = cube("a");
  b.set_external_force(Eigen::Vector3d(0.0, -0.0, 0.0));
  ASSERT_TRUE(b.has_extras());
  EXPECT_TRUE(std::signbit(b.external_force().y()));
  Block c = cube("c");
  Servo s;
  s.gain = -0.0;
  c.set_servo(s);
  ASSERT_TRUE(c.has_extras());
  EXPECT_TRUE(same_bits(c.servo(), s));
}

TEST(BlockExtras, CopiesAreDeepAndMovesKeepThem) {
  Block a = cube("a");
  a.set_group("g1");
  a.set_external_torque(Eigen::Vector3d(0, 0, 2.5));
  a.edit_servo().target_force = 3.0;
  Block copy = a;
  copy.edit_servo().target_force = 4.0;
  copy.set_group("g2");
  EXPECT_EQ(a.servo().target_force, 3.0);
  EXPECT_EQ(a.group(), "g1");
  EXPECT_EQ(copy.servo().target_force, 4.0);
  EXPECT_EQ(copy.external_torque(), Eigen::Vector3d(0, 0, 2.5));
  Block plain = cube("p");
  plain = a;  // assignment over a block without extras
  EXPECT_EQ(plain.group(), "g1");
  a = cube("q");  // and back to none
  EXPECT_FALSE(a.has_extras());
  EXPECT_EQ(plain.group(), "g1");
  Block moved = std::move(plain);
  EXPECT_EQ(moved.group(), "g1");
  EXPECT_EQ(moved.servo().target_force, 3.0);
}

TEST(BlockExtras, SurviveWorldGrowthCopiesAndSavedState) {
  World w = linear_world(10e9, 1e9, 30.0);
  for (int i = 0; i < 40; ++i) {  // the block vector reallocates several times
    Block b = box_block(Eigen::Vector3d::Constant(0.046), {0.1 * i, 0, 0.023}, 1207.0,
                        i % 3 == 0 ? Motion::servo : Motion::free, std::to_string(i));
    if (i % 3 == 0) b.edit_servo().target_force = 1.0 + i;
    if (i % 5 == 0) b.set_external_force(Eigen::Vector3d(0.5 * i, 0, 0));
    w.add_block(b);
  }
  const auto check = [](const World& v) {
    for (int i = 0; i < 40; ++i) {
      const Block& b = v.blocks()[static_cast<std::size_t>(i)];
      EXPECT_EQ(b.has_extras(), i % 3 == 0 || i % 5 == 0) << i;
      EXPECT_EQ(b.servo().target_force, i % 3 == 0 ? 1.0 + i : 0.0) << i;
      EXPECT_EQ(b.external_force().x(), i % 5 == 0 ? 0.5 * i : 0.0) << i;
    }
  };
  check(w);
  World copy = w;
  check(copy);
  StateWriter out;
  w.save_state(out);
  for (auto& b : w.blocks()) b.edit_servo().target_force = -7.0;
  const std::vector<std::uint8_t> bytes = out.bytes();
  StateReader in(bytes.data(), bytes.size());
  w.load_state(in);
  EXPECT_TRUE(in.done());
  for (int i = 0; i < 40; ++i)
    EXPECT_EQ(w.blocks()[static_cast<std::size_t>(i)].servo().target_force,
              i % 3 == 0 ? 1.0 + i : 0.0);
  check(copy);  // the copy did not share the changed extras
}

}  // namespace
}  // namespace blockdem::test
