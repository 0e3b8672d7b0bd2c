// Stability search outputs (docs/stability.md).
#include "blockdem/run/stability_outputs.hpp"

#include <algorithm>

#include "blockdem/io/csv.hpp"
#include "blockdem/io/vtk.hpp"

namespace blockdem {

void write_trials_csv(const std::filesystem::path& path, const std::string& parameter,
                      const StabilitySearch& search) {
  CsvWriter csv(path, {"trial", parameter, "stable", "outcome", "steps", "max_displacement_m",
                       "displacement_limit_m", "max_speed_m_s", "kinetic_energy_J", "load_work_J",
                       "moving_blocks", "acceleration_m_s2"});
  int i = 0;
  for (const auto& t : search.trials) {
    csv.cell(++i)
        .cell(t.parameter)
        .cell(t.stable ? 1 : 0)
        .cell(to_string(t.outcome))
        .cell(static_cast<long long>(t.steps))
        .cell(t.motion.max_displacement)
        .cell(t.motion.displacement_limit)
        .cell(t.motion.max_speed)
        .cell(t.motion.kinetic_energy)
        .cell(t.motion.load_work)
        .cell(static_cast<long long>(t.motion.moving_blocks.size()))
        .cell(t.acceleration);
    csv.end_row();
  }
}

void write_mechanism(const std::filesystem::path& dir, const std::string& stem,
                     const StabilitySearch& search, bool vtk) {
  if (!search.failed_world) return;
  const World& w = *search.failed_world;
  const MotionReport* motion = nullptr;
  for (const auto& t : search.trials) {
    if (!t.stable && t.parameter == search.first_failed) motion = &t.motion;
  }
  if (vtk) {
    std::filesystem::create_directories(dir / "vtk");
    write_vtk_blocks(dir / "vtk" / (stem + ".vtk"), w);
  }
  CsvWriter csv(dir / (stem + ".csv"), {"block", "moving", "x_m", "z_m", "ux_mm", "uy_mm", "uz_mm",
                                        "vx_m_s", "vy_m_s", "vz_m_s", "speed_m_s"});
  for (const auto& b : w.blocks()) {
    if (!b.is_dynamic()) continue;
    const bool moving =
        motion && std::find(motion->moving_blocks.begin(), motion->moving_blocks.end(), b.index) !=
                      motion->moving_blocks.end();
    const Eigen::Vector3d u = 1e3 * (b.position - b.initial_position);
    csv.cell(b.name)
        .cell(moving ? 1 : 0)
        .cell(b.position.x() + w.settings().origin.x())
        .cell(b.position.z() + w.settings().origin.z())
        .cell(u.x())
        .cell(u.y())
        .cell(u.z())
        .cell(b.velocity.x())
        .cell(b.velocity.y())
        .cell(b.velocity.z())
        .cell(b.velocity.norm());
    csv.end_row();
  }
}

nlohmann::json trials_json(const StabilitySearch& search) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& t : search.trials) {
    a.push_back(
        {{"value", t.parameter},
         {"stable", t.stable},
         {"outcome", to_string(t.outcome)},
         {"steps", t.steps},
         {"max_displacement_m", t.motion.max_displacement},
         {"acceleration_m_s2", t.acceleration},
         {"placed_by", t.placed_by ? nlohmann::json(*t.placed_by) : nlohmann::json(nullptr)}});
  }
  return a;
}

}  // namespace blockdem
