// A dynamic stage's keys: `base_motion` (an acceleration record in a CSV file, or a named pulse)
// and the stage's duration and damping.
#pragma once

#include <filesystem>
#include <set>
#include <string>

#include "blockdem/dynamics/base_motion.hpp"
#include "blockdem/scenario/checked_table.hpp"
#include "blockdem/scenario/scenario.hpp"
#include "blockdem/world/stage.hpp"

namespace blockdem {

/// Reads an acceleration record: a CSV file with the header time_s, ax_m_s2, ay_m_s2, az_m_s2
/// (any order), one sample a line, `#` comment lines. Throws std::invalid_argument naming the
/// file, the line and the reason (a missing column, a value that is not a finite number, times
/// that do not increase strictly).
BaseMotion read_acceleration_record(const std::filesystem::path& path);

/// A dynamic stage's `base_motion` = { group = "base", file = "accel.csv" } (a path relative to
/// the scenario file) or { group = "base", pulse = "rectangular" | "sine" | "ricker",
/// amplitude_m_s2, direction = [1, 0, 0], and duration (rectangular), period and cycles (sine),
/// frequency and peak_time (ricker) }, and its `duration` (default: the history's end). Throws
/// ScenarioError naming the file, the key and the reason.
void read_dynamic_stage(const CheckedTable& t, const std::set<std::string>& groups, Stage& s);

/// After every stage is read: each dynamic stage's damping_after (the damping before it), and a
/// warning for a history that leaves the base moving.
void finish_dynamic_stages(Scenario& sc);

/// Checks against the built world (nothing written yet): a dynamic stage's base group holds only
/// fixed blocks, and the run is on one process (`ranks`). Throws ScenarioError naming the stage.
void check_dynamic_stages(const Scenario& sc, const World& world, int ranks);

}  // namespace blockdem
