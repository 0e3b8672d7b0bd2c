// The bolts' outputs of a run: bolts.csv at every stage end, their lines in VTK, and their
// counts in summary.json.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "blockdem/world/world.hpp"

namespace blockdem {

/// The columns of bolts.csv.
inline constexpr const char* kBoltColumns[] = {"stage",         "bolt",          "segment",
                                               "block",         "from_m",        "to_m",
                                               "axial_force_N", "shear_force_N", "state"};

/// bolts.csv's rows of this stage end: one per bolt and segment (the stretch of the bolt in one
/// block), with the largest tendon force in the segment (N, tension positive), the dowel's shear
/// force at the joint where the segment ends (N; 0 for the last segment) and the bolt's state.
std::string bolt_rows(const World& world, const std::string& stage);

/// (Re)writes bolts.csv with the header and `rows`.
void write_bolts_csv(const std::filesystem::path& path, const std::string& rows);

/// How many bolts are installed and how many are in each state, for summary.json.
nlohmann::json bolt_counts(const World& world);

}  // namespace blockdem
