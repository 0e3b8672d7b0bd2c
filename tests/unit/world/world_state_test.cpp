// The world's complete saved state: a world built afresh and loaded with it continues exactly
// (bit for bit) as the world it was saved from; states that do not fit are refused.
#include <gtest/gtest.h>

#include "validation/scenes.hpp"

namespace blockdem::test {
namespace {

// Three cubes on a fixed base pushed sideways: contacts with normal force and shear history.
World pushed_cubes() {
  WorldSettings s;
  s.gravity = Eigen::Vector3d(0, 0, -9.81);
  s.damping = 0.3;
  World w = linear_world(10e9, 1e9, 30.0, s);
  w.add_block(box_block({0.5, 0.2, 0.05}, {0, 0, -0.025}, 1207.0, Motion::fixed, "base"));
  for (int i = 0; i < 3; ++i) {
    Block cube = box_block(Eigen::Vector3d::Constant(0.046), {0.06 * i, 0, 0.023 - 1e-7}, 1207.0,
                           Motion::free, "cube" + std::to_string(i));
    cube.external_force = Eigen::Vector3d(0.2 * (i + 1), 0.0, 0.0);
    w.add_block(cube);
  }
  return w;
}

std::vector<std::uint8_t> saved(const World& w) {
  StateWriter out;
  w.save_state(out);
  return out.bytes();
}

void load(World& w, const std::vector<std::uint8_t>& bytes) {
  StateReader in(bytes.data(), bytes.size());
  w.load_state(in);
  EXPECT_TRUE(in.done());
}

// Oracle: the world that was never saved. Tolerance: none (the complete state, byte for byte).
TEST(WorldState, AFreshWorldLoadedWithTheStateContinuesBitIdentically) {
  World w = pushed_cubes();
  for (int k = 0; k < 250; ++k) w.step();  // past the divergence checkpoint at step 200
  ASSERT_EQ(w.contact_count(), 3u);
  ASSERT_GT(w.contacts()[0]->shear.force.norm(), 0.0);
  const auto state = saved(w);
  World restarted = pushed_cubes();
  load(restarted, state);
  EXPECT_EQ(saved(restarted), state);
  for (int k = 0; k < 300; ++k) {
    w.step();
    restarted.step();
  }
  EXPECT_EQ(saved(restarted), saved(w));
}

TEST(WorldState, RemovedBlocksAreRemovedAgainByName) {
  World w = pushed_cubes();
  for (int k = 0; k < 50; ++k) w.step();
  w.remove_blocks({2});
  for (int k = 0; k < 50; ++k) w.step();
  World restarted = pushed_cubes();
  load(restarted, saved(w));
  ASSERT_EQ(restarted.blocks().size(), 3u);
  EXPECT_EQ(restarted.blocks()[2].name, "cube2");
  for (int k = 0; k < 50; ++k) {
    w.step();
    restarted.step();
  }
  EXPECT_EQ(saved(restarted), saved(w));
}

TEST(WorldState, StatesThatDoNotFitAreRefused) {
  World w = pushed_cubes();
  for (int k = 0; k < 20; ++k) w.step();
  auto state = saved(w);
  // Truncated.
  World a = pushed_cubes();
  const std::vector<std::uint8_t> cut(state.begin(), state.begin() + state.size() / 2);
  StateReader in(cut.data(), cut.size());
  EXPECT_THROW(a.load_state(in), StateError);
  // Another scene: a world whose blocks have other names.
  World other = linear_world(10e9, 1e9, 30.0);
  other.add_block(box_block({0.5, 0.2, 0.05}, {0, 0, -0.025}, 1207.0, Motion::fixed, "floor"));
  for (int i = 0; i < 3; ++i)
    other.add_block(box_block(Eigen::Vector3d::Constant(0.046), {0.06 * i, 0, 0.023}, 1207.0,
                              Motion::free, "other" + std::to_string(i)));
  StateReader whole(state.data(), state.size());
  EXPECT_THROW(other.load_state(whole), StateError);
}

}  // namespace
}  // namespace blockdem::test
