// The ground water and pseudo-static earthquake keys of a scenario file ([settings] and
// [[stages]]): water_table, water_density, seismic_kh, seismic_direction_deg, seismic_kv.
#pragma once

#include <optional>

#include "blockdem/scenario/checked_table.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

/// What a table's water keys say: nothing, a water table with its density, or (a stage's
/// water_table = "none") no water from then on.
struct WaterInput {
  std::optional<GroundWater> water;
  bool dry = false;
};

/// Reads `water_table` (a plane { point = [x, y, z], normal = [nx, ny, nz] }, a surface
/// { points = [[x, y, z], ...] }, or with `allow_none` the string "none") and `water_density`
/// (kg/m^3, default 1000; only beside a water table). Throws ScenarioError naming the file, the
/// key and the reason.
WaterInput read_water(const CheckedTable& t, bool allow_none);

/// Reads seismic_kh, seismic_direction_deg (default 0) and seismic_kv (default 0); empty when
/// none is given. Throws ScenarioError for a value that is not finite.
std::optional<SeismicLoad> read_seismic(const CheckedTable& t);

}  // namespace blockdem
