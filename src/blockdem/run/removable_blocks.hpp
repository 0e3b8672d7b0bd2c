// Removable blocks of an excavation by block theory: the blocks an excavation stage exposes that
// can move into the opening under gravity, with mode, factor of safety and support force, for
// key_blocks.json (`blockdem keyblocks`) and summary.json (docs/key-blocks.md).
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

#include "blockdem/scenario/scenario.hpp"
#include "blockdem/world/stability.hpp"

namespace blockdem {

/// Factor of safety the support force brings a block to, unless the user asks for another (-).
inline constexpr double kDefaultRequiredFactor = 1.5;

/// The blocks left after excavation stage `stage` (an index of scenario.stages with blocks to
/// remove) that share a face with a block it removes and that gravity can move into the opening
/// (analysis/block_theory.hpp), at their poses in the scenario, lowest factor of safety first:
/// block, stage, volume_m3, weight_N, mode, planes (the planes it slides on), direction,
/// factor_of_safety, support_force_N (a bolt against the motion, to `required_factor`).
/// Contact planes: the faces the block shares with blocks that stay, with the peak friction and
/// cohesion of the joint law the world gives that contact (area-weighted over the neighbours on
/// one plane), and two frictionless planes across each axis a roller boundary holds it along.
/// Gravity: the last one set by the stages up to `stage` (none: an empty list).
nlohmann::json removable_blocks(const Scenario& scenario, std::size_t stage,
                                double required_factor = kDefaultRequiredFactor);

/// One line for a run's progress: how many blocks `removable` (removable_blocks's list) holds,
/// and the first three: name, mode, factor of safety.
std::string removable_blocks_line(const nlohmann::json& removable);

/// A strength reduction's cross-check of block theory: the block that moved most between the
/// search's last stable trial and its first failed one, when an earlier stage of `stages`
/// (summary.json's) lists it in "removable_blocks": block, block_theory_factor, dem_factor (the
/// bracket's middle), dem_bracket, agrees (the block-theory factor lies in the bracket widened by
/// kBlockTheoryAgreement at each end). Null when no listed block moved.
nlohmann::json block_theory_check(const nlohmann::json& stages, const StabilitySearch& search);

/// One line for a run's progress: block_theory_check's block, factors and verdict.
std::string block_theory_check_line(const nlohmann::json& check);

/// Relative widening of a strength reduction's bracket within which block theory agrees (-).
inline constexpr double kBlockTheoryAgreement = 0.02;

}  // namespace blockdem
