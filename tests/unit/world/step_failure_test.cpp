// A check inside a step that refuses a value (a non-finite stress, a negative moment) is a
// numerical breakdown of the run, not bad input: the step resets the world to its last good
// state and throws StepFailure (a DivergenceError) naming the step and the check, as a blow-up
// does; a stage that ends with it is `diverged`, never `collapsed`.
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "blockdem/world/stability.hpp"
#include "support/thread_distribution.hpp"
#include "validation/scenes.hpp"

namespace blockdem::test {
namespace {

// A cube resting on a fixed base through the exponential law (a = 0.5405e5 Pa, b = 3.7e4 1/m):
// its stress a (exp(b d) - 1) overflows a double once the closure d passes ~19 mm.
World exponential_cube(ContactMode mode, std::shared_ptr<PairDistribution> distribution = nullptr) {
  WorldSettings s;
  s.distribution = std::move(distribution);
  s.gravity = Eigen::Vector3d(0, 0, -9.81);
  s.damping = 0.7;
  s.contact_mode = mode;
  World w(s);
  JointLaw law;
  law.name = "joint";
  law.normal = ExponentialNormal::eq4();
  law.shear = LinearShear{1e9, JointStrength::from_friction_deg(40.0)};
  w.add_joint_law(law);
  w.add_joint_rule(JointRule{"", "", 0});
  w.add_block(box_block({0.2, 0.2, 0.05}, {0, 0, -0.025}, 1207.0, Motion::fixed, "base"));
  w.add_block(box_block(Eigen::Vector3d::Constant(0.046), {0, 0, 0.023 - 1e-7}, 1207.0));
  return w;
}

// The cube settles for 30 steps; pushed 30 mm into the base, the next step's normal force
// overflows to infinity and the shear update refuses it. The step must not escape as a
// std::invalid_argument (which the command line reports as bad input): it throws StepFailure, a
// DivergenceError, naming the step and the check, and the world is back at its last good state (the
// checkpoint taken before the first step), bit for bit the state of a fresh world.
TEST(StepFailure, ARefusedValueInsideAStepResetsTheWorldAndIsADivergence) {
  World w = exponential_cube(ContactMode::boon2012);
  const World fresh = exponential_cube(ContactMode::boon2012);
  for (int k = 0; k < 30; ++k) w.step();
  w.blocks()[1].position.z() -= 0.03;
  try {
    w.step();
    FAIL() << "the step went through with a normal force of infinity";
  } catch (const StepFailure& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("failed at step 31"), std::string::npos) << what;
    EXPECT_NE(what.find("must be finite"), std::string::npos) << what;
    EXPECT_NE(what.find("last good state (step 0)"), std::string::npos) << what;
  } catch (const std::exception& e) {
    FAIL() << "not a StepFailure: " << e.what();
  }
  EXPECT_EQ(w.step_count(), 0);
  EXPECT_EQ(w.time(), 0.0);
  EXPECT_EQ(w.blocks()[1].position, fresh.blocks()[1].position);
  EXPECT_EQ(w.blocks()[1].velocity, fresh.blocks()[1].velocity);
  EXPECT_EQ(w.blocks()[1].orientation.coeffs(), fresh.blocks()[1].orientation.coeffs());
  // And the world steps on from there as the fresh one does.
  World reference = fresh;
  for (int k = 0; k < 5; ++k) {
    w.step();
    reference.step();
  }
  EXPECT_EQ(w.blocks()[1].position, reference.blocks()[1].position);
}

// A stability trial whose step refuses a value is `diverged`: not stable, and never counted as
// the mechanism a collapse search looks for (the motion before it says nothing of a collapse).
TEST(StepFailure, AStabilityTrialThatMeetsItIsDivergedNotCollapsed) {
  World w = exponential_cube(ContactMode::boon2012);
  w.blocks()[1].position.z() -= 0.03;  // 30 mm into the base from the start
  Stage stage;
  stage.name = "trial";
  stage.gravity = Eigen::Vector3d(0, 0, -9.81);
  const StabilityTrial t = run_trial(w, stage, 1.0);
  EXPECT_FALSE(t.stable);
  EXPECT_EQ(t.outcome, TrialOutcome::diverged);
  EXPECT_EQ(w.step_count(), 0) << "reset to the state before the first step";
}

// Distributed over two processes (threads here, as MPI processes would be): the cube's owner
// meets the refused value, the other process has no pair of its own. Both reset the whole world
// and throw the same StepFailure, and the world each holds is the one-process world's after
// its reset, bit for bit.
TEST(StepFailure, EveryProcessOfADistributedWorldResetsAndThrowsTheSameMessage) {
  World alone = exponential_cube(ContactMode::boon2012);
  for (int k = 0; k < 30; ++k) alone.step();
  alone.blocks()[1].position.z() -= 0.03;
  std::string alone_message;
  try {
    alone.step();
  } catch (const StepFailure& e) {
    alone_message = e.what();
  }
  ASSERT_FALSE(alone_message.empty());

  const int parts = 2;
  auto meeting = std::make_shared<Meeting>(parts);
  std::vector<std::string> messages(parts);
  std::vector<Eigen::Vector3d> positions(parts), velocities(parts);
  std::vector<std::int64_t> steps(parts, -1);
  std::vector<std::thread> threads;
  for (int r = 0; r < parts; ++r) {
    threads.emplace_back([&, r] {
      const auto k = static_cast<std::size_t>(r);
      World w =
          exponential_cube(ContactMode::boon2012, std::make_shared<ThreadDistribution>(meeting, r));
      try {
        for (int step = 0; step < 30; ++step) w.step();
        w.synchronize();
        w.blocks()[1].position.z() -= 0.03;  // alike on every process
        w.step();
        messages[k] = "no failure";
      } catch (const StepFailure& e) {
        messages[k] = e.what();
      } catch (const std::exception& e) {
        messages[k] = std::string("another error: ") + e.what();
      }
      positions[k] = w.blocks()[1].position;
      velocities[k] = w.blocks()[1].velocity;
      steps[k] = w.step_count();
    });
  }
  for (auto& t : threads) t.join();
  for (std::size_t k = 0; k < parts; ++k) {
    EXPECT_EQ(messages[k], alone_message) << "process " << k;
    EXPECT_EQ(steps[k], alone.step_count()) << "process " << k;
    EXPECT_EQ(positions[k], alone.blocks()[1].position) << "process " << k;
    EXPECT_EQ(velocities[k], alone.blocks()[1].velocity) << "process " << k;
  }
}

}  // namespace
}  // namespace blockdem::test
