// Scenario runner: reads a restart, builds the world, clears the output folder, drives the stages
// (run/stage_driver.hpp) with the run's outputs and the scene's as observers, and writes the
// summary last.
#include "blockdem/run/scenario_runner.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <optional>

#include "blockdem/io/atomic_file.hpp"
#include "blockdem/io/checkpoint_file.hpp"
#include "blockdem/io/process_memory.hpp"
#include "blockdem/io/run_recorder.hpp"
#include "blockdem/io/time_history.hpp"
#include "blockdem/io/vtu.hpp"
#include "blockdem/numerics/number_text.hpp"
#include "blockdem/parallel/mpi_run.hpp"
#include "blockdem/run/bolt_outputs.hpp"
#include "blockdem/run/dynamic_outputs.hpp"
#include "blockdem/run/key_blocks.hpp"
#include "blockdem/run/removable_blocks.hpp"
#include "blockdem/run/run_checkpoint.hpp"
#include "blockdem/run/run_files.hpp"
#include "blockdem/run/run_restart.hpp"
#include "blockdem/run/run_summary.hpp"
#include "blockdem/run/stability_outputs.hpp"
#include "blockdem/run/stage_driver.hpp"
#include "blockdem/scenario/base_motion_input.hpp"
#include "blockdem/world/time_step_report.hpp"

namespace blockdem {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

std::string state_bytes(const World& world) {
  StateWriter w;
  world.save_state(w);
  return std::string(w.bytes().begin(), w.bytes().end());
}

bool is_checkpoint(const std::string& rel) {
  return rel == kCheckpointName || rel == kPreviousCheckpointName;
}

/// Reports a set-up part that took a second or more, with its wall time.
void report_setup(const RunCallbacks& cb, Clock::time_point since, const std::string& what) {
  const double s = seconds_since(since);
  if (cb.setup_done && s >= 1.0) cb.setup_done(what + " in " + number_text(s, "%.1f") + " s");
}

/// The block that sets the time step: to the callback and into summary.json (`time_step`).
void report_time_step(const World& world, const RunCallbacks& cb, nlohmann::json& summary) {
  const TimeStepReport r = time_step_report(world);
  if (r.block < 0) return;
  summary["time_step"] = {{"block", r.name},
                          {"block_index", r.block},
                          {"volume_m3", r.volume},
                          {"aspect_ratio", r.aspect_ratio},
                          {"critical_step_s", r.critical_step},
                          {"allowed_step_s", r.time_step},
                          {"median_critical_step_s", r.median_step},
                          {"outlier", r.outlier}};
  if (!cb.time_step) return;
  cb.time_step(describe(r), false);
  if (r.outlier) cb.time_step(outlier_warning(r), true);
}

/// Input errors found only once the world is built (nothing written yet).
void check_built_world(const Scenario& sc, const World& world, int ranks) {
  check_time_step(sc, world);
  if (ranks > static_cast<int>(world.blocks().size()))
    throw ScenarioError(sc.file, "",
                        "cannot run " + std::to_string(world.blocks().size()) + " blocks on " +
                            std::to_string(ranks) +
                            " processes: need at least one block per process");
  for (std::size_t k = 0; k < sc.stages.size(); ++k) {
    if (ranks > 1 && !sc.stages[k].bolts.empty())
      throw ScenarioError(sc.file, "bolts",
                          "bolts run on one process (their loads are summed serially): run "
                          "without mpirun");
  }
  check_dynamic_stages(sc, world, ranks);
  for (const auto& name : sc.output.history_blocks) {
    if (world.find_block(name) < 0)
      throw ScenarioError(sc.file, "output.history_blocks", "no block named '" + name + "'");
  }
}

/// The output folder: what an earlier run left goes; a restart puts back the files written so
/// far. Returns the files that were there before and stay (not the run's).
std::set<std::string> prepare_folder(const std::filesystem::path& out, RunPoint* resume) {
  clear_earlier_run(out, resume != nullptr);
  std::set<std::string> foreign;
  for (const std::string& rel : list_run_folder(out)) {
    if (!is_checkpoint(rel)) foreign.insert(rel);
  }
  if (resume) {
    for (auto& [rel, content] : resume->files) {
      std::filesystem::create_directories((out / rel).parent_path());
      write_file_atomically(out / rel, content);
      std::string().swap(content);  // in the folder now
    }
  }
  return foreign;
}

/// The run's own outputs, as an observer of the stages: RunRecorder's tables and VTK frames,
/// time_history.csv, the stability searches' files, the stages' entries of summary.json, the
/// result's counters, and the callbacks' stage lines.
class RunOutputs final : public RunObserver {
 public:
  RunOutputs(const Scenario& sc, const std::filesystem::path& out, const RunCallbacks& cb,
             RunResult& res)
      : sc_(sc), out_(out), cb_(cb), res_(res), stages_(nlohmann::json::array()) {}

