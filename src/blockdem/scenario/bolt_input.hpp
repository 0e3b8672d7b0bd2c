// The [[bolts]] and [[bolt_patterns]] of a scenario: rock bolts and cables, each installed by a
// stage.
#pragma once

#include "blockdem/scenario/checked_table.hpp"
#include "blockdem/scenario/scenario.hpp"

namespace blockdem {

/// Reads every [[bolts]] entry into the `bolts` of the stage its `install_stage` names, and
/// checks its line against the blocks left at that stage (those no earlier stage nor that one
/// removes): the collar in a block, the far end in the rock, at least one joint crossed. Call
/// after the stages and blocks are read, before the scene is moved to another origin. Throws
/// ScenarioError naming the file, "bolts[K].KEY" and the reason.
/// Then every [[bolt_patterns]] entry: the [[bolts]] keys of the element and its `length` and
/// `install_stage`, an `excavation` (a name of Scenario::excavations) and `spacing = [along,
/// around]` (m): on each face where a block of the excavation touches a block that stays, bolts
/// normal to the face into the rock on a lattice of that spacing, named "NAME-1", "NAME-2", ...
/// (`name`, default "pattern K"). Bolts that cross no joint or leave the model are left out,
/// with a warning.
void read_bolts(const CheckedTable& root, Scenario& sc);

}  // namespace blockdem
