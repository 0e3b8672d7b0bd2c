// A run that continues a checkpoint (run/run_restart.hpp).
#include "blockdem/run/run_restart.hpp"

#include <functional>

#include "blockdem/world/state_stream.hpp"

namespace blockdem {
namespace {

/// `passed`: told every few MB how far the reader has come (a mapped checkpoint gives back the
/// pages behind it).
void load_bytes(World& world, std::string_view bytes,
                const std::function<void(std::size_t)>& passed = {}) {
  StateReader r(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  if (passed) r.on_progress(std::size_t{16} << 20, passed);
  world.load_state(r);
  if (!r.done()) throw StateError("saved world state is corrupt (bytes left over)");
}

}  // namespace

void read_restart(const RunControl& control, const std::vector<std::string>& stage_names,
                  Restart& r) {
  if (control.restart.empty()) return;
  try {
    if (control.restart_payload) {
      r.point = decode_run_point(std::move(*control.restart_payload));
      r.world = r.point->world;
      r.before = r.point->before;
    } else {
      r.mapped = control.restart_file ? control.restart_file
                                      : std::make_shared<MappedCheckpoint>(
                                            control.restart, control.fingerprint.accepted());
      r.point = decode_run_point(r.mapped->payload(), r.world, r.before);
    }
  } catch (const StateError& e) {
    throw CheckpointError(control.restart, e.what());
  } catch (const CheckpointScenarioError& e) {
    // A dynamic stage's record counts with its bytes: an edited record is a reason to name.
    throw CheckpointScenarioError(control.restart, e.reason() + records_note(control.fingerprint));
  }
  if (r.point->level < 0) throw CheckpointError(control.restart, "saved stage index is corrupt");
  r.compared = check_restart_point(
      control.fingerprint, control.restart,
      control.restart_payload ? control.restart_hash : r.mapped->scenario_hash(), r.point->level,
      r.point->in_stage, stage_names);
  if (r.point->level >= static_cast<int>(stage_names.size()))
    throw CheckpointError(control.restart, "saved stage index is corrupt");
}

void load_restart(Restart& restart, const Scenario& sc, World& world, const RunControl& control,
                  DriveStart& start) {
  RunPoint& point = *restart.point;
  const Stage& at = sc.stages[point.level];
  const bool search = at.find_collapse && at.kind == Stage::Kind::equilibrium;
  std::shared_ptr<MappedCheckpoint>& mapped = restart.mapped;
  try {
    // The world before the searching stage starts from the world as built (a copy: the
    // scenario's blocks may have been moved into the world).
    if (point.in_stage && search) start.before.emplace(world);
    const auto passed = [&](std::string_view part) -> std::function<void(std::size_t)> {
      if (!mapped) return {};
      const auto from = static_cast<std::size_t>(part.data() - mapped->payload().data());
      return [&mapped, from](std::size_t read) { mapped->release_before(from + read); };
    };
    load_bytes(world, restart.world, passed(restart.world));
    if (point.in_stage) {
      if (at.kind == Stage::Kind::strength_reduction || search != !restart.before.empty())
        throw StateError("saved stage state does not fit the scenario's stage");
      StateReader r(reinterpret_cast<const std::uint8_t*>(point.monitor.data()),
                    point.monitor.size());
      start.monitor.emplace(r);
      if (search) load_bytes(*start.before, restart.before, passed(restart.before));
    }
    // The ground water and earthquake the stages run so far set, which the saved states do not
    // hold: the world's and the state before a searching stage's up to the stage before. A
    // strength reduction's act in its trials only.
    const auto apply_up_to = [&sc](WorldSettings& settings, int end) {
      for (int k = 0; k < end; ++k) {
        const Stage& st = sc.stages[static_cast<std::size_t>(k)];
        if (st.kind != Stage::Kind::strength_reduction) apply_stage_loads(settings, st);
      }
    };
    // This stage's water and seismic load run_stage takes from its ramp (world/stage.hpp).
    apply_up_to(world.settings(), point.level);
    if (start.before) apply_up_to(start.before->settings(), point.level);
    // The worlds hold their states now (a large world's state): the bytes go.
    restart.world = restart.before = {};
    std::string().swap(point.world);
    std::string().swap(point.before);
    if (mapped) mapped->close();  // also the caller's (restart_file): the file may be replaced
    mapped.reset();
  } catch (const StateError& e) {
    throw CheckpointError(control.restart, e.what());
  }
  start.level = point.level;
  if (point.in_stage) start.resume = &point.stage;
}

}  // namespace blockdem
