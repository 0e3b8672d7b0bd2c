// The dynamic stage's base motion applied to the world, step by step.
#include "blockdem/world/base_drive.hpp"

#include <stdexcept>
#include <string>

namespace blockdem {

BaseDrive::BaseDrive(World& world, const Stage& stage, double start_time, bool resumed) {
  if (stage.kind != Stage::Kind::dynamic || !stage.base_motion) return;
  const auto fail = [&stage](const std::string& what) {
    throw std::invalid_argument("stage '" + stage.name + "': base_motion: " + what);
  };
  if (world.settings().distribution)
    fail("a dynamic stage runs on one process (run without mpirun)");
  stage_ = &stage;
  start_time_ = start_time;
  damping_before_ = world.settings().damping;
  const std::string& group = stage.base_motion->group;
  for (std::size_t i = 0; i < world.blocks().size(); ++i) {
    if (world.blocks()[i].group() == group) base_.push_back(static_cast<int>(i));
  }
  if (base_.empty()) fail("no block is in group \"" + group + "\"");
  before_.resize(base_.size());
  if (resumed) return;
  world.settings().damping = stage.damping.value_or(0.0);
  for (const int i : base_) {
    Block& b = world.blocks()[static_cast<std::size_t>(i)];
    if (b.motion != Motion::fixed)
      fail("block \"" + b.name + "\" of group \"" + group +
           "\" is not fixed: the base moves fixed blocks only");
    b.motion = Motion::prescribed;
    b.velocity.setZero();
    b.angular_velocity.setZero();
    b.angular_momentum.setZero();
  }
}

void BaseDrive::before_step(const World& world) {
  if (!stage_) return;
  tau_before_ = world.time() - start_time_;
  for (std::size_t k = 0; k < base_.size(); ++k)
    before_[k] = world.blocks()[static_cast<std::size_t>(base_[k])].position;
}

void BaseDrive::after_step(World& world) {
  if (!stage_) return;
  const double tau = world.time() - start_time_;
  const double dt = world.last_time_step();
  const Eigen::Vector3d du =
      stage_->base_motion->at(tau).displacement - stage_->base_motion->at(tau_before_).displacement;
  for (std::size_t k = 0; k < base_.size(); ++k) {
    Block& b = world.blocks()[static_cast<std::size_t>(base_[k])];
    b.position = before_[k] + du;
    b.velocity = du / dt;
    b.angular_velocity.setZero();
    b.angular_momentum.setZero();
    world.note_boundary_velocity(base_[k]);
  }
}

void BaseDrive::finish(World& world) {
  if (!stage_) return;
  for (const int i : base_) {
    Block& b = world.blocks()[static_cast<std::size_t>(i)];
    b.motion = Motion::fixed;
    b.velocity.setZero();
    b.angular_velocity.setZero();
    b.angular_momentum.setZero();
  }
  world.settings().damping = stage_->damping_after.value_or(damping_before_);
}

}  // namespace blockdem