  /// The writers, opened in this order: the recorder (`tables`: blocks.csv, contacts.csv and
  /// history.csv; VTK pieces into `pieces`), then the time history.
  void open_recorder(bool tables, bool resumed, const std::filesystem::path& pieces) {
    recorder_ = std::make_unique<RunRecorder>(out_, sc_.output.vtk, tables, resumed, pieces);
  }
  void open_history(const World& world, bool resumed) {
    history_ = std::make_unique<TimeHistoryWriter>(
        out_ / "time_history.csv", world,
        TimeHistoryOptions{sc_.output.history_interval, sc_.output.history_interval_s,
                           sc_.output.history_max_rows, sc_.output.history_blocks,
                           sc_.output.history_bolts, moves_base(sc_.stages)},
        resumed);
  }
  /// A restart: the writers continue their files, the scene's observer (if any) takes up what it
  /// measured, and the summary, stages and counters go on from the checkpoint's.
  void resume(const RunPoint& point, const std::filesystem::path& restart, RunObserver* scene) {
    try {
      StateReader r(reinterpret_cast<const std::uint8_t*>(point.outputs.data()),
                    point.outputs.size());
      history_->load_state(r);
      recorder_->load_state(r);
      // An excavation stage's blocks at its start, for its key blocks at its end.
      resumed_in_stage_ = point.in_stage;
      stage_start_time_ = point.stage.start_time;
      start_positions_.clear();
      for (std::size_t k = r.size(); k-- > 0;) {
        std::string name = r.str();
        start_positions_[std::move(name)] = r.vec();
      }
      load_bolt_outputs(r);
      if (scene) scene->load_state(r);
      if (!r.done()) throw StateError("saved output state is corrupt (bytes left over)");
    } catch (const StateError& e) {
      throw CheckpointError(restart, e.what());
    }
    res_.summary = nlohmann::json::parse(point.summary);
    stages_ = nlohmann::json::parse(point.stages);
    res_.steps_per_stage = point.steps_per_stage;
    res_.factor_of_safety = point.factor_of_safety;
  }
  RunRecorder& recorder() { return *recorder_; }
  /// The excavation stage's blocks at its start, and the bolts' outputs so far (resume reads
  /// them back).
  void save_stage_start(StateWriter& w) const {
    w.size(start_positions_.size());
    for (const auto& [name, x] : start_positions_) {
      w.str(name);
      w.vec(x);
    }
    w.str(bolt_rows_);
    w.pod(static_cast<std::int32_t>(bolt_frames_));
    const std::size_t n = bolts_pvd_ ? bolts_pvd_->frames().size() : 0;
    w.size(n);
    for (std::size_t i = 0; i < n; ++i) {
      w.pod(bolts_pvd_->frames()[i].first);
      w.str(bolts_pvd_->frames()[i].second);
    }
  }
  TimeHistoryWriter& history() { return *history_; }
  nlohmann::json& summary() { return res_.summary; }
  nlohmann::json& stages() { return stages_; }
  const std::string& interrupted_where() const { return interrupted_where_; }
  /// The excavation stages' removable blocks by stage index (block theory, found before the
  /// world took the scenario's blocks).
  void set_removable(std::map<int, nlohmann::json> removable) { removable_ = std::move(removable); }

  /// After every step: a time_history.csv row and a VTK frame when due.
  void after_step(const World& w, const Stage& s, int level) {
    if (history_->due(w)) set_base_columns(w, s);
    history_->after_step(w, s.name);
    if (sc_.output.vtk_interval > 0 && (w.step_count() - 1) % sc_.output.vtk_interval == 0)
      recorder_->write_frame(w, level);
  }

  /// An excavation's key blocks read the world.
  bool reads_world_at_stage_end(const Stage& stage) const override { return !stage.remove.empty(); }
  void on_stage_start(const World& world, const Stage& stage, int) override {
    // A stage resumed from a checkpoint started before it: its start positions came with it.
    if (std::exchange(resumed_in_stage_, false)) return;
    stage_start_time_ = world.time();
    start_positions_ = stage.remove.empty() && stage.kind != Stage::Kind::dynamic
                           ? std::map<std::string, Eigen::Vector3d>{}
                           : block_positions(world);
  }
  void on_stage_end(const World& world, const StageEnd& end) override;
  void on_strength_reduction(const World& world, const Stage& stage, int level,
                             const StabilitySearch& search, const StageResult& result) override;
  void on_collapse_search(const Stage& stage, int, const StabilitySearch& search) override;
  void on_interrupted(const World& world, const Stage& stage, int level,
                      const StageResult* result) override;
  void on_input_error(const World& world, const Stage& stage, int,
                      const std::string& message) override {
    res_.steps_per_stage.push_back(0);
    stages_.push_back({{"name", stage.name},
                       {"converged", false},
                       {"status", "input_error"},
                       {"steps", 0},
                       {"time_s", world.time()},
                       {"message", message}});
  }

