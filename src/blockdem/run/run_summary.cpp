// summary.json's entries that a run writes at its start and at its end.
#include "blockdem/run/run_summary.hpp"

#include <array>
#include <cstdint>

#include "blockdem/parallel/mpi_run.hpp"
#include "blockdem/run/bolt_outputs.hpp"

namespace blockdem {

nlohmann::json broken_bonds_by_set(const World& world, const std::vector<std::string>& sets) {
  nlohmann::json by_set = nlohmann::json::object();
  const auto& table = world.broken_bonds_by_set();
  for (std::size_t k = 0; k <= sets.size() || k < table.size(); ++k) {
    const std::array<std::int64_t, 2> row =
        k < table.size() ? table[k] : std::array<std::int64_t, 2>{};
    const std::string name = k == 0                ? "other faces"
                             : k - 1 < sets.size() ? sets[k - 1]
                                                   : "set " + std::to_string(k - 1);
    by_set[name] = {{"tension", row[0]}, {"shear", row[1]}};
  }
  return by_set;
}

nlohmann::json fresh_summary(const Scenario& sc, const World& world) {
  nlohmann::json summary;
  summary["program"] = "blockdem";
  summary["scenario"] = sc.file;
  summary["title"] = sc.title;
  summary["blocks"] = world.blocks().size();
  summary["contact_mode"] = to_string(sc.settings.contact_mode);
  summary["citations"] = {
      "Boon C.W., Houlsby G.T., Utili S. (2012) A new algorithm for contact detection between "
      "convex "
      "polygonal and polyhedral particles in the discrete element method. Computers and "
      "Geotechnics 44:73-82.",
      "Boon C.W., Houlsby G.T., Utili S. (2015) DEM modelling of a jointed rock beam with emphasis "
      "on "
      "interface properties. Geotechnique Letters 5:49-55.",
      "Cundall P.A. (1987) Distinct element models of rock and soil structure. In: Analytical and "
      "Computational Methods in Engineering Rock Mechanics, ch. 4 (local non-viscous damping)."};
  return summary;
}

void finish_summary(nlohmann::json& summary, const nlohmann::json& stages, const RunResult& res,
                    const World& world, const RunObserver* scene,
                    const std::vector<std::string>& joint_sets) {
  const auto& distribution = world.settings().distribution;
  const int ranks = distribution ? distribution->size() : 1;
  summary["status"] = to_string(res.status);
  summary["message"] = res.message;
  summary["stages"] = stages;
  summary["steps"] = res.steps;
  summary["time_s"] = world.time();
  summary["wall_time_s"] = res.wall_time;
  // What describes the machine, not the run: not in the checkpoints, which any number of
  // threads and processes continue.
  summary["threads"] = world.thread_count();
  summary["ranks"] = ranks;
  summary["contacts"] = world.contact_count();
  summary["broken_bonds"] = world.broken_bond_count();
  summary["broken_bonds_by_set"] = broken_bonds_by_set(world, joint_sets);
  if (!world.bolts().empty()) summary["bolts"] = bolt_counts(world);
  // Every excavation stage's key blocks (from `stages`, which a restart carries on).
  nlohmann::json all_key_blocks = nlohmann::json::array();
  bool any_excavation = false;
  for (const auto& st : stages) {
    if (!st.contains("key_blocks")) continue;
    any_excavation = true;
    for (nlohmann::json e : st["key_blocks"]) {
      e["stage"] = st["name"];
      all_key_blocks.push_back(std::move(e));
    }
  }
  if (any_excavation) summary["key_blocks"] = all_key_blocks;
  if (ranks > 1)  // per process, in rank order (a collective call: every process gets here)
    summary["distribution"] = gather_distribution_json(*distribution, world.distribution_stats());
  // The ground water's force on the free blocks (collective: every process gets here).
  const Eigen::Vector3d water = world.total_water_force();
  summary["water_force_N"] = water.norm();
  summary["water_force_vector_N"] = {water.x(), water.y(), water.z()};
  const EnergyBudget& energy = world.energy_budget();  // at the last level (docs/outputs.md)
  summary["energy_J"] = {{"kinetic", energy.kinetic},
                         {"elastic", energy.elastic},
                         {"gravity_work", energy.gravity_work},
                         {"load_work", energy.load_work},
                         {"water_work", energy.water_work},
                         {"seismic_work", energy.seismic_work},
                         {"boundary_work", energy.boundary_work},
                         {"friction_dissipation", energy.friction_dissipation},
                         {"damping_dissipation", energy.damping_dissipation},
                         {"residual", energy.residual()}};
  if (world.settings().contact_damping > 0.0)
    summary["energy_J"]["contact_damping"] = energy.contact_damping;
  if (scene) scene->add_to_summary(summary, res.status);
}

}  // namespace blockdem
