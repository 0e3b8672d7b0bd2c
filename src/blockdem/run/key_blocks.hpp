// Key blocks of an excavation: the blocks that move out of place while an excavation stage runs
// (they fall or slide into the opening), for summary.json.
#pragma once

#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "blockdem/world/world.hpp"

namespace blockdem {

/// A key block moved more than this fraction of its size V^(1/3) during the excavation stage.
inline constexpr double kKeyBlockSizeFraction = 0.1;

/// Block centroids by name (m), taken when a stage starts.
std::map<std::string, Eigen::Vector3d> block_positions(const World& world);

/// The blocks that moved more than kKeyBlockSizeFraction V^(1/3) since `start`, largest
/// displacement first: name, centroid at the start (m), displacement (m), speed now (m/s),
/// volume (m^3).
nlohmann::json key_blocks(const World& world, const std::map<std::string, Eigen::Vector3d>& start);

}  // namespace blockdem
