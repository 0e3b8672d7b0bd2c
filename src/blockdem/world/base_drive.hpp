// A dynamic stage's moving base: the base group's blocks set to the prescribed history at every
// step, in step with the leapfrog's staggering (positions at t_n, velocities at t_{n+1/2}).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "blockdem/world/stage.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

/// Drives the base blocks of a Stage::Kind::dynamic stage; does nothing for another stage.
///
/// The leapfrog moves a block by dt_n v_{n+1/2} over step n, and a contact evaluated at step n+1
/// sees the blocks at x_{n+1} with velocities v_{n+1/2}. So after each step the base is put at
/// x_{n+1} = x_n + (u(t_{n+1}) - u(t_n)), the exact increment of the history's displacement,
/// with the velocity v_{n+1/2} = (u(t_{n+1}) - u(t_n)) / dt_n that carries it: the base's
/// displacement over the stage is u(t) to rounding, and the joints see the relative velocity of
/// the same staggered instant as the free blocks'. The increment depends only on the stage time
/// and the base's position before the step, so a restart continues the same motion without any
/// state of its own. Stage time is the world time since the stage start.
class BaseDrive {
 public:
  /// `start_time`: the world time at the stage start (s). At a fresh start the base blocks,
  /// which must be fixed, become prescribed at rest, and the local damping becomes the stage's
  /// (0 unless it gives one). Throws std::invalid_argument for a base group without blocks, a
  /// base block that is not fixed, or a world spread over processes.
  BaseDrive(World& world, const Stage& stage, double start_time, bool resumed);
  /// Keeps the base's positions and the stage time before a step.
  void before_step(const World& world);
  /// Moves the base to the history's position after the step (see the class comment).
  void after_step(World& world);
  /// The stage's end: the base blocks fixed where they are, the local damping of before.
  void finish(World& world);

 private:
  const Stage* stage_ = nullptr;  ///< null: not a dynamic stage
  double start_time_ = 0.0;
  double damping_before_ = 0.0;
  std::vector<int> base_;
  std::vector<Eigen::Vector3d> before_;
  double tau_before_ = 0.0;
};

}  // namespace blockdem
