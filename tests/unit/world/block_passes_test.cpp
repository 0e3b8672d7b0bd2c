// The step's passes over every block that a large world runs over its threads (the a-priori time
// step's minimum, the search for the first diverged block) give what one thread gives, and what
// a world holding only the block that decides them gives: the same bits, the same block named.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "blockdem/world/world.hpp"
#include "validation/scenes.hpp"

namespace blockdem::test {
namespace {

constexpr int kBlocks = 9000;    // above the size from which these passes use the threads
constexpr int kSmallest = 6001;  // in the second half: another thread's share than block 0's

WorldSettings settings(int threads) {
  WorldSettings s;
  s.gravity = Eigen::Vector3d(0, 0, -9.81);
  s.damping = 0.7;
  s.threads = threads;
  return s;
}

void add_law(World& w) {
  JointLaw law;
  law.name = "joint";
  law.normal = LinearNormal{5e9};
  law.shear = LinearShear{5e8, JointStrength::from_friction_deg(35.0)};
  w.add_joint_law(law);
  w.add_joint_rule(JointRule{"", "", 0});
}

Eigen::Vector3d grid_point(int i) {
  return Eigen::Vector3d(i % 30, (i / 30) % 30, i / 900);
}

// Cubes apart on a grid (no pair touches), their edges between 0.2 and 0.3 m; one of them
// smaller (0.05 m) and so the one whose step is the shortest.
World cubes(int threads) {
  World w(settings(threads));
  add_law(w);
  for (int i = 0; i < kBlocks; ++i) {
    const double edge = i == kSmallest ? 0.05 : 0.2 + 0.1 * std::fmod(0.37 * i, 1.0);
    w.add_block(box_block(Eigen::Vector3d::Constant(edge), grid_point(i), 2600.0, Motion::free,
                          "cube_" + std::to_string(i)));
  }
  return w;
}

TEST(BlockPasses, TheAPrioriTimeStepOverThreadsIsTheOneThreadsAndTheDecidingBlocks) {
  World alone(settings(1));
  add_law(alone);
  // The smallest cube where the grid has it (its shape's values to the last bit).
  alone.add_block(box_block(Eigen::Vector3d::Constant(0.05), grid_point(kSmallest), 2600.0));
  const double expected = alone.next_time_step();
  ASSERT_TRUE(std::isfinite(expected) && expected > 0.0);
  for (const int threads : {1, 2, 3}) {
    const World w = cubes(threads);
    // The same bits: a minimum is exact whatever the order of its terms.
    EXPECT_EQ(w.next_time_step(), expected) << threads << " threads";
  }
}

TEST(BlockPasses, TheFirstDivergedBlockOverThreadsIsTheOneThreadsFirst) {
  for (const int threads : {1, 2, 3}) {
    World w = cubes(threads);
    // Two blocks diverge in the second half (another thread's share than the first block's): the
    // one of the lower index is named, for its reason.
    w.blocks()[7100].velocity = Eigen::Vector3d(std::numeric_limits<double>::quiet_NaN(), 0, 0);
    w.blocks()[6500].velocity = Eigen::Vector3d(0, 0, 1e4);
    try {
      w.step();
      FAIL() << "no divergence found with " << threads << " threads";
    } catch (const DivergenceError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("block 'cube_6500' moves at"), std::string::npos)
          << threads << " threads: " << what;
    }
    World n = cubes(threads);
    n.blocks()[7100].velocity = Eigen::Vector3d(std::numeric_limits<double>::quiet_NaN(), 0, 0);
    try {
      n.step();
      FAIL() << "no divergence found with " << threads << " threads";
    } catch (const DivergenceError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("block 'cube_7100' has a non-finite position or velocity"),
                std::string::npos)
          << threads << " threads: " << what;
    }
  }
}

}  // namespace
}  // namespace blockdem::test
