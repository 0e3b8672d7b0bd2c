// The compact checkpoint: a restore puts back the block states and contact shear histories, and
// the run then follows the same path as a copy of the world taken at the checkpoint.
#include <gtest/gtest.h>

#include <cmath>

#include "validation/scenes.hpp"

namespace blockdem::test {
namespace {

// A cube on a fixed base, pushed sideways below its friction limit: the joint carries a normal
// force and an elastic shear force, the history a restore must keep.
World pushed_cube() {
  WorldSettings s;
  s.gravity = Eigen::Vector3d(0, 0, -9.81);
  s.damping = 0.7;
  s.contact_mode = ContactMode::boon2012;
  World w = linear_world(10e9, 1e9, 40.0, s);
  w.add_block(box_block({0.2, 0.2, 0.05}, {0, 0, -0.025}, 1207.0, Motion::fixed, "base"));
  Block cube = box_block(Eigen::Vector3d::Constant(0.046), {0, 0, 0.023 - 1e-7}, 1207.0);
  cube.set_external_force(Eigen::Vector3d(0.3, 0.0, 0.0));  // 0.3 N < tan 40° x 1.15 N
  w.add_block(cube);
  return w;
}

// Oracle: a copy of the world taken at the checkpoint. Tolerances: block states and shear
// forces right after the restore, exact; after 50 more steps, 1e-12 m and 1e-9 N (the restore
// drops narrow-phase warm starts, which move results by round-off only).
TEST(Checkpoint, RestoreGivesBackStatesAndShearHistoryAndTheSamePath) {
  World w = pushed_cube();
  for (int k = 0; k < 120; ++k) w.step();  // the world also checkpoints every 200 steps
  w.save_checkpoint();
  const World at_checkpoint = w;
  ASSERT_EQ(w.contact_count(), 1u);
  const Eigen::Vector3d shear = w.contacts()[0]->shear.force;
  ASSERT_GT(shear.norm(), 0.01) << "the joint must carry shear";

  for (int k = 0; k < 50; ++k) w.step();
  EXPECT_NE(w.blocks()[1].position, at_checkpoint.blocks()[1].position);
  w.restore_checkpoint();
  EXPECT_EQ(w.step_count(), at_checkpoint.step_count());
  EXPECT_EQ(w.time(), at_checkpoint.time());
  EXPECT_EQ(w.blocks()[1].position, at_checkpoint.blocks()[1].position);
  EXPECT_EQ(w.blocks()[1].velocity, at_checkpoint.blocks()[1].velocity);
  EXPECT_EQ(w.blocks()[1].orientation.coeffs(), at_checkpoint.blocks()[1].orientation.coeffs());
  ASSERT_EQ(w.contact_count(), 1u);
  EXPECT_EQ(w.contacts()[0]->shear.force, shear);
  EXPECT_GT(w.contacts()[0]->normal_force, 0.0) << "geometry re-derived at the restored pose";

  World reference = at_checkpoint;
  for (int k = 0; k < 50; ++k) {
    w.step();
    reference.step();
  }
  EXPECT_LT((w.blocks()[1].position - reference.blocks()[1].position).norm(), 1e-12);
  ASSERT_EQ(w.contact_count(), 1u);
  EXPECT_LT((w.contacts()[0]->shear.force - reference.contacts()[0]->shear.force).norm(), 1e-9);
}

// The checkpoint keeps only the servos that are not Servo{}: a restore gives every block its servo
// as saved, a servo block's and a plain block's (Servo{}), even after both were changed.
TEST(Checkpoint, RestoreGivesBackEachBlocksServo) {
  World w = pushed_cube();
  Block pusher =
      box_block(Eigen::Vector3d::Constant(0.046), {0.2, 0, 0.023}, 1207.0, Motion::servo, "pusher");
  pusher.edit_servo().axis = -Eigen::Vector3d::UnitX();
  pusher.edit_servo().target_force = 2.5;
  pusher.edit_servo().gain = -0.0;  // a bit pattern Servo{} does not have
  w.add_block(pusher);
  w.save_checkpoint();
  const Servo saved = w.blocks()[2].servo();
  for (Block& b : w.blocks()) {
    b.edit_servo().target_force = 7.0;
    b.edit_servo().hold = true;
  }
  w.restore_checkpoint();
  EXPECT_TRUE(same_bits(w.blocks()[0].servo(), Servo{}));
  EXPECT_TRUE(same_bits(w.blocks()[1].servo(), Servo{}));
  EXPECT_TRUE(same_bits(w.blocks()[2].servo(), saved));
  EXPECT_FALSE(same_bits(saved, Servo{}));
  EXPECT_TRUE(std::signbit(w.blocks()[2].servo().gain));
}

}  // namespace
}  // namespace blockdem::test
