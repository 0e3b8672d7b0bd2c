// A dynamic stage's entry in summary.json: the base's displacement and each free block's
// permanent displacement over the stage, absolute and relative to the base.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "blockdem/world/stage.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

/// For a Stage::Kind::dynamic stage that has ended: { "base_group", "base_displacement_m",
/// "blocks": [{ "block", "displacement_m", "relative_displacement_m" }, ...] } with the free
/// blocks in the world's order; displacements from the centroids at the stage start (`start`),
/// vectors in m, world axes. Relative: the block's displacement minus the base's.
nlohmann::json permanent_displacements(const World& world, const Stage& stage,
                                       const std::map<std::string, Eigen::Vector3d>& start);

/// Whether a stage moves a base (a Stage::Kind::dynamic stage): time_history.csv's base columns.
bool moves_base(const std::vector<Stage>& stages);

}  // namespace blockdem
