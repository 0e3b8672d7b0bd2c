// Reading the ground water and pseudo-static earthquake keys of a scenario file.
#include "blockdem/scenario/water_input.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace blockdem {

WaterInput read_water(const CheckedTable& t, bool allow_none) {
  WaterInput in;
  if (!t.has("water_table")) {
    if (t.has("water_density"))
      t.fail("water_density", "only beside a water_table in the same table");
    return in;
  }
  if (t.is_string("water_table")) {
    if (!allow_none || t.string("water_table") != "none")
      t.fail("water_table",
             allow_none ? "must be { point, normal }, { points = [...] } or \"none\""
                        : "must be { point = [x, y, z], normal = [nx, ny, nz] } or { points = "
                          "[[x, y, z], ...] }");
    if (t.has("water_density")) t.fail("water_density", "a dry model (\"none\") has no water");
    in.dry = true;
    return in;
  }
  if (!t.is_table("water_table"))
    t.fail("water_table",
           "must be { point = [x, y, z], normal = [nx, ny, nz] } or { points = [[x, y, z], ...] }");
  const CheckedTable w = t.table("water_table");
  GroundWater water;
  try {
    if (w.has("points")) {
      if (w.has("point") || w.has("normal"))
        w.fail("points", "a surface through points takes no point or normal");
      std::vector<Eigen::Vector3d> points;
      for (const auto& r : w.rows("points", 3)) points.emplace_back(r[0], r[1], r[2]);
      water.table = WaterTable::surface(points);
    } else {
      const Eigen::Vector3d point = w.vec3("point");
      const Eigen::Vector3d normal = w.vec3("normal");
      water.table = WaterTable::plane(point, normal);
    }
  } catch (const std::invalid_argument& e) {
    if (w.has("points")) w.fail("points", e.what());
    t.fail("water_table", e.what());
  }
  w.finish();
  water.density = t.number("water_density", water.density);
  if (!(water.density > 0.0) || !std::isfinite(water.density))
    t.fail("water_density",
           "must be a positive, finite density (kg/m^3), got " + number_text(water.density));
  in.water = water;
  return in;
}

std::optional<SeismicLoad> read_seismic(const CheckedTable& t) {
  if (!t.has("seismic_kh") && !t.has("seismic_kv") && !t.has("seismic_direction_deg"))
    return std::nullopt;
  SeismicLoad s;
  const auto finite = [&t](const char* key, double fallback) {
    const double v = t.number(key, fallback);
    if (!std::isfinite(v)) t.fail(key, "must be finite, got " + number_text(v));
    return v;
  };
  s.horizontal = finite("seismic_kh", 0.0);
  s.direction_deg = finite("seismic_direction_deg", 0.0);
  s.vertical = finite("seismic_kv", 0.0);
  if (t.has("seismic_direction_deg") && s.horizontal == 0.0)
    t.fail("seismic_direction_deg", "a direction needs a horizontal coefficient seismic_kh");
  return s;
}

}  // namespace blockdem
