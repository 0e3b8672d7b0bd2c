// The permanent displacements a dynamic stage leaves, for summary.json.
#include "blockdem/run/dynamic_outputs.hpp"

#include <algorithm>

namespace blockdem {

namespace {

nlohmann::json vec(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

}  // namespace

nlohmann::json permanent_displacements(const World& world, const Stage& stage,
                                       const std::map<std::string, Eigen::Vector3d>& start) {
  const std::string& group = stage.base_motion->group;
  // The base's blocks all move alike: the first one's displacement.
  Eigen::Vector3d base = Eigen::Vector3d::Zero();
  for (const Block& b : world.blocks()) {
    const auto it = start.find(b.name);
    if (b.group() != group || it == start.end()) continue;
    base = b.position - it->second;
    break;
  }
  nlohmann::json blocks = nlohmann::json::array();
  for (const Block& b : world.blocks()) {
    const auto it = start.find(b.name);
    if (!b.is_dynamic() || it == start.end()) continue;
    const Eigen::Vector3d u = b.position - it->second;
    blocks.push_back({{"block", b.name},
                      {"displacement_m", vec(u)},
                      {"relative_displacement_m", vec(u - base)}});
  }
  return {{"base_group", group}, {"base_displacement_m", vec(base)}, {"blocks", blocks}};
}

bool moves_base(const std::vector<Stage>& stages) {
  return std::any_of(stages.begin(), stages.end(),
                     [](const Stage& st) { return st.kind == Stage::Kind::dynamic; });
}

}  // namespace blockdem
