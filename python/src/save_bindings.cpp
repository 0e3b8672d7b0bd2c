// Simulation.save and Simulation.load: a simulation's state between two stages in a file, and a
// simulation of the same scenario, or of one whose later stages differ, continued from it.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "blockdem/io/checkpoint_file.hpp"
#include "blockdem/run/scenario_fingerprint.hpp"
#include "blockdem/world/stage.hpp"
#include "blockdem/world/state_stream.hpp"
#include "simulation.hpp"

namespace py = pybind11;

namespace blockdem::python {
namespace {

/// The first bytes of a saved simulation's payload (a run's checkpoint starts otherwise).
constexpr const char* kSavedSimulation = "blockdem simulation 1";

/// The scenario's fingerprint for a saved simulation. Its options differ from any command
/// line's, so that `blockdem run --restart` refuses the file rather than misread it.
ScenarioFingerprint fingerprint(const Scenario& sc) {
  if (sc.text.empty())
    throw py::value_error(
        "this scenario's text is not kept (a file over 8 MiB of listed blocks): a simulation of "
        "it cannot be saved or loaded");
  return scenario_fingerprint(sc.text, "python Simulation.save");
}

void save(Simulation& s, const std::filesystem::path& path) {
  const Running running(s);
  const ScenarioFingerprint f = fingerprint(*s.scenario);
  StateWriter w;
  w.str(kSavedSimulation);
  w.pod(static_cast<std::int32_t>(s.next_stage));
  s.world.save_state(w);
  const std::vector<std::uint8_t>& bytes = w.bytes();
  CheckpointFileWriter file(path, f.at(s.next_stage, false));
  file.append(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  file.finish();
}

std::unique_ptr<Simulation> load(const std::filesystem::path& path,
                                 const std::shared_ptr<Scenario>& given, bool quiet) {
  if (!given) throw py::type_error("Simulation.load(path, scenario): a blockdem.Scenario");
  auto sc = std::make_shared<Scenario>(*given);
  const ScenarioFingerprint f = fingerprint(*sc);
  std::vector<std::string> names;
  for (const Stage& st : sc->stages) names.push_back(st.name);
  auto sim = std::make_unique<Simulation>(sc);
  try {
    const MappedCheckpoint file(path, f.accepted());
    const std::string_view payload = file.payload();
    StateReader r(reinterpret_cast<const std::uint8_t*>(payload.data()), payload.size());
    if (r.str() != kSavedSimulation)
      throw CheckpointError(path,
                            "not a file of Simulation.save (a run's checkpoint continues "
                            "with `blockdem run --restart`)");
    const int level = r.pod<std::int32_t>();
    if (level < 0 || level > static_cast<int>(names.size()))
      throw CheckpointError(path, "saved stage index is corrupt");
    const bool after_last = level == static_cast<int>(names.size());
    if (after_last && f.stages_shared(file.scenario_hash()) < level)
      throw CheckpointError(path,
                            "saved after the last stage of a run whose scenario differs "
                            "from this one");
    const std::string compared =
        after_last ? "restarting from " + path.string() + ", saved after the last stage"
                   : check_restart_point(f, path, file.scenario_hash(), level, false, names);
    sim->world.load_state(r);
    if (!r.done()) throw StateError("saved world state is corrupt (bytes left over)");
    // The ground water and earthquake of the stages run so far, which the state does not hold
    // (a strength reduction's act in its trials only), as a restart of `blockdem run` applies.
    for (int k = 0; k < level; ++k)
      if (sc->stages[k].kind != Stage::Kind::strength_reduction)
        apply_stage_loads(sim->world.settings(), sc->stages[k]);
    sim->next_stage = level;
    if (!quiet)
      py::module_::import("sys").attr("stderr").attr("write")("blockdem: " + compared + "\n");
  } catch (const CheckpointError& e) {
    throw py::value_error(e.what());
  } catch (const StateError& e) {
    throw py::value_error(path.string() + ": " + e.what());
  }
  return sim;
}

}  // namespace

void bind_save(py::class_<Simulation>& cls) {
  cls.def("save", &save, py::arg("path"),
          "Saves the simulation between two stages (the world's state and next_stage) into "
          "`path`, written whole or not at all. Simulation.load continues it, bit for bit.");
  cls.def_static(
      "load", &load, py::arg("path"), py::arg("scenario"), py::arg("quiet") = false,
      "A Simulation of `scenario` in the state Simulation.save wrote into `path`, its "
      "next_stage the saved one. The scenario must be the one saved, or differ only in the "
      "stages from next_stage on (a branch: new bounds, laws or stages); raises ValueError "
      "naming what differs otherwise. Prints what it compared unless quiet.");
}

}  // namespace blockdem::python
