// Gradual excavation: the blocks removed, the loads they exerted on the blocks left taken down
// over a number of steps (a relaxation), so that the rock mass unloads quasi-statically.
#include <map>
#include <stdexcept>

#include "blockdem/world/world.hpp"

namespace blockdem {

void World::remove_blocks_gradually(const std::vector<int>& indices) {
  if (settings_.distribution != nullptr)
    throw std::invalid_argument(
        "a gradual excavation (relax_steps) runs on one process: run without mpirun, or excavate "
        "at once");
  std::vector<char> removed(blocks_.size(), 0);
  for (int i : indices) {
    if (i < 0 || i >= static_cast<int>(blocks_.size()))
      throw std::invalid_argument("remove_blocks_gradually: no block " + std::to_string(i));
    removed[static_cast<std::size_t>(i)] = 1;
  }
  // The removed blocks' contact loads on each block left, as the scatter applies them: the force
  // at the force point and the couple about the normal.
  std::map<int, std::pair<Eigen::Vector3d, Eigen::Vector3d>> loads;
  for (const Contact& ct : contacts_) {
    const bool gone_a = removed[static_cast<std::size_t>(ct.a)] != 0;
    const bool gone_b = removed[static_cast<std::size_t>(ct.b)] != 0;
    if (gone_a == gone_b) continue;
    const int kept = gone_a ? ct.b : ct.a;
    const double sign = gone_a ? 1.0 : -1.0;  // the force on b, or its negative on a
    const Eigen::Vector3d f = sign * ct.force_on_b();
    const Eigen::Vector3d moment =
        (ct.force_point() - blocks_[static_cast<std::size_t>(kept)].position).cross(f) +
        sign * ct.couple_about_normal() * ct.geometry.normal;
    auto& [force, torque] =
        loads.try_emplace(kept, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()).first->second;
    force += f;
    torque += moment;
  }
  relaxation_.clear();
  for (const auto& [i, load] : loads) {
    const Block& b = blocks_[static_cast<std::size_t>(i)];
    relaxation_.push_back({i, b.external_force(), b.external_torque(), load.first, load.second});
  }
  remove_blocks(indices);  // renumbers relaxation_'s blocks
  relax(1.0);
}

void World::relax(double remaining) {
  for (const Relaxation& r : relaxation_) {
    Block& b = blocks_[static_cast<std::size_t>(r.block)];
    b.set_external_force(r.base_force + remaining * r.force);
    b.set_external_torque(r.base_torque + remaining * r.torque);
  }
  if (remaining <= 0.0) {
    for (const Relaxation& r : relaxation_) {
      Block& b = blocks_[static_cast<std::size_t>(r.block)];
      b.set_external_force(r.base_force);
      b.set_external_torque(r.base_torque);
    }
    relaxation_.clear();
  }
}

}  // namespace blockdem