 private:
  std::string stage_label(int level, const Stage& stage) const {
    return "stage " + std::to_string(level + 1) + "/" + std::to_string(sc_.stages.size()) + " '" +
           stage.name + "': ";
  }

  const Scenario& sc_;
  const std::filesystem::path out_;
  const RunCallbacks& cb_;
  RunResult& res_;
  nlohmann::json stages_;  ///< summary.json's "stages"
  std::unique_ptr<RunRecorder> recorder_;
  std::unique_ptr<TimeHistoryWriter> history_;
  std::map<std::string, Eigen::Vector3d> start_positions_;  ///< an excavation's blocks at start
  bool resumed_in_stage_ = false;  ///< resume() continues a stage: its start is not now
  double stage_start_time_ = 0.0;  ///< world time at the running stage's start (s)

  /// time_history.csv's base columns at the level of the next row: a dynamic stage's history
  /// at its stage time, zero in other stages.
  void set_base_columns(const World& w, const Stage& s) {
    history_->set_base(s.kind == Stage::Kind::dynamic
                           ? s.base_motion->at(w.level_time() - stage_start_time_)
                           : BaseKinematics{});
  }
  std::string interrupted_where_;
  std::string bolt_rows_;  ///< bolts.csv's rows so far
  int bolt_frames_ = 0;
  std::unique_ptr<PvdCollection> bolts_pvd_;
  std::map<int, nlohmann::json> removable_;  ///< set_removable's lists

