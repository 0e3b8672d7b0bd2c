// `blockdem run SCENARIO.toml --out DIR`: runs a scenario's stages and writes its outputs.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <new>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <omp.h>
#include <unistd.h>

#include "blockdem/io/atomic_file.hpp"
#include "blockdem/io/checkpoint_file.hpp"
#include "blockdem/io/output_error.hpp"
#include "blockdem/io/process_memory.hpp"
#include "blockdem/numerics/number_text.hpp"
#include "blockdem/parallel/mpi_run.hpp"
#include "blockdem/rockmass/scene.hpp"
#include "blockdem/run/run_files.hpp"
#include "blockdem/run/run_report.hpp"
#include "blockdem/run/scenario_runner.hpp"
#include "blockdem/run/scene_builders.hpp"
#include "blockdem/voussoir/measures.hpp"
#include "blockdem/voussoir/scene.hpp"
#include "blockdem/world/world.hpp"
#include "commands.hpp"
#include "figures.hpp"
#include "progress.hpp"

namespace blockdem::cli {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string one_decimal(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

struct RunOptions {
  std::string scenario;
  std::string out;
  bool quiet = false;
  bool figures = true;
  std::int64_t max_steps = 0;  ///< > 0: every stage stops after at most this many steps
  int threads = 0;             // 0: OMP_NUM_THREADS, else every core
  std::int64_t checkpoint_every = 0;
  double checkpoint_seconds = 0.0;
  std::string restart;
  bool resume = false;
  std::string shared_out;  ///< the run's output folder when `out` is a process's scratch folder
  bool memory_report = false;
};

// The signal that asked the run to stop (SIGINT, SIGTERM), or 0. A second signal ends the
// program at once, as if it had no handler.
volatile std::sig_atomic_t stop_signal = 0;

extern "C" void on_stop_signal(int sig) {
  if (stop_signal != 0) {
    std::signal(sig, SIG_DFL);
    std::raise(sig);
    return;
  }
  stop_signal = sig;
}

// A test hook (docs/restart.md): BLOCKDEM_TEST_KILL_RANK=R:STEP[:SIGNAL] makes process R of
// the run (0 without a launcher) send itself SIGNAL (KILL, the default, TERM or INT) after
// world step STEP, where the processes agree on stopping: a deterministic stand-in for a
// signal or a crash that reaches one process.
struct KillHook {
  int rank = -1;
  std::int64_t step = -1;
  int signal = SIGKILL;
};

/// Test hook BLOCKDEM_TEST_RESTART_UNSEEN=R: process R of an MPI restart acts as if it could not
/// see the checkpoint file (the first process then sends its bytes to all); -1 when unset.
int unseen_restart_rank_from_environment() {
  const char* text = std::getenv("BLOCKDEM_TEST_RESTART_UNSEEN");
  return text == nullptr ? -1 : std::atoi(text);
}

KillHook kill_hook_from_environment() {
  KillHook hook;
  const char* text = std::getenv("BLOCKDEM_TEST_KILL_RANK");
  if (text == nullptr) return hook;
  const std::string s = text;
  const auto first = s.find(':');
  if (first == std::string::npos)
    throw std::invalid_argument("BLOCKDEM_TEST_KILL_RANK: expected RANK:STEP[:KILL|TERM|INT]");
  const auto second = s.find(':', first + 1);
  hook.rank = std::atoi(s.substr(0, first).c_str());
  hook.step = std::atoll(s.substr(first + 1, second - first - 1).c_str());
  if (second != std::string::npos) {
    const std::string name = s.substr(second + 1);
    if (name == "TERM")
      hook.signal = SIGTERM;
    else if (name == "INT")
      hook.signal = SIGINT;
    else if (name != "KILL")
      throw std::invalid_argument("BLOCKDEM_TEST_KILL_RANK: signal '" + name +
                                  "' is not KILL, TERM or INT");
  }
  return hook;
}

void install_stop_handlers() {
  struct sigaction action = {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int run_one(RunOptions opt, const MpiSession& mpi);

/// The options checked against this machine: a bad one is an input error (exit code 2)
/// before anything is written.
void check_options(const RunOptions& opt) {
  check_thread_count(opt.threads);
}

int run(const RunOptions& opt) {
  check_options(opt);
  // Under mpirun/srun every rank runs the scenario in lockstep (parallel/mpi_run.hpp); rank 0
  // writes the outputs, the others write into a private scratch folder removed at the end.
  const MpiSession mpi;
  if (!mpi.active()) {
    const char* size = std::getenv("OMPI_COMM_WORLD_SIZE");
    if (!size) size = std::getenv("PMI_SIZE");
    if (size && std::atoi(size) > 1) {
      std::cerr << "blockdem: error: started by an MPI launcher with " << size
                << " processes, but this blockdem was built without MPI (BLOCKDEM_MPI=OFF)\n";
      return 2;
    }
    return run_one(opt, mpi);
  }
  RunOptions mine = opt;
  bool scratch_ok = true;
  std::string why;
  if (mpi.rank() != 0) {
    mine.shared_out = opt.out;  // where this process writes its VTK pieces
    mine.quiet = true;
    mine.figures = false;
    std::error_code tmp_error;
    const std::filesystem::path tmp = std::filesystem::temp_directory_path(tmp_error);
    if (tmp_error) {
      // TMPDIR names no folder on this process's node: every process stops before anything is
      // written, with this message once.
      const char* tmpdir = std::getenv("TMPDIR");
      scratch_ok = false;
      why = "process " + std::to_string(mpi.rank()) +
            " has no temporary folder for its scratch files (TMPDIR=" + (tmpdir ? tmpdir : "") +
            "): " + tmp_error.message();
    } else {
      mine.out =
          (tmp / ("blockdem-rank" + std::to_string(mpi.rank()) + "-" + std::to_string(getpid())))
              .string();
    }
  }
  if (!mpi.all_ok(scratch_ok, why)) {
    if (mpi.rank() == 0) std::cerr << "blockdem: error: " << why << "\n";
    return 2;
  }
  std::error_code ec;
  if (mpi.rank() != 0) std::filesystem::remove_all(mine.out, ec);
  int code = 1;
  try {
    code = run_one(mine, mpi);
  } catch (const std::exception& e) {
    // A failure on one process only (a full disk on the writer): the others would wait for it
    // in the next collective, so every process ends now (rank 0's files are whole or absent;
    // summary.json is not written). The system's refusals (exit code 4) are not defects.
    const bool system = dynamic_cast<const OutputError*>(&e) != nullptr ||
                        dynamic_cast<const std::filesystem::filesystem_error*>(&e) != nullptr ||
                        dynamic_cast<const std::bad_alloc*>(&e) != nullptr;
    std::cerr << "blockdem: " << (system ? "error" : "internal error") << " on process "
              << mpi.rank() << ": " << e.what() << "\n";
    // The abort ends this process without returning here: its scratch folder goes first.
    if (mpi.rank() != 0) std::filesystem::remove_all(mine.out, ec);
    mpi.abort(system ? 4 : 1);
  }
  if (mpi.rank() != 0) std::filesystem::remove_all(mine.out, ec);
  // No process ends before the writer has finished: the launcher stops the others as soon as
  // one exits with a non-zero code.
  mpi.barrier();
  return code;
}

/// A restart checkpoint that the run wrote before an error is kept: it is the run's progress
/// (hours of it, maybe), not a result, and a corrected program or input may go on from it.
bool checkpoint_kept(const RunOptions& opt, bool restarting) {
  std::error_code ec;
  return !restarting &&
         std::filesystem::exists(std::filesystem::path(opt.out) / kCheckpointName, ec);
}

/// After an input error found while running: what the run wrote goes (`existed`: the folder was
/// there before the run).
void remove_outputs(const RunOptions& opt, bool existed, bool restarting) {
  std::error_code ec;
  if (restarting) return;  // the folder holds the run being continued: leave it as it is
  if (!existed && !checkpoint_kept(opt, restarting)) {
    std::filesystem::remove_all(opt.out, ec);
    return;
  }
  if (!existed) {
    std::vector<std::filesystem::path> written;
    for (const auto& entry : std::filesystem::directory_iterator(opt.out, ec)) {
      const std::string name = entry.path().filename().string();
      if (name != kCheckpointName && name != kPreviousCheckpointName)
        written.push_back(entry.path());
    }
    for (const auto& path : written) std::filesystem::remove_all(path, ec);
    return;
  }
  for (const std::string& f : run_output_names())
    std::filesystem::remove_all(std::filesystem::path(opt.out) / f, ec);
}

/// The first process checks the checkpoint: one it refuses stops every process (exit code 2).
/// Then each process maps the file itself where it sees the same file (the same checksum), so
/// that no process holds the file's bytes beside its world; where one does not (an output
/// folder only the first process sees), the first process sends the bytes to every process.
/// One process alone leaves it all to the runner, which maps the file. Returns false when every
/// process stops (exit code 2).
bool share_restart(const RunOptions& opt, const MpiSession& mpi, RunControl& control) {
  std::string why;
  std::shared_ptr<MappedCheckpoint> mine;
  std::string checksum(sizeof(std::uint64_t), '\0');
  std::string hash(sizeof(std::uint64_t), '\0');  // the scenario hash the file carries
  if (mpi.rank() == 0) {
    try {
      mine = std::make_shared<MappedCheckpoint>(control.restart, control.fingerprint.accepted());
      const std::uint64_t sum = mine->checksum();
      std::memcpy(checksum.data(), &sum, sizeof sum);
      const std::uint64_t carried = mine->scenario_hash();
      std::memcpy(hash.data(), &carried, sizeof carried);
    } catch (const CheckpointError& e) {
      why = e.what();
    }
  }
  if (!mpi.all_ok(why.empty(), why)) {
    if (mpi.rank() == 0) std::cerr << "blockdem: error: " << why << "\n";
    return false;
  }
  mpi.broadcast(checksum, 0);
  mpi.broadcast(hash, 0);
  std::memcpy(&control.restart_hash, hash.data(), sizeof control.restart_hash);
  if (mpi.rank() != 0 && unseen_restart_rank_from_environment() != mpi.rank()) {
    // --resume: the checkpoint in process 0's output folder (this process's own is scratch).
    const std::filesystem::path file = opt.resume && !opt.shared_out.empty()
                                           ? std::filesystem::path(opt.shared_out) / kCheckpointName
                                           : control.restart;
    try {
      mine = std::make_shared<MappedCheckpoint>(file, control.fingerprint.accepted());
      std::uint64_t first = 0;
      std::memcpy(&first, checksum.data(), sizeof first);
      if (mine->checksum() != first)
        mine.reset();  // another file of that name: not the first process's checkpoint
    } catch (const CheckpointError&) {
      mine.reset();
    }
  }
  if (std::string none; mpi.all_ok(mine != nullptr, none)) {
    control.restart_file = std::move(mine);
  } else {
    control.restart_payload = std::make_shared<std::string>();
    if (mpi.rank() == 0) {
      std::cerr << "blockdem: a process does not see " << control.restart.string()
                << ": process 0 sends it to every process\n";
      control.restart_payload->assign(mine->payload());
    }
    mine.reset();
    mpi.broadcast(*control.restart_payload, 0);
  }
  return true;
}

/// The run's figures (matplotlib scripts in tools/) and its report.md, listed in summary.json's
/// record. A figure that cannot be drawn is a warning of one line, and a line in the report.
void draw_figures(const RunOptions& opt, const RunResult& r, bool beam) {
  namespace fs = std::filesystem;
  const fs::path out(opt.out);
  std::vector<std::string> warnings;
  auto draw = [&](const char* script, const std::vector<std::string>& args, const char* what) {
    std::string why;
    if (run_plot_script(script, args, why)) return;
    std::cerr << "blockdem: warning: no " << what << ": " << why << "\n";
    warnings.push_back(std::string(what) + ": " + why);
  };
  if (opt.figures && beam && !voussoir_levels(r).empty())
    draw("plot_voussoir.py", {"case", opt.out}, "beam figures");
  if (opt.figures && !beam) {
    // The blocks at the last frame, coloured by displacement (key blocks stand out).
    fs::path last;
    std::error_code ec;
    if (fs::is_directory(out / "vtk", ec)) {
      for (const auto& e : fs::directory_iterator(out / "vtk", ec)) {
        const std::string name = e.path().filename().string();
        if (name.rfind("blocks_", 0) == 0 && name.ends_with(".vtu") &&
            (last.empty() || e.path() > last))
          last = e.path();
      }
    }
    if (!last.empty())
      draw("plot_rock_mass.py",
           {"--run-vtk", last.string(), "--png", (out / "blocks_final.png").string()},
           "model view");
    if (fs::is_regular_file(out / "time_history.csv", ec))
      draw("plot_time_history.py", {opt.out}, "time history figure");
  }
  if (opt.figures && r.factor_of_safety) draw("plot_mechanism.py", {opt.out}, "mechanism figure");
  try {
    write_run_report(out, warnings);
  } catch (const std::exception& e) {
    std::cerr << "blockdem: warning: no report.md: " << e.what() << "\n";
  }
  // The figures and the report are part of the run: the record, written last, lists them too.
  update_files_record(opt.out, r.foreign_files);
}

/// --memory-report: one line per process (each prints its own, in one write).
void report_memory(const RunResult& r, const MpiSession& mpi) {
  const std::int64_t run_peak = resident_memory().peak;
  const auto mb = [](std::int64_t bytes) {
    return bytes < 0 ? -1.0 : static_cast<double>(bytes) / 1048576.0;
  };
  std::fprintf(stderr,
               "blockdem: process %d of %d: peak resident memory %.1f MiB while setting up "
               "(reading the scene, building the world; %.1f MiB after it), %.1f MiB while "
               "running the stages\n",
               mpi.rank(), mpi.size(), mb(r.set_up_peak_memory), mb(r.set_up_memory), mb(run_peak));
}

/// The run's last lines on stderr; returns the exit code.
int report_end(const RunOptions& opt, const RunResult& r, const MpiSession& mpi,
               std::chrono::steady_clock::time_point command0) {
  // Process 0 speaks for the run (every process holds the same answer).
  if (mpi.rank() != 0) return r.exit_code;
  if (r.factor_of_safety)
    std::fprintf(stderr, "blockdem: factor of safety %.4g\n", *r.factor_of_safety);
  if (r.collapse) {
    std::fprintf(stderr, "blockdem: collapse between %.4g g (stable) and %.4g g (failed)\n",
                 r.collapse->first, r.collapse->second);
  }
  if (r.exit_code != 0) {
    std::cerr << "blockdem: error: " << r.message << "\n"
              << "blockdem: outputs up to the last good state are in " << opt.out
              << " (summary.json status \"" << to_string(r.status) << "\")\n";
  } else if (!opt.quiet) {
    // The whole command's time: reading the scenario (a large one's rock mass cut) and the run.
    // A stability search's trials step copies of the model: their steps are counted apart (its
    // stage's row in history.csv counts them).
    std::int64_t staged = 0;
    for (const std::int64_t n : r.steps_per_stage) staged += n;
    std::string line = "blockdem: done in " + number_text(seconds_since(command0), "%.2f") +
                       " s, " + std::to_string(r.steps) + " steps";
    if (staged > r.steps)
      line += " (and " + std::to_string(staged - r.steps) + " in the stability search's trials)";
    std::cerr << line << "; outputs in " << opt.out << "\n";
  }
  return r.exit_code;
}
/// Whether the output folder holds a run that completed (its summary.json says so).
bool run_completed(const std::string& out) {
  std::ifstream in(std::filesystem::path(out) / "summary.json");
  if (!in) return false;
  const auto summary = nlohmann::json::parse(in, nullptr, false);
  return !summary.is_discarded() && summary.is_object() && summary.contains("status") &&
         summary["status"] == "completed";
}

int run_one(RunOptions opt, const MpiSession& mpi) {
  Progress progress(!opt.quiet);
  RunCallbacks cb;
  cb.progress = [&](const std::string& s) { progress.update(s); };
  cb.stage_done = [&](const std::string& s) {
    if (!opt.quiet) progress.message(s);
  };
  cb.setup_done = [&](const std::string& s) {
    if (!opt.quiet) progress.message("blockdem: " + s);
  };
  cb.time_step = [&](const std::string& s, bool warning) {
    if (warning && mpi.rank() == 0) progress.message("blockdem: warning: " + s);
    if (!warning && !opt.quiet && mpi.rank() == 0) progress.message("blockdem: " + s);
  };
  const auto command0 = std::chrono::steady_clock::now();
  RunResult r;
  bool beam = false;
  bool rock_mass = false;
  // Some input errors show only while running (strength-reduction bounds that do not bracket
  // the failure): then what the run wrote is removed, so that nothing is left.
  const bool existed = std::filesystem::exists(opt.out);
  const bool restarting = !opt.restart.empty() || opt.resume;
  if (opt.resume && run_completed(opt.shared_out.empty() ? opt.out : opt.shared_out)) {
    // Nothing to resume: running the last checkpoint's stages again would rewrite a finished
    // run (and an interrupt would then mark it interrupted).
    if (mpi.rank() == 0)
      std::cerr << "blockdem: the run in " << opt.out
                << " completed (summary.json status \"completed\"): nothing to resume; to branch "
                   "from its last checkpoint, run into another folder with --restart "
                << (std::filesystem::path(opt.out) / kCheckpointName).string() << "\n";
    return 0;
  }
  // Until every rank has read the scenario, a failure must be agreed on by all (collective).
  bool agreed = false;
  auto agree = [&](bool ok, std::string& why) {
    if (agreed) return ok;
    agreed = true;
    return mpi.all_ok(ok, why);
  };
  // An input error found while running (every process alike): the outputs go, the message once.
  const auto stop_on_error = [&](std::string why) {
    agree(false, why);
    remove_outputs(opt, existed, restarting);
    if (mpi.rank() == 0) {
      std::cerr << "blockdem: error: " << why << "\n";
      if (checkpoint_kept(opt, restarting))
        std::cerr << "blockdem: the run's last checkpoint is kept: "
                  << (std::filesystem::path(opt.out) / kCheckpointName).string() << "\n";
    }
    return 2;
  };
  int agreed_signal = 0;  // the stop signal the processes agreed on
  try {
    // Read and check everything before anything is written.
    progress.update("blockdem: reading " + opt.scenario);
    // A rock mass's blocks are made on as many threads as the run steps with.
    if (opt.threads > 0) omp_set_num_threads(opt.threads);
    Scenario sc = load_scenario(opt.scenario);
    if (const double s = seconds_since(command0); s >= 1.0) {
      // A large scene: reading it (and cutting its rock mass) takes a while.
      cb.setup_done("read " + opt.scenario + " (" + std::to_string(sc.blocks.size()) + " blocks" +
                    (rock_mass_scene(sc) ? ", its rock mass cut" : "") + ") in " + one_decimal(s) +
                    " s");
    }
    if (opt.max_steps > 0) {
      for (auto& stage : sc.stages) {
        stage.max_steps = std::min(stage.max_steps, opt.max_steps);
        stage.min_steps = std::min(stage.min_steps, opt.max_steps);
      }
    }
    if (opt.threads > 0) sc.settings.threads = opt.threads;
    RunControl control;
    control.checkpoint_every = opt.checkpoint_every;
    control.checkpoint_seconds = opt.checkpoint_seconds;
    if (!opt.restart.empty()) control.restart = opt.restart;
    if (opt.resume) control.restart = std::filesystem::path(opt.out) / kCheckpointName;
    // The scenario up to each stage and the options that change results (not --threads).
    control.fingerprint = scenario_fingerprint(
        read_file_bytes(opt.scenario), "max_steps=" + std::to_string(opt.max_steps), opt.scenario);
    beam = voussoir_scene(sc) != nullptr;
    for (const auto& w : mpi.rank() == 0 ? sc.warnings : std::vector<std::string>{})
      std::cerr << "blockdem: warning: " << opt.scenario << ": " << w << "\n";
    rock_mass = rock_mass_scene(sc) != nullptr;
    // The rock mass's sliced cells serve `blockdem generate`; a run has their blocks and reads
    // nothing else of them, so they go before the world is built (they were still held at the
    // peak of a large rock mass's first step).
    if (rock_mass) sc.built.reset();
    if (sc.stages.empty())
      throw ScenarioError(sc.file, "stages", "a run needs at least one [[stages]] entry");
    const KillHook hook = kill_hook_from_environment();
    if (std::string why; !agree(true, why)) {
      // Another rank could not read the scenario: every rank stops with its message.
      if (mpi.rank() == 0) std::cerr << "blockdem: error: " << why << "\n";
      return 2;
    }
    if (!control.restart.empty() && mpi.size() > 1 && !share_restart(opt, mpi, control)) return 2;
    install_stop_handlers();
    // After every step, one reduction over the processes: the largest stop signal any of them
    // received and whether any clock says a timed checkpoint is due. All stop after the same
    // step and take the same checkpoints.
    control.poll = [&mpi, hook, &agreed_signal](std::int64_t steps, bool due) {
      if (hook.rank == mpi.rank() && hook.step == steps) std::raise(hook.signal);
      std::vector<int> flags = {static_cast<int>(stop_signal), due ? 1 : 0};
      mpi.max_over_ranks(flags);
      agreed_signal = flags[0];
      return RunPoll{flags[0] != 0, flags[1] != 0};
    };
    control.write_checkpoint_files = mpi.rank() == 0;
    control.shared_out = opt.shared_out;
    control.report_memory = opt.memory_report;
    sc.settings.distribution = mpi.distribution();
    r = run_scenario(std::move(sc), opt.out, cb, control);
  } catch (const CheckpointError& e) {
    // Found by every process alike (the same bytes): one message.
    if (mpi.rank() == 0) std::cerr << "blockdem: error: " << e.what() << "\n";
    return 2;
  } catch (const ScenarioError& e) {
    return stop_on_error(e.what());
  } catch (const std::invalid_argument& e) {
    return stop_on_error(opt.scenario + ": " + e.what());
  }
  if (r.interrupted) {
    // 128 + the signal, as a shell reports a program ended by it (130 SIGINT, 143 SIGTERM); under
    // MPI the signal the processes agreed on, on every process.
    if (mpi.rank() == 0) std::cerr << "blockdem: " << r.message << "\n";
    return 128 + (agreed_signal != 0 ? agreed_signal : SIGINT);
  }
  draw_figures(opt, r, beam);
  if (opt.memory_report) report_memory(r, mpi);
  return report_end(opt, r, mpi, command0);
}

}  // namespace

void register_run(CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  CLI::App* cmd =
      app.add_subcommand("run", "Run a scenario file (TOML; see docs/scenario-files.md)");
  cmd->add_option("scenario", opt->scenario, "Scenario file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--out", opt->out, "Output folder (created if missing)")->required();
  cmd->add_flag("--quiet", opt->quiet, "No progress output");
  cmd->add_option("--max-steps", opt->max_steps,
                  "Stop every stage after at most N steps (a quick look at a scenario; a stage "
                  "cut short is reported as not converged)")
      ->check(positive_number("steps"));
  cmd->add_option("--threads", opt->threads,
                  "Threads for the step (default: OMP_NUM_THREADS, else every core; at most 64 "
                  "per core and 1024); results are bit-identical for any number")
      ->check(positive_number("threads"));
  cmd->add_option("--checkpoint-every", opt->checkpoint_every,
                  "Write OUT/checkpoint.bdck every N steps and at every stage end (the one "
                  "before is kept as checkpoint.bdck.prev)")
      ->check(positive_number("steps"));
  cmd->add_option("--checkpoint-seconds", opt->checkpoint_seconds,
                  "Write a checkpoint every S seconds of wall time (and at every stage end)")
      ->check(positive_number("seconds"));
  auto* restart = cmd->add_option("--restart", opt->restart,
                                  "Continue the run saved in this checkpoint (same scenario up "
                                  "to the checkpoint's stage, later stages may differ; same "
                                  "--max-steps; any --threads): bit-identical to a run never "
                                  "stopped")
                      ->check(CLI::ExistingFile);
  cmd->add_flag("--resume", opt->resume, "Continue from OUT/checkpoint.bdck (see --restart)")
      ->excludes(restart);
  cmd->add_flag("--memory-report", opt->memory_report,
                "At the end, print each process's peak resident memory while it read the scene "
                "and set up the world, and while it ran the stages (the process's peak is "
                "started again after the set-up)");
  cmd->add_flag("!--no-figures", opt->figures,
                "Do not draw figures (voussoir scenarios draw PNGs with matplotlib)");
  cmd->callback([opt] { set_exit_code(run(*opt)); });
}

}  // namespace blockdem::cli
