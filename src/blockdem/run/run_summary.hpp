// summary.json's entries that a run writes at its start and at its end (run/scenario_runner.cpp).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "blockdem/run/scenario_runner.hpp"
#include "blockdem/run/stage_driver.hpp"
#include "blockdem/scenario/scenario.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

/// Bonds broken since the start per joint set (by name; "other faces": faces of no set) and
/// cause: {"J1": {"tension": n, "shear": m}, ...}.
nlohmann::json broken_bonds_by_set(const World& world, const std::vector<std::string>& sets);

/// summary.json as a run starts: program, scenario, title, blocks, contact mode, citations.
nlohmann::json fresh_summary(const Scenario& sc, const World& world);

/// summary.json's entries written at the run's end. Collective on a distributed world (every
/// process calls it).
void finish_summary(nlohmann::json& summary, const nlohmann::json& stages, const RunResult& res,
                    const World& world, const RunObserver* scene,
                    const std::vector<std::string>& joint_sets);

}  // namespace blockdem
