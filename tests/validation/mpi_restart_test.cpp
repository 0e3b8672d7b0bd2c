// Stopping, restarting and failing under `mpirun -np K blockdem run`: a stop signal that reaches
// one process stops every process after the same step (the processes agree after every step),
// with the checkpoint and summary.json of a one-process run stopped there; that checkpoint, the
// same bytes for any K but for the VTK pieces it carries, continues under 1, 2 or 3 processes to
// the outputs of the run that was never stopped; a process killed outright leaves the last whole
// checkpoint and no summary.json. The oracle is always the one-process run. Signals and kills
// come from the test hook BLOCKDEM_TEST_KILL_RANK=R:STEP[:SIGNAL] (process R sends itself SIGNAL
// after step STEP), so that every run stops at a known step. Skipped when the build has no MPI
// (BLOCKDEM_MPI=OFF).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "blockdem/io/atomic_file.hpp"
#include "blockdem/io/checkpoint_file.hpp"
#include "blockdem/run/run_checkpoint.hpp"
#include "blockdem/run/run_files.hpp"
#include "blockdem/run/scenario_fingerprint.hpp"
#include "support/mpi_launcher.hpp"
#include "support/sanitized_run.hpp"
#include "unit/run/restart_support.hpp"

namespace blockdem::test {
namespace {

namespace fs = std::filesystem;

// The restart scenario (three blocks with slip history on a base; settle 400 steps, tilt 600,
// then a steps stage of kLongSteps), with rows of time_history.csv and VTK frames inside stages.
constexpr long long kLongSteps = 1500;
// Where the stops and the kill fall: in the last stage (it starts after step 1000), between
// the checkpoints every 500 steps in the kill test.
constexpr int kStopStep = 1300;
constexpr int kKillStep = 1250;

/// `blockdem run SCENARIO --out OUT ARGS` on `ranks` processes (0: no launcher), with `env`
/// (-x NAME=VALUE for mpirun, NAME=VALUE before the program without it). Returns the exit code
/// (-1: no normal exit).
int run(int ranks, const fs::path& scenario, const fs::path& out, const std::string& args,
        const std::string& env_name = "", const std::string& env_value = "") {
  std::ostringstream c;
  if (ranks == 0) {
    if (!env_name.empty()) c << env_name << "=" << env_value << " ";
  } else {
    c << mpirun(ranks, env_name.empty() ? "" : "-x " + env_name + "=" + env_value + " ");
  }
  c << BLOCKDEM_CLI_PATH << " run '" << scenario.string() << "' --out '" << out.string()
    << "' --quiet --no-figures --threads 1 " << args << " > /dev/null 2>&1";
  const int status = std::system(c.str().c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// Every output file of a run folder (checkpoints and VTK frames left out) -> its FNV-1a 64;
/// summary.json without what describes the machine (wall time, threads, ranks and the
/// per-process figures) and without its record of the VTK files. The VTK frames of K > 1
/// processes are pieces: expect_same_frames compares them.
std::map<std::string, std::string> outputs(const fs::path& dir) {
  auto d = folder_digest(dir);
  std::erase_if(d, [](const auto& kv) {
    return kv.first.find("checkpoint.bdck") == 0 || kv.first.find("vtk/") == 0;
  });
  auto j = nlohmann::json::parse(read_file_bytes(dir / "summary.json"));
  for (const char* key : {"wall_time_s", "threads", "ranks", "distribution"}) j.erase(key);
  nlohmann::json files = nlohmann::json::array();  // the record of the VTK files left out too
  for (const auto& f : j.at("files"))
    if (f.at("path").get<std::string>().rfind("vtk/", 0) != 0) files.push_back(f);
  j["files"] = files;
  d["summary.json"] = j.dump(2);
  return d;
}

/// The VTK frames of `dir`, read with VTK (compare_vtk_frames.py), equal those of `reference`
/// (one process) to 0, whatever number of processes wrote each frame.
void expect_same_frames(const fs::path& reference, const fs::path& dir) {
  const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const std::string cmd = python +
                          " '" BLOCKDEM_SOURCE_DIR "/tests/validation/compare_vtk_frames.py' '" +
                          reference.string() + "' '" + dir.string() + "' 0 > /dev/null";
  const int status = std::system(cmd.c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << cmd;
}

/// A checkpoint without its VTK part: the run point with the files under vtk/ and the writers'
/// state (time_history.csv's and the VTK frame lists, whose names are .pvtu indices on K > 1
/// processes) left out. Those are checked through the resumed runs' outputs instead.
std::string checkpoint_without_vtk(const fs::path& file, const fs::path& scenario) {
  const ScenarioFingerprint print = scenario_fingerprint(read_file_bytes(scenario), "max_steps=0");
  RunPoint p = decode_run_point(read_checkpoint_file(file, print.accepted()));
  std::erase_if(p.files, [](const auto& f) { return f.first.find("vtk/") == 0; });
  p.outputs.clear();
  return encode_run_point(p);
}

class MpiRestart : public ::testing::Test {
 protected:
  void SetUp() override {
    if (kMpiexec == nullptr) GTEST_SKIP() << "built without MPI (BLOCKDEM_MPI=OFF)";
    scenario_ = write_restart_scenario("mpi_restart", 0, kLongSteps);
    reference_ = fresh_dir("mpi_restart_reference");
    ASSERT_EQ(run(0, scenario_, reference_, ""), 0);
  }
  static fs::path dir(const std::string& name) { return fresh_dir("mpi_restart_" + name); }
  fs::path scenario_, reference_;
};

// SIGTERM (2 processes) or SIGINT (3 processes) reaching process 1 alone after step 1300: every
// process stops after that step and exits with 143 or 130 (mpirun passes the first non-zero
// code on); process 0 writes summary.json "interrupted" with 300 steps of the last stage and a
// checkpoint byte-identical to that of one process stopped after step 1300 but for its VTK part
// (checkpoint_without_vtk). Reference: the one-process run stopped by the same hook. Tolerance:
// none (bytes).
TEST_F(MpiRestart, SignalToOneRankStopsEveryRankAfterTheSameStep) {
  const fs::path single = dir("single");
  ASSERT_EQ(run(0, scenario_, single, "", "BLOCKDEM_TEST_KILL_RANK",
                "0:" + std::to_string(kStopStep) + ":TERM"),
            143);
  const std::string checkpoint = checkpoint_without_vtk(single / "checkpoint.bdck", scenario_);
  for (const auto& [ranks, signal, code] :
       {std::tuple{2, "TERM", 143}, std::tuple{3, "INT", 130}}) {
    SCOPED_TRACE(std::to_string(ranks) + " ranks, SIG" + signal);
    const fs::path out = dir("stopped" + std::to_string(ranks));
    EXPECT_EQ(run(ranks, scenario_, out, "", "BLOCKDEM_TEST_KILL_RANK",
                  "1:" + std::to_string(kStopStep) + ":" + signal),
              code);
    const auto summary = nlohmann::json::parse(read_file_bytes(out / "summary.json"));
    EXPECT_EQ(summary.at("status"), "interrupted");
    EXPECT_EQ(summary.at("ranks").get<int>(), ranks);
    EXPECT_EQ(summary.at("steps").get<int>(), kStopStep);
    EXPECT_EQ(summary.at("stages").back().at("steps").get<int>(), kStopStep - 1000);
    EXPECT_TRUE(checkpoint_without_vtk(out / "checkpoint.bdck", scenario_) == checkpoint)
        << "the checkpoint does not depend on the number of processes (but for its VTK pieces)";
  }
}

// The checkpoint of a 2-process run stopped after step 1300, continued with --resume under 1, 2
// and 3 processes, and that of a 3-process run continued under 2: every output file and
// summary.json byte-identical (the VTK frames, pieces of 2 or 3 processes and whole frames after
// a one-process resume, equal through VTK's reader) to the one-process run never stopped
// (summary.json but for wall time, threads, ranks and the per-process figures). Tolerance: none.
TEST_F(MpiRestart, CheckpointOfKRanksResumesOnOneTwoThreeRanksBitIdentically) {
  for (int ranks_before : {2, 3}) {
    const fs::path stopped = dir("before" + std::to_string(ranks_before));
    ASSERT_EQ(run(ranks_before, scenario_, stopped, "", "BLOCKDEM_TEST_KILL_RANK",
                  "1:" + std::to_string(kStopStep) + ":TERM"),
              143);
    for (int ranks_after : ranks_before == 2 ? std::vector<int>{0, 2, 3} : std::vector<int>{2}) {
      SCOPED_TRACE(std::to_string(ranks_before) + " ranks, then " + std::to_string(ranks_after));
      const fs::path out =
          dir("after" + std::to_string(ranks_before) + std::to_string(ranks_after));
      fs::copy(stopped, out, fs::copy_options::recursive);
      ASSERT_EQ(run(ranks_after, scenario_, out, "--resume"), 0);
      const auto summary = nlohmann::json::parse(read_file_bytes(out / "summary.json"));
      EXPECT_EQ(summary.at("ranks").get<int>(), ranks_after == 0 ? 1 : ranks_after);
      EXPECT_EQ(outputs(out), outputs(reference_));
      expect_same_frames(reference_, out);
    }
  }
}

// A resume on 2 processes maps the checkpoint in each process; when process 1 does not see the
// file (test hook BLOCKDEM_TEST_RESTART_UNSEEN=1), process 0 says so and sends it the bytes.
// Either way the resumed run ends with the outputs of the run never stopped. Reference: the
// one-process run. Tolerance: none (bytes).
TEST_F(MpiRestart, ResumeWhereAProcessDoesNotSeeTheFileGetsItsBytesFromTheFirst) {
  const fs::path stopped = dir("unseen_before");
  ASSERT_EQ(run(2, scenario_, stopped, "", "BLOCKDEM_TEST_KILL_RANK",
                "1:" + std::to_string(kStopStep) + ":TERM"),
            143);
  for (const bool unseen : {false, true}) {
    SCOPED_TRACE(unseen ? "process 1 does not see the file" : "every process sees it");
    const fs::path out = dir(unseen ? "unseen_after" : "seen_after");
    fs::copy(stopped, out, fs::copy_options::recursive);
    const fs::path log = remove_at_exit(out.string() + ".stderr");
    std::ostringstream c;
    c << mpirun(2, unseen ? "-x BLOCKDEM_TEST_RESTART_UNSEEN=1 " : "") << BLOCKDEM_CLI_PATH
      << " run '" << scenario_.string() << "' --out '" << out.string()
      << "' --no-figures --threads 1 --resume > /dev/null 2> '" << log.string() << "'";
    const int status = std::system(c.str().c_str());
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << c.str();
    const std::string said = read_file_bytes(log);
    EXPECT_EQ(said.find("process 0 sends it to every process") != std::string::npos, unseen)
        << said;
    EXPECT_EQ(outputs(out), outputs(reference_));
  }
}

// Process 1 of 2 killed (SIGKILL) after step 1250 of a run with checkpoints every 500 steps, in
// a folder that held a finished run: the launcher stops process 0 and exits non-zero; there is
// no summary.json (nothing claims a finished run); checkpoint.bdck is the whole checkpoint of
// step 1000, byte-identical to the one a single process killed there leaves but for its VTK part
// (checkpoint_without_vtk), and a resume from
// it on 2 processes ends with the outputs of the run never stopped. Tolerance: none.
TEST_F(MpiRestart, KilledRankLeavesTheLastWholeCheckpointAndNoSummary) {
  const std::string every = "--checkpoint-every 500";
  const std::string kill = "1:" + std::to_string(kKillStep);
  const fs::path single = dir("killed_single");
  EXPECT_NE(
      run(0, scenario_, single, every, "BLOCKDEM_TEST_KILL_RANK", "0:" + std::to_string(kKillStep)),
      0);  // killed
  const fs::path out = dir("killed");
  fs::copy(reference_, out, fs::copy_options::recursive);  // an earlier, finished run
  EXPECT_NE(run(2, scenario_, out, every, "BLOCKDEM_TEST_KILL_RANK", kill), 0);
  EXPECT_FALSE(fs::exists(out / "summary.json"));
  ASSERT_TRUE(fs::exists(out / "checkpoint.bdck"));
  EXPECT_TRUE(checkpoint_without_vtk(out / "checkpoint.bdck", scenario_) ==
              checkpoint_without_vtk(single / "checkpoint.bdck", scenario_));
  ASSERT_EQ(run(2, scenario_, out, "--resume"), 0);
  EXPECT_EQ(outputs(out), outputs(reference_));
  expect_same_frames(reference_, out);
}

// Checkpoints every 250 steps, inside stages and at their ends, by 2 processes: each is merged
// to process 0 without a whole-world refresh (summary.json's "distribution": on each process no
// more refreshes than the two later stages' starts and one per new partition after the first,
// which the timing-driven rebalancing makes; the ten checkpoints, seven inside stages, made as
// many more before), the last two byte-identical to one process's but for their VTK part
// (checkpoint_without_vtk), and the outputs those of the run never stopped. Tolerance: none.
TEST_F(MpiRestart, CheckpointsInsideStagesNeedNoWholeWorld) {
  const std::string every = "--checkpoint-every 250";
  const fs::path single = dir("every_single"), out = dir("every2");
  ASSERT_EQ(run(0, scenario_, single, every), 0);
  ASSERT_EQ(run(2, scenario_, out, every), 0);
  const auto summary = nlohmann::json::parse(read_file_bytes(out / "summary.json"));
  ASSERT_EQ(summary.at("distribution").size(), 2u);
  for (const auto& p : summary.at("distribution")) {
    const auto refreshes = p.at("replica_refreshes").get<long long>();
    const auto partitions = p.at("partitions").get<long long>();
    EXPECT_LE(refreshes, 2 + (partitions - 1)) << p.dump();
  }
  for (const char* name : {"checkpoint.bdck", "checkpoint.bdck.prev"}) {
    SCOPED_TRACE(name);
    EXPECT_TRUE(checkpoint_without_vtk(out / name, scenario_) ==
                checkpoint_without_vtk(single / name, scenario_));
  }
  EXPECT_EQ(outputs(out), outputs(reference_));
}

// Bad input: a checkpoint that is not one, given to --resume on 3 processes. Process 0 alone
// reads it; every process stops with its one message, exit code 2, the folder untouched.
TEST_F(MpiRestart, UnusableCheckpointStopsEveryRankWithOneMessage) {
  const fs::path out = dir("bad_checkpoint");
  fs::create_directories(out);
  const std::string garbage = "not a checkpoint\n";
  write_file_atomically(out / "checkpoint.bdck", garbage);
  const fs::path log = remove_at_exit(out.string() + ".log");
  const std::string cmd = mpirun(3) + BLOCKDEM_CLI_PATH + " run " + scenario_.string() + " --out " +
                          out.string() + " --quiet --resume 2> " + log.string();
  const int status = std::system(cmd.c_str());
  EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 2);
  const std::string err = read_file_bytes(log);
  const std::string message = "checkpoint.bdck: not a blockdem checkpoint";
  const auto at = err.find(message);
  EXPECT_NE(at, std::string::npos) << err;
  EXPECT_EQ(err.find(message, at + 1), std::string::npos) << "printed once: " << err;
  EXPECT_EQ(list_run_folder(out), std::vector<std::string>{"checkpoint.bdck"});
  EXPECT_EQ(read_file_bytes(out / "checkpoint.bdck"), garbage);
}

// A voussoir beam (Boon et al. 2015, Table 2 case 1, its levels up to 5 g), stopped inside its
// 2 g level on 2 processes and resumed on 1 and on 3: the beam's tables and summary.json (the
// recorder's levels travel in the checkpoint) and every other output byte-identical to the
// one-process run never stopped, its VTK frames equal through VTK's reader. Tolerance: none.
// Under the sanitizers the resume on 3 processes is left out (a step of 3 oversubscribed
// processes is slow there; the same code runs on 1).
TEST(MpiRestartVoussoir, StoppedOnTwoProcessesResumesOnOneAndThreeBitIdentically) {
  if (kMpiexec == nullptr) GTEST_SKIP() << "built without MPI (BLOCKDEM_MPI=OFF)";
  std::string text =
      read_file_bytes(fs::path(BLOCKDEM_SOURCE_DIR) / "scenarios/boon2015/T2-1.toml");
  const auto table = text.find("[voussoir]\n");
  ASSERT_NE(table, std::string::npos);
  text.insert(table + 11, "g_max = 5.0\n");  // preload (6,040 steps), 2 g and 5 g
  const fs::path beam = temp_path("mpi_voussoir.toml");
  std::ofstream(beam) << text;
  const fs::path reference = fresh_dir("mpi_voussoir_reference");
  ASSERT_EQ(run(0, beam, reference, ""), 0);
  const fs::path stopped = fresh_dir("mpi_voussoir_stopped");
  ASSERT_EQ(run(2, beam, stopped, "", "BLOCKDEM_TEST_KILL_RANK", "1:7000:TERM"), 143);
  for (int ranks : sanitized_run() ? std::vector<int>{0} : std::vector<int>{0, 3}) {
    SCOPED_TRACE("resumed on " + std::to_string(ranks) + " (0: no launcher)");
    const fs::path out = fresh_dir("mpi_voussoir_after" + std::to_string(ranks));
    fs::copy(stopped, out, fs::copy_options::recursive);
    ASSERT_EQ(run(ranks, beam, out, "--resume"), 0);
    EXPECT_EQ(outputs(out), outputs(reference));
    EXPECT_TRUE(outputs(out).count("joints.csv")) << "the beam's own tables compared";
    expect_same_frames(reference, out);
  }
}

/// Runs the restart scenario with a last stage of `steps` steps on 2 processes and, once they
/// are inside that stage, sends SIGTERM from outside to process 1 alone (its process id from a
/// wrapper shell that execs the program) or to mpirun (which passes it on to both after
/// `odls_base_sigkill_timeout`, here 3 s, and kills them as long after). Checks: the launcher's
/// exit code, summary.json "interrupted" inside the stage, and, with `resume`, that a
/// one-process --resume ends with the outputs of the run never stopped (the reference, on one
/// process). Tolerance: none (bytes).
void signal_from_outside(bool to_launcher, long long steps, int expected_code, bool resume) {
  const std::string name = to_launcher ? "mpi_signal_launcher" : "mpi_signal_rank";
  const fs::path scenario = write_restart_scenario(name, 0, steps);
  const fs::path reference = fresh_dir(name + "_reference");
  if (resume) {
    ASSERT_EQ(run(0, scenario, reference, ""), 0);
  }
  const fs::path out = fresh_dir(name + "_out");
  const fs::path pid_file = fresh_dir(name + "_pid");
  // Unquoted: the paths have no spaces, and the command goes inside sh -c '...'.
  const std::string args =
      " run " + scenario.string() + " --out " + out.string() + " --quiet --no-figures --threads 1";
  const std::string timeout = "--mca odls_base_sigkill_timeout 3 ";
  const std::string cmd = to_launcher ? "sh -c 'echo $$ > " + pid_file.string() + "; exec " +
                                            mpirun(2, timeout) + BLOCKDEM_CLI_PATH + args + "'"
                                      : mpirun(1, timeout) + BLOCKDEM_CLI_PATH + args +
                                            " : -np 1 sh -c 'echo $$ > " + pid_file.string() +
                                            "; exec " + BLOCKDEM_CLI_PATH + args + "'";
  FILE* launcher = ::popen((cmd + " > /dev/null 2>&1; echo $?").c_str(), "r");
  ASSERT_NE(launcher, nullptr);
  // Inside the last stage by its progress, not by a time that a loaded machine can outlast:
  // frame 3 is the first `vtk_interval` frame of the long stage (frames 0-2 are the start and
  // the two stage ends), written at step 2500, 1500 steps into it; frames are renamed into
  // place whole.
  const fs::path inside = out / "vtk" / "blocks_000003.pvtu";
  const auto start = std::chrono::steady_clock::now();
  while (!fs::exists(inside) &&
         std::chrono::steady_clock::now() - start < std::chrono::seconds(120))
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_TRUE(fs::exists(inside)) << "the run did not reach step 2500 in 120 s";
  std::string pid;
  std::ifstream(pid_file) >> pid;
  ASSERT_FALSE(pid.empty());
  ::kill(static_cast<pid_t>(std::stol(pid)), SIGTERM);
  char line[32] = {};
  const bool read = std::fgets(line, sizeof line, launcher) != nullptr;
  ::pclose(launcher);
  ASSERT_TRUE(read);
  EXPECT_EQ(std::atoi(line), expected_code);
  const auto summary = nlohmann::json::parse(read_file_bytes(out / "summary.json"));
  EXPECT_EQ(summary.at("status"), "interrupted");
  const long long done = summary.at("stages").back().at("steps").get<long long>();
  EXPECT_GT(done, 0) << "stopped inside the last stage";
  EXPECT_LT(done, steps);
  EXPECT_TRUE(fs::exists(out / "checkpoint.bdck"));
  if (resume) {
    ASSERT_EQ(run(0, scenario, out, "--resume"), 0);
    EXPECT_EQ(outputs(out), outputs(reference));
    expect_same_frames(reference, out);
  }
}

// SIGTERM to process 1 alone: both stop after the same step; mpirun passes on the exit code 143.
TEST(MpiRestartSignal, SigtermFromOutsideToOneRankStopsAllAndResumesBitIdentically) {
  if (kMpiexec == nullptr) GTEST_SKIP() << "built without MPI (BLOCKDEM_MPI=OFF)";
  // The stage (100,000 steps) outlasts the moment the signal arrives (1500 steps into it).
  signal_from_outside(false, 100000, 143, true);
}

// SIGTERM to mpirun (as Ctrl-C or a batch system would send it): Open MPI passes SIGTERM on to
// every process after odls_base_sigkill_timeout and exits with 1 itself; the processes stop
// and write their checkpoint and interrupted record within that time.
TEST(MpiRestartSignal, SigtermToTheLauncherStopsAllWithAnInterruptedRecord) {
  if (kMpiexec == nullptr) GTEST_SKIP() << "built without MPI (BLOCKDEM_MPI=OFF)";
  // A stage that outlasts the 3 s before the signal on any machine (no reference run: the
  // resumes are checked above and in MpiRestart.*).
  signal_from_outside(true, 100000000, 1, false);
}

}  // namespace
}  // namespace blockdem::test