  /// save_stage_start's bolt part: bolts.csv's rows and the bolt frames so far.
  void load_bolt_outputs(StateReader& r) {
    bolt_rows_ = r.str();
    bolt_frames_ = r.pod<std::int32_t>();
    std::vector<std::pair<double, std::string>> frames(r.size());
    for (auto& [t, file] : frames) {
      r.pod(t);
      file = r.str();
    }
    if (bolt_frames_ < 0 || frames.size() != static_cast<std::size_t>(bolt_frames_))
      throw StateError("saved bolt frame list is corrupt");
    if (!frames.empty()) {
      bolts_pvd_ = std::make_unique<PvdCollection>(out_ / "vtk" / "bolts.pvd");
      bolts_pvd_->set_frames(std::move(frames));
    }
  }
  /// A stage end's bolts: bolts.csv's rows, a VTK frame of their lines, their counts.
  void write_bolts(const World& world, const std::string& stage) {
    bolt_rows_ += bolt_rows(world, stage);
    write_bolts_csv(out_ / "bolts.csv", bolt_rows_);
    stages_.back()["bolts"] = bolt_counts(world);
    if (!sc_.output.vtk) return;
    if (!bolts_pvd_) bolts_pvd_ = std::make_unique<PvdCollection>(out_ / "vtk" / "bolts.pvd");
    char name[64];
    std::snprintf(name, sizeof name, "bolts_%06d.vtu", bolt_frames_++);
    write_vtu_bolts(out_ / "vtk" / name, world);
    bolts_pvd_->add(world.level_time(), name);
  }
};

void RunOutputs::on_stage_end(const World& world, const StageEnd& end) {
  const Stage& stage = end.stage;
  const StageResult& result = end.result;
  res_.steps_per_stage.push_back(result.steps);
  stages_.push_back(
      {{"name", stage.name},
       {"converged", result.converged},
       // Whether the rock is at rest by the stage's tolerances, whatever its kind
       // (a steps or duration stage converges when its steps or time are done).
       {"in_equilibrium", result.measures.unbalanced_force_ratio <= stage.unbalanced_tolerance &&
                              result.measures.kinetic_energy_ratio <= stage.kinetic_tolerance},
       {"status", end.failure ? to_string(*end.failure) : "completed"},
       {"steps", result.steps},
       {"time_s", result.time},
       {"unbalanced_force_ratio", result.measures.unbalanced_force_ratio},
       {"kinetic_energy_ratio", result.measures.kinetic_energy_ratio},
       {"contacts", world.contact_count()},
       {"broken_bonds", world.broken_bond_count()},
       {"broken_bonds_by_set", broken_bonds_by_set(world, sc_.joint_sets)},
       {"message", end.message()}});
  if (!world.bolts().empty() && !end.diverged) write_bolts(world, stage.name);
  if (!stage.remove.empty()) {
    // An excavation: the blocks that fell or slid into the opening.
    stages_.back()["removed_blocks"] = stage.remove.size();
    stages_.back()["key_blocks"] = key_blocks(world, start_positions_);
    // And those that block theory finds free to move into it (removable_blocks.hpp).
    if (const auto it = removable_.find(end.level); it != removable_.end())
      stages_.back()["removable_blocks"] = it->second;
  }
  if (stage.kind == Stage::Kind::dynamic && !end.diverged)
    stages_.back()["permanent_displacements"] =
        permanent_displacements(world, stage, start_positions_);
  // Outputs of this level. A level that did not converge is written flagged converged = 0; a
  // diverged one is not written (the rows so far end with the last good state).
  if (!end.diverged) recorder_->record(world, result, end.level);
  if (!end.diverged) {
    set_base_columns(world, stage);
    history_->write(world, stage.name);
  }
  history_->flush();  // like the other CSV files, whole at every stage end
  if (cb_.stage_done) {
    cb_.stage_done(stage_label(end.level, stage) +
                   (end.failure ? to_string(*end.failure) : "done") + " after " +
                   std::to_string(result.steps) + " steps (unbalanced " +
                   number_text(result.measures.unbalanced_force_ratio, "%.2e") + ")");
    if (stages_.back().contains("removable_blocks"))
      cb_.stage_done(removable_blocks_line(stages_.back()["removable_blocks"]));
  }
}

void RunOutputs::on_strength_reduction(const World& world, const Stage& stage, int level,
                                       const StabilitySearch& sr, const StageResult& result) {
  const double F = 0.5 * (sr.last_stable + sr.first_failed);
  res_.summary["factor_of_safety"] = {
      {"value", F},
      {"last_stable", sr.last_stable},
      {"first_failed", sr.first_failed},
      {"stage", stage.name},
      {"tolerance", stage.strength.tolerance},
      {"search", sr.extrapolating ? "extrapolate" : "bisect"},
      {"extrapolated",
       sr.extrapolated ? nlohmann::json(*sr.extrapolated) : nlohmann::json(nullptr)},
      {"trials", trials_json(sr)}};
  write_trials_csv(out_ / "strength_reduction.csv", "factor", sr);
  write_mechanism(out_, "mechanism", sr, sc_.output.vtk);
  res_.factor_of_safety = F;
  res_.steps_per_stage.push_back(result.steps);
  stages_.push_back({{"name", stage.name},
                     {"converged", true},
                     {"steps", result.steps},
                     {"factor_of_safety", F},
                     {"message", ""}});
  const nlohmann::json check = block_theory_check(stages_, sr);
  if (!check.is_null()) stages_.back()["block_theory_check"] = check;
  recorder_->record(world, result, level);
  if (cb_.stage_done)
    cb_.stage_done(stage_label(level, stage) + "factor of safety " + number_text(F, "%.4g") +
                   " (stable at " + number_text(sr.last_stable, "%.4g") + ", failed at " +
                   number_text(sr.first_failed, "%.4g") + ")");
  if (cb_.stage_done && !check.is_null()) cb_.stage_done(block_theory_check_line(check));
}

void RunOutputs::on_collapse_search(const Stage& stage, int, const StabilitySearch& cs) {
  // A search of the seismic coefficient k_h (a stage without gravity), else of gravity.
  const bool seismic = !stage.gravity;
  res_.summary["collapse"] = {
      {"last_stable", cs.last_stable},         {"first_failed", cs.first_failed},
      {"unit", seismic ? "seismic_kh" : "g"},  {"stage", stage.name},
      {"tolerance", stage.collapse_tolerance}, {"trials", trials_json(cs)}};
  write_trials_csv(out_ / "collapse_search.csv", seismic ? "seismic_kh" : "g_level", cs);
  write_mechanism(out_, "collapse_mechanism", cs, sc_.output.vtk);
  if (cs.interrupted) {
    res_.summary["collapse"]["interrupted"] = true;
    interrupted_where_ = "in the collapse search of stage '" + stage.name + "' after " +
                         std::to_string(cs.trials.size()) + " trials (bracket so far " +
                         number_text(cs.last_stable, "%.4g") + " to " +
                         number_text(cs.first_failed, "%.4g") + (seismic ? ")" : " g)");
  }
}

void RunOutputs::on_interrupted(const World& world, const Stage& stage, int,
                                const StageResult* result) {
  if (!result) {
    stages_.push_back({{"name", stage.name},
                       {"converged", false},
                       {"status", "interrupted"},
                       {"steps", 0},
                       {"time_s", world.time()},
                       {"message", "interrupted before the stage started"}});
    interrupted_where_ = "before stage '" + stage.name + "'";
    return;
  }
  res_.steps_per_stage.push_back(result->steps);
  stages_.push_back({{"name", stage.name},
                     {"converged", false},
                     {"status", "interrupted"},
                     {"steps", result->steps},
                     {"time_s", world.time()},
                     {"message", result->message}});
  interrupted_where_ =
      stage.kind == Stage::Kind::strength_reduction
          ? "in the strength reduction of stage '" + stage.name + "'"
          : "in stage '" + stage.name + "' after " + std::to_string(result->steps) + " steps";
}

/// Checkpoints (the world, where the run stands, and the files written so far) and the caller's
/// poll: a checkpoint every process of an MPI run decides on together (the outputs' writer alone
/// writes the file), so that it does not depend on the number of processes.
class Checkpoints {
 public:
  Checkpoints(World& world, const std::filesystem::path& out, const RunControl& control,
              RunOutputs& outputs, const RunObserver* scene, const RunResult& res)
      : world_(world), out_(out), control_(control), outputs_(outputs), scene_(scene), res_(res) {}

