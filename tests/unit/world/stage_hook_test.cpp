// The after-step hook of run_stage: called after every step that does not end the stage, with the
// steps taken; a true return ends the stage there (what the Python module's callbacks stand on).
#include <gtest/gtest.h>

#include <vector>

#include "blockdem/world/stage.hpp"
#include "validation/scenes.hpp"

namespace blockdem::test {
namespace {

// A free cube in zero gravity pushed by a constant force F from step 1: Newton's second law with
// leapfrog velocities, v after k steps = k F dt / m exactly (tolerance: round-off, 1e-12).
TEST(StageHook, CalledEveryStepAndStopsTheStage) {
  WorldSettings s;
  s.time_step = 1e-4;
  World w = linear_world(1e9, 1e8, 40.0, s);
  Block cube = box_block(Eigen::Vector3d::Ones(), {0, 0, 0}, 1000.0);
  cube.set_external_force(Eigen::Vector3d(50.0, 0.0, 0.0));
  w.add_block(cube);
  Stage stage;
  stage.kind = Stage::Kind::steps;
  stage.steps = 1000;
  std::vector<std::int64_t> seen;
  const StageResult r = run_stage(w, stage, {}, nullptr, [&](const StageResume& at) {
    seen.push_back(at.steps_done);
    return at.steps_done >= 250;
  });
  ASSERT_EQ(seen.size(), 250u);
  for (std::size_t i = 0; i < seen.size(); ++i)
    EXPECT_EQ(seen[i], static_cast<std::int64_t>(i + 1));
  EXPECT_TRUE(r.interrupted);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.steps, 250);
  EXPECT_EQ(w.step_count(), 250);
  EXPECT_NEAR(w.blocks()[0].velocity.x(), 250 * 50.0 * 1e-4 / 1000.0, 1e-12);

  // Without a hook (or one that never stops) the stage runs to its end.
  const StageResult full =
      run_stage(w, stage, {}, nullptr, [](const StageResume&) { return false; });
  EXPECT_FALSE(full.interrupted);
  EXPECT_TRUE(full.converged);
  EXPECT_EQ(full.steps, 1000);
}

// A stage that runs to a count or a time, cut short by its step limit (blockdem run --max-steps):
// not converged, and said to be stopped, not to have missed an equilibrium it never sought. The
// cube of the test above, pushed on: after k steps, v = k F dt / m.
TEST(StageHook, StepLimitStopsACountedOrTimedStageAndSaysSo) {
  WorldSettings s;
  s.time_step = 1e-4;
  World w = linear_world(1e9, 1e8, 40.0, s);
  Block cube = box_block(Eigen::Vector3d::Ones(), {0, 0, 0}, 1000.0);
  cube.set_external_force(Eigen::Vector3d(50.0, 0.0, 0.0));
  w.add_block(cube);
  Stage counted;
  counted.kind = Stage::Kind::steps;
  counted.steps = 1000;
  counted.max_steps = 300;
  const StageResult r = run_stage(w, counted);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.steps, 300);
  EXPECT_EQ(r.message.rfind(
                "stopped by its step limit (max_steps = 300) after 300 of its 1000 steps:", 0),
            0u)
      << r.message;
  EXPECT_NEAR(w.blocks()[0].velocity.x(), 300 * 50.0 * 1e-4 / 1000.0, 1e-12);

  Stage timed;
  timed.kind = Stage::Kind::duration;
  timed.duration = 1.0;
  timed.max_steps = 200;
  const StageResult t = run_stage(w, timed);
  EXPECT_FALSE(t.converged);
  EXPECT_EQ(t.steps, 200);
  EXPECT_EQ(
      t.message.rfind("stopped by its step limit (max_steps = 200) after 200 steps, at 0.02 s "
                      "of its 1 s:",
                      0),
      0u)
      << t.message;
}

}  // namespace
}  // namespace blockdem::test
