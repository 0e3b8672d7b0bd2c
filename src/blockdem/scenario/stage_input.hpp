// Reading a scenario's [[stages]] (scenario.cpp reads the rest of the file).
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "blockdem/scenario/checked_table.hpp"
#include "blockdem/scenario/scenario.hpp"
#include "blockdem/world/stage.hpp"

namespace blockdem {

/// What a stage's keys may name besides blocks and excavations: joint laws, joint sets, groups.
struct StageNames {
  const std::map<std::string, int>& laws;
  const std::vector<std::string>& joint_sets;
  const std::set<std::string>& groups;
};

/// A stage's `set_laws`: [{ joint_set = "J1", law = "J1_peak" }, { group = "rock", law =
/// "elastic" }, ...]. "elastic" (unless a law has that name) is each face's elastic twin.
std::vector<LawChange> read_law_changes(const CheckedTable& t, const StageNames& known);

/// One [[stages]] entry, every key checked. Throws ScenarioError naming the file and key.
Stage read_stage(const CheckedTable& t, const std::set<std::string>& block_names,
                 const std::map<std::string, std::vector<std::string>>& excavations,
                 const StageNames& known);

/// The elastic twin of a law, "NAME (elastic)": the same stiffnesses, with a strength no load
/// reaches (cohesion and tensile strength of 1e30 Pa), so that no joint slips, opens a bond or
/// breaks while it holds.
JointLaw elastic_twin(const JointLaw& law);
/// When a stage makes laws elastic: every joint law gets its twin (elastic_twin).
void add_elastic_twins(Scenario& sc);

}  // namespace blockdem