  /// What the caller's poll says now, with whether the local clock says a checkpoint is due.
  RunPoll poll() const {
    const bool due =
        control_.checkpoint_seconds > 0.0 && seconds_since(last_) >= control_.checkpoint_seconds;
    return control_.poll ? control_.poll(world_.step_count(), due) : RunPoll{false, due};
  }

  /// A distributed world's state is merged to process 0 without making it whole anywhere
  /// (collectively: every process calls this at the same steps, see poll()).
  void take(int level, const StageResume* at, const MotionMonitor* monitor, const World* before) {
    if (control_.write_checkpoint_files)
      write(level, at, monitor, before);
    else
      world_.save_state_to_root([](std::string_view) {});
    last_ = Clock::now();
  }

 private:
  void write(int level, const StageResume* at, const MotionMonitor* monitor, const World* before);

  World& world_;
  const std::filesystem::path out_;
  const RunControl& control_;
  RunOutputs& outputs_;
  const RunObserver* scene_;  ///< the scene's observer (its state follows the outputs'), or null
  const RunResult& res_;
  Clock::time_point last_ = Clock::now();
};

void Checkpoints::write(int level, const StageResume* at, const MotionMonitor* monitor,
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
  p.summary = outputs_.summary().dump();
  p.stages = outputs_.stages().dump();
  p.steps_per_stage = res_.steps_per_stage;
  p.factor_of_safety = res_.factor_of_safety;
  {
    StateWriter w;
    outputs_.history().save_state(w);
    outputs_.recorder().save_state(w);
    outputs_.save_stage_start(w);
    if (scene_) scene_->save_state(w);
    p.outputs.assign(w.bytes().begin(), w.bytes().end());
  }
  outputs_.history().flush();  // the rows so far are in the file saved below
  for (const std::string& rel : list_run_folder(out_)) {
    if (is_checkpoint(rel) || res_.foreign_files.count(rel)) continue;
    p.files.emplace_back(rel, read_file_bytes(out_ / rel));
  }
  // The world's state streams into the file as it is merged (encode_run_point's layout): no
  // process holds it whole, nor process 0 its bytes.
  const auto [head, tail] = encode_run_point_around_world(p);
  CheckpointFileWriter file(out_ / kCheckpointName, control_.fingerprint.at(level, at != nullptr));
  file.append(head);
  const std::uint64_t length_at = file.size();
  file.append(std::string(sizeof(std::uint64_t), '\0'));
  world_.save_state_to_root([&](std::string_view bytes) { file.append(bytes); });
  const std::uint64_t length = file.size() - length_at - sizeof(std::uint64_t);
  file.patch(length_at, std::string_view(reinterpret_cast<const char*>(&length), sizeof length));
  file.append(tail);
  file.finish();
}

/// "1234 steps/s", or three digits below 100 steps per second ("0.412 steps/s": a step of a
/// million blocks takes seconds).
std::string steps_per_second_text(double rate) {
  return number_text(rate, rate >= 100.0 ? "%.0f steps/s" : "%.3g steps/s");
}

/// The status line of stage `level` while it runs: steps per second of this stage and, where
/// the stage's end is known, the time left (measured from where this process took it up).
ProgressFn stage_progress(const Scenario& sc, const World& world, const RunCallbacks& cb, int level,
                          const StageResume* resume) {
  if (!cb.progress) return {};
  const Stage& stage = sc.stages[level];
  const int n = static_cast<int>(sc.stages.size());
  const auto stage_wall0 = Clock::now();
  const double stage_time0 = resume ? resume->start_time : world.time();
  const std::int64_t stage_steps0 = resume ? resume->steps_done : 0;
  const double done0 =
      resume && stage.kind == Stage::Kind::steps
          ? static_cast<double>(stage_steps0) / static_cast<double>(stage.steps)
      : resume && (stage.kind == Stage::Kind::duration || stage.kind == Stage::Kind::dynamic)
          ? (world.time() - stage_time0) / stage.duration
          : 0.0;
  // A strength reduction's trials step copies of the world: their time is not the world's.
  const bool trials = stage.kind == Stage::Kind::strength_reduction;
  return [&world, &cb, level, n, stage_wall0, stage_time0, stage_steps0, done0, trials](
             const Stage& s, std::int64_t k, const EquilibriumMeasures& m) {
    const double wall = seconds_since(stage_wall0);
    std::string line =
        "[" + std::to_string(level + 1) + "/" + std::to_string(n) + "] " + s.name + ": step " +
        std::to_string(k) +
        (trials ? std::string() : ", t = " + number_text(world.time(), "%.4g s")) +
        ", unbalanced " + number_text(m.unbalanced_force_ratio, "%.2e") + ", KE ratio " +
        number_text(m.kinetic_energy_ratio, "%.2e") + ", " +
        steps_per_second_text(wall > 0.0 ? static_cast<double>(k - stage_steps0) / wall : 0.0);
    double done = -1.0;
    if (s.kind == Stage::Kind::steps) done = static_cast<double>(k) / static_cast<double>(s.steps);
    if (s.kind == Stage::Kind::duration || s.kind == Stage::Kind::dynamic)
      done = (world.time() - stage_time0) / s.duration;
    if (done > done0)
      line += number_text(100.0 * done, ", %.0f%%") +
              number_text(wall * (1 - done) / (done - done0), ", about %.0f s left");
    else
      line += ", at most " + std::to_string(s.max_steps) + " steps";
    cb.progress(line);
  };
}

/// The result's status, message and exit code from how the drive ended.
void settle_result(const DriveResult& d, const Scenario& sc, const RunOutputs& outputs,
                   const RunObserver* scene, const std::filesystem::path& out, RunResult& res) {
  res.status = d.status;
  if (d.status == RunStatus::completed) return;
  if (d.status == RunStatus::input_error) {
    res.exit_code = 2;
    std::error_code ec;
    res.message = d.stage.message;
    if (std::filesystem::exists(out / kCheckpointName, ec))
      res.message += "\nthe state before stage '" + d.stage.name + "' is saved in " +
                     (out / kCheckpointName).string() +
                     ": correct the stage and continue from there with --restart " +
                     (out / kCheckpointName).string() + " (docs/restart.md, \"Branching\")";
    return;
  }
  if (d.status == RunStatus::interrupted) {
    res.interrupted = true;
    res.exit_code = 130;
    std::error_code ec;
    const bool checkpoint = std::filesystem::exists(out / kCheckpointName, ec);
    res.message = "interrupted " + outputs.interrupted_where() +
                  (checkpoint ? "; continue with --restart " + (out / kCheckpointName).string()
                              : "; no checkpoint was written (--checkpoint-every keeps one)");
    return;
  }
  const std::string& name = sc.stages[d.level].name;
  if (d.collapse) {
    res.collapse = d.collapse;
    const bool seismic = !sc.stages[d.level].gravity;
    const std::string unit = seismic ? "" : " g";
    res.message = "stage '" + name + "': collapse between " + (seismic ? "k_h = " : "") +
                  number_text(d.collapse->first, "%.4g") + unit + " (stable) and " +
                  number_text(d.collapse->second, "%.4g") + unit + " (failed), found by bisection";
    res.exit_code = 0;  // asked to search, and found
  } else {
    res.message = "stage '" + name + "': " + d.stage.message;
    res.exit_code = 3;
  }
  if (scene) res.message += scene->failure_note();
}

/// What the run does between steps and stages: checkpoints, the caller's stop, time-history rows
/// and VTK frames, status lines. `first`/`resumed`: where a restart takes the run up.
DriveControl run_control(const Scenario& sc, World& world, const RunCallbacks& cb,
                         const RunControl& control, RunOutputs& outputs, Checkpoints& checkpoints,
                         int first, const StageResume* resumed, bool restarted) {
  const bool periodic = control.checkpoint_every > 0 || control.checkpoint_seconds > 0.0;
  DriveControl dc;
  // A stage boundary (the end of the previous stage): checkpoint, and stop if asked.
  dc.at_boundary = [=, &checkpoints](int level) {
    const bool stop = checkpoints.poll().stop;
    if ((periodic || stop) && !(restarted && level == first))
      checkpoints.take(level, nullptr, nullptr, nullptr);
    return stop;
  };
  // After every step: a checkpoint when one is due or a stop is asked for.
  dc.after_step = [=, &world, &control, &checkpoints](int level, const StageResume& at,
                                                      const MotionMonitor& monitor,
                                                      const World* before) {
    const RunPoll now = checkpoints.poll();
    const bool due =
        now.stop || now.checkpoint ||
        (control.checkpoint_every > 0 && world.step_count() % control.checkpoint_every == 0);
    if (due) checkpoints.take(level, &at, &monitor, before);
    return now.stop;
  };
  dc.on_step = [&outputs](const World& w, const Stage& s, int level) {
    outputs.after_step(w, s, level);
  };
  dc.progress = [&sc, &world, &cb, first, resumed](int level) {
    return stage_progress(sc, world, cb, level, level == first ? resumed : nullptr);
  };
  // Between two trials of a search: stop if asked. A strength reduction has recorded nothing
  // yet: the checkpoint before it continues the run by running it again.
  dc.between_trials = [=, &checkpoints](int level, bool before_stage) {
    const bool stop = checkpoints.poll().stop;
    if (stop && before_stage) checkpoints.take(level, nullptr, nullptr, nullptr);
    return stop;
  };
  // And inside a trial, after each of its steps: the trial is dropped and the run stops as it
  // would have before it (a trial may take minutes; a signal does not wait for its end).
  dc.in_trial = dc.between_trials;
  dc.trial_done = [&cb](const StabilityTrial& t) {
    if (cb.stage_done)
      cb.stage_done("  trial " + number_text(t.parameter, "%.4g") + ": " + to_string(t.outcome) +
                    " after " + std::to_string(t.steps) + " steps" +
                    (t.placed_by ? " (placed by the extrapolated critical factor " +
                                       number_text(*t.placed_by, "%.4g") + ")"
                                 : std::string()));
  };
  return dc;
}

/// The step callback reads no whole world: a time_history.csv row of a distributed world comes
/// from reductions and a merge to process 0 (TimeHistoryWriter::write), and a VTK frame is
/// written in pieces, each process its own blocks and contacts. Nor the stage's end, unless an
/// observer reads it (an excavation's key blocks, a scene's measures) or a failure's
/// explanation does: blocks.csv, contacts.csv and the stage's rows are merged to process 0 from
/// each process's own blocks and contacts (RunRecorder::record).
StageSync run_sync() {
  StageSync sync;
  sync.after_step_synchronizes = true;
  sync.on_step_reads = [](const World&) { return false; };
  sync.end_synchronizes = false;
  return sync;
}

/// Drives the stages. An input error found while running (an unusable strength-reduction
/// bracket, a stage's value refused) ends the run there as RunStatus::input_error, with the
/// outputs so far kept; `keep_state_before(level)` then saves the state before a strength
/// reduction (which leaves the world as it was), from which a corrected stage can continue.
DriveResult drive(const Scenario& sc, World& world, DriveStart start, const DriveControl& dc,
                  const std::vector<RunObserver*>& observers,
                  const std::function<void(int)>& keep_state_before) {
  int level = -1;
  std::string message;
  try {
    return drive_stages(world, sc.stages, static_cast<int>(sc.stages.size()), std::move(start), dc,
                        observers);
  } catch (const StrengthReductionError& e) {
    // The reason starts with the key ("factor_bounds: ...").
    const std::string what = e.what();
    const auto colon = what.find(": ");
    const std::string key = colon == std::string::npos ? "kind" : what.substr(0, colon);
    level = e.level;
    message = ScenarioError(sc.file, "stages[" + std::to_string(e.level + 1) + "]." + key,
                            colon == std::string::npos ? what : what.substr(colon + 2))
                  .what();
  }
  const Stage& stage = sc.stages[level];
  for (RunObserver* o : observers) o->on_input_error(world, stage, level, message);
  if (keep_state_before) keep_state_before(level);
  DriveResult ended{RunStatus::input_error, level, {}, true, {}};
  ended.stage.name = stage.name;
  ended.stage.message = message;
  return ended;
}

/// run_scenario with the world built by `build` (from the scenario's blocks, copied or moved),
/// which is called once, after the restart file has been read. Everything is read and checked
/// before anything is written: the restart file first.
RunResult run_with(const Scenario& sc, const std::function<World()>& build,
                   const std::filesystem::path& out, const RunCallbacks& cb,
                   const RunControl& control) {
  const auto wall0 = Clock::now();
  const BuiltScene* scene = sc.built.get();
  Restart restart;
  std::vector<std::string> stage_names;
  for (const Stage& st : sc.stages) stage_names.push_back(st.name);
  read_restart(control, stage_names, restart);
  if (restart.point && cb.setup_done) cb.setup_done(restart.compared);
  RunPoint* resume = restart.point ? &*restart.point : nullptr;
  auto setup0 = Clock::now();
  if (cb.progress) cb.progress("setting up the world (initial-overlap check, first contacts)");
  // Block theory reads the scenario's blocks, which building the world may take.
  std::map<int, nlohmann::json> removable;
  for (std::size_t s = 0; s < sc.stages.size(); ++s) {
    if (!sc.stages[s].remove.empty()) removable[static_cast<int>(s)] = removable_blocks(sc, s);
  }
  World world = build();  // may throw ScenarioError: nothing written yet
  report_setup(cb, setup0,
               "world of " + std::to_string(world.blocks().size()) +
                   " blocks set up (initial-overlap check, first contacts' narrow phase)");
  if (!world.preloads().empty() && cb.progress)
    cb.progress("in-situ stress: " + std::to_string(world.preloads().size()) +
                " joints start with the field's closure and shear (docs/ground-stress.md)");
  const auto& distribution = world.settings().distribution;
  const int ranks = distribution ? distribution->size() : 1;
  check_built_world(sc, world, ranks);
  DriveStart start;
  if (resume) {
    setup0 = Clock::now();
    if (cb.progress) cb.progress("loading the checkpoint's state");
    load_restart(restart, sc, world, control, start);
    report_setup(cb, setup0, "checkpoint's state loaded");
  }
  // What was read to build the world (the scene's blocks, a checkpoint's bytes) is freed: its
  // pages go back to the system, so that the run's resident memory is the world's.
  release_free_heap();
  const ResidentMemory set_up = control.report_memory ? resident_memory() : ResidentMemory{};
  if (control.report_memory) restart_peak();
  RunResult res;
  res.set_up_peak_memory = set_up.peak;
  res.set_up_memory = set_up.current;
  res.foreign_files = prepare_folder(out, resume);
  RunOutputs outputs(sc, out, cb, res);
  outputs.set_removable(std::move(removable));
  outputs.open_recorder(!(scene && scene->writes_own_tables()), resume != nullptr,
                        (control.shared_out.empty() ? out : control.shared_out) / "vtk");
  // Every process writes its VTK pieces into the shared folder: not before process 0 has
  // cleared it of an earlier run and put back a restarted run's files (one collective).
  if (ranks > 1 && sc.output.vtk) distribution->sum({0});
  std::shared_ptr<RunObserver> scene_observer =
      scene ? scene->observer(out, world, resume != nullptr) : nullptr;
  outputs.open_history(world, resume != nullptr);
  res.summary = fresh_summary(sc, world);
  report_time_step(world, cb, res.summary);
  if (resume) {
    outputs.resume(*resume, control.restart, scene_observer.get());
    res.summary["scenario"] = sc.file;  // a branch may continue under another file's name
  }
  Checkpoints checkpoints(world, out, control, outputs, scene_observer.get(), res);
  DriveControl dc = run_control(sc, world, cb, control, outputs, checkpoints, start.level,
                                start.resume, resume != nullptr);
  const StageSync sync = run_sync();
  dc.sync = &sync;
  std::vector<RunObserver*> observers{&outputs};
  if (scene_observer) observers.push_back(scene_observer.get());
  const DriveResult d = drive(sc, world, std::move(start), dc, observers, [&](int level) {
    checkpoints.take(level, nullptr, nullptr, nullptr);
  });
  settle_result(d, sc, outputs, scene_observer.get(), out, res);
  res.steps = world.step_count();
  res.wall_time = seconds_since(wall0);
  finish_summary(res.summary, outputs.stages(), res, world, scene_observer.get(), sc.joint_sets);
  // Written last, with the record of every other file the run wrote: a folder without it holds
  // a run still going or one that died.
  outputs.history().flush();  // an interrupted stage's rows too, before the record reads the file
  res.summary["files"] = run_files_record(out, res.foreign_files);
  write_file_atomically(out / "summary.json", res.summary.dump(2) + "\n");
  if (scene_observer) scene_observer->on_run_end();
  res.scene_output = std::move(scene_observer);
  return res;
}

}  // namespace

RunResult run_scenario(const Scenario& sc, const std::filesystem::path& out, const RunCallbacks& cb,
                       const RunControl& control) {
  return run_with(
      sc, [&] { return build_world(sc); }, out, cb, control);
}

RunResult run_scenario(Scenario&& sc, const std::filesystem::path& out, const RunCallbacks& cb,
                       const RunControl& control) {
  return run_with(
      sc, [&] { return build_world_taking_blocks(sc); }, out, cb, control);
}

}  // namespace blockdem
