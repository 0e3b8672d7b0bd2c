// Scenario runner: stages, outputs, summary.
#include "blockdem/run/scenario_runner.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <optional>

#include "blockdem/io/atomic_file.hpp"
#include "blockdem/io/checkpoint_file.hpp"
#include "blockdem/io/run_recorder.hpp"
#include "blockdem/io/time_history.hpp"
#include "blockdem/numerics/units.hpp"
#include "blockdem/parallel/mpi_run.hpp"
#include "blockdem/run/key_blocks.hpp"
#include "blockdem/run/run_checkpoint.hpp"
#include "blockdem/run/run_files.hpp"
#include "blockdem/run/stability_outputs.hpp"
#include "blockdem/voussoir/recorder.hpp"
#include "blockdem/voussoir/scene.hpp"
#include "blockdem/world/stability.hpp"

namespace blockdem {
namespace {

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string state_bytes(const World& world) {
  StateWriter w;
  world.save_state(w);
  return std::string(w.bytes().begin(), w.bytes().end());
}

/// `passed`: told every few MB how far the reader has come (a mapped checkpoint gives back the
/// pages behind it).
void load_bytes(World& world, std::string_view bytes,
                const std::function<void(std::size_t)>& passed = {}) {
  StateReader r(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  if (passed) r.on_progress(std::size_t{16} << 20, passed);
  world.load_state(r);
  if (!r.done()) throw StateError("saved world state is corrupt (bytes left over)");
}

bool is_checkpoint(const std::string& rel) {
  return rel == kCheckpointName || rel == kPreviousCheckpointName;
}

// run_scenario with the world built by `build` (from the scenario's blocks, copied or moved),
// which is called once, after the restart file has been read.
RunResult run_built(const Scenario& sc, const std::function<World()>& build,
                    const std::filesystem::path& out, const RunCallbacks& cb,
                    const RunControl& control) {
  const auto wall0 = std::chrono::steady_clock::now();
  const VoussoirScene* voussoir = voussoir_scene(sc);
  const bool beam = voussoir != nullptr;
  const int n = static_cast<int>(sc.stages.size());
  const bool checkpoints = control.checkpoint_every > 0 || control.checkpoint_seconds > 0.0;
  if (beam && (checkpoints || !control.restart.empty()))
    throw std::invalid_argument(
        "checkpoints and restarts are not available for voussoir beam scenarios yet");
  // Everything is read and checked before anything is written: the restart file first.
  // A restart file read by this process is mapped, not read into memory: the world's states are
  // read in place and the pages behind the reader given back, so that the file's bytes and the
  // loaded world are never both resident (a payload handed over by the caller is a string).
  std::optional<RunPoint> resume;
  std::shared_ptr<MappedCheckpoint> mapped;
  std::string_view saved_world, saved_before;
  if (!control.restart.empty()) {
    try {
      if (control.restart_payload) {
        resume = decode_run_point(std::move(*control.restart_payload));
        saved_world = resume->world;
        saved_before = resume->before;
      } else {
        mapped = control.restart_file
                     ? control.restart_file
                     : std::make_shared<MappedCheckpoint>(control.restart, control.scenario_hash);
        resume = decode_run_point(mapped->payload(), saved_world, saved_before);
      }
    } catch (const StateError& e) {
      throw CheckpointError(control.restart, e.what());
    }
    if (resume->level >= n) throw CheckpointError(control.restart, "saved stage index is corrupt");
  }
  // A set-up part that took a second or more is reported with its wall time.
  auto setup_done = [&cb](const std::chrono::steady_clock::time_point since,
                          const std::string& what) {
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
    if (cb.setup_done && s >= 1.0) cb.setup_done(what + " in " + fmt("%.1f", s) + " s");
  };
  auto setup0 = std::chrono::steady_clock::now();
  if (cb.progress) cb.progress("setting up the world (initial-overlap check, first contacts)");
  World world = build();  // may throw ScenarioError: nothing written yet
  setup_done(setup0, "world of " + std::to_string(world.blocks().size()) +
                         " blocks set up (initial-overlap check, first contacts' narrow phase)");
  check_time_step(sc, world);
  const auto& distribution = world.settings().distribution;
  const int ranks = distribution ? distribution->size() : 1;
  if (ranks > static_cast<int>(world.blocks().size()))
    throw ScenarioError(sc.file, "",
                        "cannot run " + std::to_string(world.blocks().size()) + " blocks on " +
                            std::to_string(ranks) +
                            " processes: need at least one block per process");
  for (const auto& name : sc.output.history_blocks) {
    if (world.find_block(name) < 0)
      throw ScenarioError(sc.file, "output.history_blocks", "no block named '" + name + "'");
  }
  std::optional<MotionMonitor> resumed_monitor;
  std::optional<World> resumed_before;
  if (resume) {
    const Stage& at = sc.stages[resume->level];
    const bool search = at.find_collapse && at.kind == Stage::Kind::equilibrium;
    setup0 = std::chrono::steady_clock::now();
    if (cb.progress) cb.progress("loading the checkpoint's state");
    try {
      // The world before the searching stage starts from the world as built (a copy: the
      // scenario's blocks may have been moved into the world).
      if (resume->in_stage && search) resumed_before.emplace(world);
      const auto passed = [&](std::string_view part) -> std::function<void(std::size_t)> {
        if (!mapped) return {};
        const auto from = static_cast<std::size_t>(part.data() - mapped->payload().data());
        return [&mapped, from](std::size_t read) { mapped->release_before(from + read); };
      };
      load_bytes(world, saved_world, passed(saved_world));
      if (resume->in_stage) {
        if (at.kind == Stage::Kind::strength_reduction || search != !saved_before.empty())
          throw StateError("saved stage state does not fit the scenario's stage");
        StateReader r(reinterpret_cast<const std::uint8_t*>(resume->monitor.data()),
                      resume->monitor.size());
        resumed_monitor.emplace(r);
        if (search) load_bytes(*resumed_before, saved_before, passed(saved_before));
      }
      // The worlds hold their states now (a large world's state): the bytes go.
      saved_world = saved_before = {};
      std::string().swap(resume->world);
      std::string().swap(resume->before);
      if (mapped) mapped->close();  // also the caller's (restart_file): the file may be replaced
      mapped.reset();
    } catch (const StateError& e) {
      throw CheckpointError(control.restart, e.what());
    }
    setup_done(setup0, "checkpoint's state loaded");
  }
  RunResult res;
  // The folder: what an earlier run left goes; a restart puts back the files written so far.
  clear_earlier_run(out, resume.has_value());
  for (const std::string& rel : list_run_folder(out)) {
    if (!is_checkpoint(rel)) res.foreign_files.insert(rel);
  }
  if (resume) {
    for (auto& [rel, content] : resume->files) {
      std::filesystem::create_directories((out / rel).parent_path());
      write_file_atomically(out / rel, content);
      std::string().swap(content);  // in the folder now
    }
  }
  RunRecorder recorder(out, sc.output.vtk, !beam, resume.has_value(),
                       (control.shared_out.empty() ? out : control.shared_out) / "vtk");
  // Every process writes its VTK pieces into the shared folder: not before process 0 has
  // cleared it of an earlier run and put back a restarted run's files (one collective).
  if (ranks > 1 && sc.output.vtk) distribution->sum({0});
  std::unique_ptr<VoussoirRecorder> beam_recorder;
  VoussoirReference reference;
  if (beam) beam_recorder = std::make_unique<VoussoirRecorder>(out, world);
  auto history = std::make_unique<TimeHistoryWriter>(
      out / "time_history.csv", world,
      TimeHistoryOptions{sc.output.history_interval, sc.output.history_interval_s,
                         sc.output.history_max_rows, sc.output.history_blocks},
      resume.has_value());
  if (resume) {
    // The writers that continue files pick up where the checkpoint left them.
    try {
      StateReader r(reinterpret_cast<const std::uint8_t*>(resume->outputs.data()),
                    resume->outputs.size());
      history->load_state(r);
      recorder.load_state(r);
      if (!r.done()) throw StateError("saved output state is corrupt (bytes left over)");
    } catch (const StateError& e) {
      throw CheckpointError(control.restart, e.what());
    }
  }

  nlohmann::json& summary = res.summary;
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
  nlohmann::json stages = nlohmann::json::array();
  if (resume) {
    summary = nlohmann::json::parse(resume->summary);
    stages = nlohmann::json::parse(resume->stages);
    res.steps_per_stage = resume->steps_per_stage;
    res.factor_of_safety = resume->factor_of_safety;
  }
  // A checkpoint: the world, where the run stands, and the files written so far.
  auto last_checkpoint = std::chrono::steady_clock::now();
  auto write_checkpoint = [&](int level, const StageResume* at, const MotionMonitor* monitor,
                              const World* before) {
    RunPoint p;
    p.level = level;
    p.in_stage = at != nullptr;
    if (at) p.stage = *at;
    if (monitor) {
      StateWriter w;
      monitor->save_state(w);
      p.monitor.assign(w.bytes().begin(), w.bytes().end());
    }
    if (before) p.before = state_bytes(*before);
    p.summary = summary.dump();
    p.stages = stages.dump();
    p.steps_per_stage = res.steps_per_stage;
    p.factor_of_safety = res.factor_of_safety;
    {
      StateWriter w;
      history->save_state(w);
      recorder.save_state(w);
      p.outputs.assign(w.bytes().begin(), w.bytes().end());
    }
    history->flush();  // the rows so far are in the file saved below
    for (const std::string& rel : list_run_folder(out)) {
      if (is_checkpoint(rel) || res.foreign_files.count(rel)) continue;
      p.files.emplace_back(rel, read_file_bytes(out / rel));
    }
    // The world's state streams into the file as it is merged (encode_run_point's layout): no
    // process holds it whole, nor process 0 its bytes.
    const auto [head, tail] = encode_run_point_around_world(p);
    CheckpointFileWriter file(out / kCheckpointName, control.scenario_hash);
    file.append(head);
    const std::uint64_t length_at = file.size();
    file.append(std::string(sizeof(std::uint64_t), '\0'));
    world.save_state_to_root([&](std::string_view bytes) { file.append(bytes); });
    const std::uint64_t length = file.size() - length_at - sizeof(std::uint64_t);
    file.patch(length_at, std::string_view(reinterpret_cast<const char*>(&length), sizeof length));
    file.append(tail);
    file.finish();
  };
  // A checkpoint that every process of an MPI run decides on together (the outputs' writer
  // alone writes the file): the checkpoint does not depend on the number of processes.
  auto checkpoint = [&](int level, const StageResume* at, const MotionMonitor* monitor,
                        const World* before) {
    // A distributed world's state is merged to process 0 without making it whole anywhere
    // (collectively: every process calls this at the same steps, see poll()).
    if (control.write_checkpoint_files)
      write_checkpoint(level, at, monitor, before);
    else
      world.save_state_to_root([](std::string_view) {});
    last_checkpoint = std::chrono::steady_clock::now();
  };
  auto poll = [&] {
    const bool due =
        control.checkpoint_seconds > 0.0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - last_checkpoint).count() >=
            control.checkpoint_seconds;
    return control.poll ? control.poll(world.step_count(), due) : RunPoll{false, due};
  };
  auto interrupt = [&](const std::string& where) {
    res.interrupted = true;
    res.status = "interrupted";
    res.exit_code = 130;
    res.message = "interrupted " + where +
                  (beam ? "; no checkpoint (voussoir beam scenarios have none yet)"
                        : "; continue with --restart " + (out / kCheckpointName).string());
  };
  const int first = resume ? resume->level : 0;
  for (int level = first; level < n; ++level) {
    const Stage& stage = sc.stages[level];
    const bool search_collapse = stage.find_collapse && stage.kind == Stage::Kind::equilibrium;
    const bool reduce = stage.kind == Stage::Kind::strength_reduction;
    const bool resuming = resume && level == first && resume->in_stage;
    // A stage starts from the whole world (the previous stage left each process its own part:
    // the refresh that ended a stage now comes at the next one's start, and none after the last).
    world.synchronize();
    if (!resuming) {
      // A stage boundary (the end of the previous stage): checkpoint, and stop if asked.
      const bool stop = poll().stop;
      if ((checkpoints || stop) && !beam && !(resume && level == first))
        checkpoint(level, nullptr, nullptr, nullptr);
      if (stop) {
        stages.push_back({{"name", stage.name},
                          {"converged", false},
                          {"status", "interrupted"},
                          {"steps", 0},
                          {"time_s", world.time()},
                          {"message", "interrupted before the stage started"}});
        interrupt("before stage '" + stage.name + "'");
        break;
      }
    }
    // The state before the stage, from which every trial of a search starts.
    std::optional<World> before;
    if (resuming && resumed_before) {
      before = std::move(resumed_before);
    } else if (!resuming && (search_collapse || reduce)) {
      before.emplace(world);
    }
    // Where this process took the stage up (a restart continues it part way).
    const auto stage_wall0 = std::chrono::steady_clock::now();
    const double stage_time0 = resuming ? resume->stage.start_time : world.time();
    const std::int64_t stage_steps0 = resuming ? resume->stage.steps_done : 0;
    const double done0 = resuming && stage.kind == Stage::Kind::steps
                             ? static_cast<double>(stage_steps0) / static_cast<double>(stage.steps)
                         : resuming && stage.kind == Stage::Kind::duration
                             ? (world.time() - stage_time0) / stage.duration
                             : 0.0;
    auto progress = [&](const Stage& s, std::int64_t k, const EquilibriumMeasures& m) {
      if (!cb.progress) return;
      // Steps per second of this stage and, where the stage's end is known, the time left.
      const double wall =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - stage_wall0).count();
      std::string line =
          "[" + std::to_string(level + 1) + "/" + std::to_string(n) + "] " + s.name + ": step " +
          std::to_string(k) + ", t = " + fmt("%.4g s", world.time()) + ", unbalanced " +
          fmt("%.2e", m.unbalanced_force_ratio) + ", KE ratio " +
          fmt("%.2e", m.kinetic_energy_ratio) + ", " +
          fmt("%.0f steps/s", wall > 0.0 ? static_cast<double>(k - stage_steps0) / wall : 0.0);
      double done = -1.0;
      if (s.kind == Stage::Kind::steps)
        done = static_cast<double>(k) / static_cast<double>(s.steps);
      if (s.kind == Stage::Kind::duration) done = (world.time() - stage_time0) / s.duration;
      if (done > done0)
        line += fmt(", %.0f%%", 100.0 * done) +
                fmt(", about %.0f s left", wall * (1 - done) / (done - done0));
      else
        line += ", at most " + std::to_string(s.max_steps) + " steps";
      cb.progress(line);
    };
    auto trial_done = [&](const StabilityTrial& t) {
      if (cb.stage_done)
        cb.stage_done("  trial " + fmt("%.4g", t.parameter) + ": " + t.outcome + " after " +
                      std::to_string(t.steps) + " steps");
    };
    if (reduce) {
      // Strength reduction: the stage's outcome is the factor of safety; the world stays in
      // the state before the stage.
      std::vector<int> laws;
      for (int i = 0; i < static_cast<int>(world.joint_laws().size()); ++i) {
        const auto& names = stage.strength.laws;
        if (names.empty() ||
            std::find(names.begin(), names.end(), world.joint_laws()[i].name) != names.end())
          laws.push_back(i);
      }
      StabilitySearch sr;
      try {
        sr = strength_reduction(*before, stage, laws, stage.strength.lower, stage.strength.upper,
                                stage.strength.tolerance, trial_done);
      } catch (const std::invalid_argument& e) {
        // The reason starts with the key ("factor_bounds: ...").
        const std::string what = e.what();
        const auto colon = what.find(": ");
        const std::string key = colon == std::string::npos ? "kind" : what.substr(0, colon);
        throw ScenarioError(sc.file, "stages[" + std::to_string(level + 1) + "]." + key,
                            colon == std::string::npos ? what : what.substr(colon + 2));
      }
      const double F = 0.5 * (sr.last_stable + sr.first_failed);
      summary["factor_of_safety"] = {{"value", F},
                                     {"last_stable", sr.last_stable},
                                     {"first_failed", sr.first_failed},
                                     {"stage", stage.name},
                                     {"tolerance", stage.strength.tolerance},
                                     {"trials", trials_json(sr)}};
      write_trials_csv(out / "strength_reduction.csv", "factor", sr);
      write_mechanism(out, "mechanism", sr, sc.output.vtk);
      res.factor_of_safety = F;
      StageResult result;
      result.name = stage.name;
      result.converged = true;
      for (const auto& t : sr.trials) result.steps += t.steps;
      result.time = world.time();
      result.measures = world.equilibrium();
      res.steps_per_stage.push_back(result.steps);
      stages.push_back({{"name", stage.name},
                        {"converged", true},
                        {"steps", result.steps},
                        {"factor_of_safety", F},
                        {"message", ""}});
      recorder.record(world, result, level);
      if (cb.stage_done)
        cb.stage_done("stage " + std::to_string(level + 1) + "/" + std::to_string(n) + " '" +
                      stage.name + "': factor of safety " + fmt("%.4g", F) + " (stable at " +
                      fmt("%.4g", sr.last_stable) + ", failed at " + fmt("%.4g", sr.first_failed) +
                      ")");
      continue;
    }
    StageResult result;
    bool diverged = false, refused = false;  // refused: a StepFailure
    std::optional<MotionMonitor> monitor;
    if (resuming) monitor = std::move(resumed_monitor);
    // After every step: a checkpoint when one is due or a stop is asked for.
    const AfterStepFn after_step = [&](const StageResume& at) {
      const RunPoll now = poll();
      const bool due =
          now.stop || now.checkpoint ||
          (control.checkpoint_every > 0 && world.step_count() % control.checkpoint_every == 0);
      if (due && !beam) checkpoint(level, &at, &*monitor, before ? &*before : nullptr);
      return now.stop;
    };
    // The step callback reads no whole world: a time_history.csv row of a distributed world
    // comes from reductions and a merge to process 0 (TimeHistoryWriter::write), and a VTK frame
    // is written in pieces, each process its own blocks and contacts.
    StageSync sync;
    sync.after_step_synchronizes = true;
    sync.on_step_reads = [](const World&) { return false; };
    // Nor the stage's end, unless an excavation's key blocks, a voussoir beam's measures or a
    // failure's explanation read it (below): blocks.csv, contacts.csv and the stage's rows are
    // merged to process 0 from each process's own blocks and contacts (RunRecorder::record).
    sync.end_synchronizes = false;
    const auto start_positions =
        stage.remove.empty() ? std::map<std::string, Eigen::Vector3d>{} : block_positions(world);
    try {
      result = run_stage(
          world, stage, progress, &monitor, after_step, resuming ? &resume->stage : nullptr,
          [&](const World& w, const Stage& s, std::int64_t) {
            history->after_step(w, s.name);
            if (sc.output.vtk_interval > 0 && (w.step_count() - 1) % sc.output.vtk_interval == 0)
              recorder.write_frame(w, level);
          },
          &sync);
    } catch (const DivergenceError& e) {
      diverged = true;
      refused = dynamic_cast<const StepFailure*>(&e) != nullptr;
      result.name = stage.name;
      result.time = world.time();
      result.measures = world.equilibrium();
      result.message = e.what();
      result.motion = monitor->report();
    }
    res.steps_per_stage.push_back(result.steps);
    if (result.interrupted) {
      stages.push_back({{"name", stage.name},
                        {"converged", false},
                        {"status", "interrupted"},
                        {"steps", result.steps},
                        {"time_s", world.time()},
                        {"message", result.message}});
      interrupt("in stage '" + stage.name + "' after " + std::to_string(result.steps) + " steps");
      break;
    }
    const bool failed = diverged || !result.converged;
    // Collective, on every process alike (a no-op on a whole world).
    if (failed || !stage.remove.empty() || beam) world.synchronize();
    // A value refused inside a step is numerical whatever the motion before it looked like.
    const FailureKind kind = refused  ? FailureKind::diverged
                             : failed ? classify_failure(*monitor, diverged)
                                      : FailureKind::not_converged;
    if (failed) result.message += ". " + explain_failure(kind, result.motion, world);
    stages.push_back({{"name", stage.name},
                      {"converged", result.converged},
                      {"status", failed ? to_string(kind) : "completed"},
                      {"steps", result.steps},
                      {"time_s", result.time},
                      {"unbalanced_force_ratio", result.measures.unbalanced_force_ratio},
                      {"kinetic_energy_ratio", result.measures.kinetic_energy_ratio},
                      {"contacts", world.contact_count()},
                      {"message", result.message}});
    if (!stage.remove.empty()) {
      // An excavation: the blocks that fell or slid into the opening.
      stages.back()["removed_blocks"] = stage.remove.size();
      stages.back()["key_blocks"] = key_blocks(world, start_positions);
    }
    // Outputs of this level. A level that did not converge is written flagged converged = 0; a
    // diverged one is not written (the rows so far end with the last good state).
    if (!diverged) recorder.record(world, result, level);
    if (!diverged) history->write(world, stage.name);
    history->flush();  // like the other CSV files, whole at every stage end
    if (beam && !diverged) {
      const double g_level = world.settings().gravity.norm() / kOneG;
      if (level == 0) reference = capture_reference(world);
      const VoussoirLevel lv =
          measure_voussoir(world, voussoir->spec, voussoir->layout, reference, g_level);
      beam_recorder->record(world, lv, stage.name, result.converged, result.steps, level);
      if (result.converged) res.levels.push_back(lv);
    }
    if (cb.stage_done) {
      cb.stage_done("stage " + std::to_string(level + 1) + "/" + std::to_string(n) + " '" +
                    stage.name + "': " + (failed ? to_string(kind) : "done") + " after " +
                    std::to_string(result.steps) + " steps (unbalanced " +
                    fmt("%.2e", result.measures.unbalanced_force_ratio) + ")");
    }
    if (!failed) continue;
    res.status = to_string(kind);
    res.message = "stage '" + stage.name + "': " + result.message;
    if (search_collapse && kind != FailureKind::diverged) {
      // Bracket the collapse load between the previous gravity and this stage's.
      const double g_stable = before->settings().gravity.norm() / kOneG;
      const double g_failed = stage.gravity->norm() / kOneG;
      const StabilitySearch cs = find_collapse_load(*before, stage, g_stable, g_failed,
                                                    stage.collapse_tolerance, trial_done);
      summary["collapse"] = {{"last_stable", cs.last_stable},
                             {"first_failed", cs.first_failed},
                             {"unit", "g"},
                             {"stage", stage.name},
                             {"tolerance", stage.collapse_tolerance},
                             {"trials", trials_json(cs)}};
      write_trials_csv(out / "collapse_search.csv", "g_level", cs);
      write_mechanism(out, "collapse_mechanism", cs, sc.output.vtk);
      res.collapse = std::make_pair(cs.last_stable, cs.first_failed);
      res.status = "collapsed";
      res.message = "stage '" + stage.name + "': collapse between " + fmt("%.4g", cs.last_stable) +
                    " g (stable) and " + fmt("%.4g", cs.first_failed) +
                    " g (failed), found by bisection";
      res.exit_code = 0;  // asked to search, and found
    } else {
      res.exit_code = 3;
    }
    if (beam && !res.levels.empty()) {
      res.message += "; last stable level " + fmt("%g g", res.levels.back().g_level);
    }
    break;
  }
  res.steps = world.step_count();
  res.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  summary["status"] = res.status;
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
  const EnergyBudget& energy = world.energy_budget();  // at the last level (docs/outputs.md)
  summary["energy_J"] = {{"kinetic", energy.kinetic},
                         {"elastic", energy.elastic},
                         {"gravity_work", energy.gravity_work},
                         {"load_work", energy.load_work},
                         {"boundary_work", energy.boundary_work},
                         {"friction_dissipation", energy.friction_dissipation},
                         {"damping_dissipation", energy.damping_dissipation},
                         {"residual", energy.residual()}};
  if (beam) {
    summary["voussoir"] = voussoir_summary(voussoir->spec, res.levels);
    // The headline numbers at the top level too, as the contract asks.
    for (const char* key :
         {"g_max", "thrust_N", "midspan_deflection_mm", "equilibrium_residual", "fits"}) {
      if (summary["voussoir"].contains(key)) summary[key] = summary["voussoir"][key];
    }
    summary["lost_equilibrium"] = res.status != "completed";
  }
  // Written last, with the record of every other file the run wrote: a folder without it holds
  // a run still going or one that died.
  history->flush();  // an interrupted stage's rows too, before the record reads the file
  summary["files"] = run_files_record(out, res.foreign_files);
  write_file_atomically(out / "summary.json", summary.dump(2) + "\n");
  return res;
}

}  // namespace

RunResult run_scenario(const Scenario& sc, const std::filesystem::path& out, const RunCallbacks& cb,
                       const RunControl& control) {
  return run_built(
      sc, [&] { return build_world(sc); }, out, cb, control);
}

RunResult run_scenario(Scenario&& sc, const std::filesystem::path& out, const RunCallbacks& cb,
                       const RunControl& control) {
  return run_built(
      sc, [&] { return build_world_taking_blocks(sc); }, out, cb, control);
}

}  // namespace blockdem
