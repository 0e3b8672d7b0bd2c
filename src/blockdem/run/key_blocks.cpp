// Key blocks: displacement during a stage against each block's own size.
#include "blockdem/run/key_blocks.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace blockdem {

std::map<std::string, Eigen::Vector3d> block_positions(const World& world) {
  std::map<std::string, Eigen::Vector3d> out;
  for (const auto& b : world.blocks()) out[b.name] = b.position;
  return out;
}

nlohmann::json key_blocks(const World& world, const std::map<std::string, Eigen::Vector3d>& start) {
  struct Moved {
    const Block* block;
    Eigen::Vector3d from;
    double distance;
  };
  std::vector<Moved> moved;
  for (const auto& b : world.blocks()) {
    if (!b.is_dynamic()) continue;
    const auto it = start.find(b.name);
    if (it == start.end()) continue;
    const double d = (b.position - it->second).norm();
    if (d > kKeyBlockSizeFraction * std::cbrt(b.shape.volume()))
      moved.push_back({&b, it->second, d});
  }
  std::stable_sort(moved.begin(), moved.end(),
                   [](const Moved& x, const Moved& y) { return x.distance > y.distance; });
  nlohmann::json out = nlohmann::json::array();
  for (const auto& m : moved) {
    out.push_back({{"block", m.block->name},
                   {"centroid_at_start_m", {m.from.x(), m.from.y(), m.from.z()}},
                   {"displacement_m", m.distance},
                   {"speed_m_s", m.block->velocity.norm()},
                   {"volume_m3", m.block->shape.volume()}});
  }
  return out;
}

}  // namespace blockdem
