// Stopping a run by a signal: SIGINT and SIGTERM finish the current step, write a checkpoint,
// the outputs so far, summary.json with status "interrupted" and the run record, and exit with
// 128 + the signal (130, 143); --resume then ends exactly as the run that was never stopped.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "restart_support.hpp"
#include "support/cli_runner.hpp"
#include "support/sanitized_run.hpp"

extern char** environ;

namespace blockdem::test {
namespace {

namespace fs = std::filesystem;

// The long last stage must still be running when the signal comes. The whole scenario with a
// last stage of 50,000 steps takes 0.47 s of CPU in an optimised build (5,000 steps: 0.07 s;
// 100,000: 8.1 s, the later steps dearer: their sliding face contacts at full combined slip took
// 62 % of the CPU). A sanitizer makes a step slower (AddressSanitizer: 226 s for the runs with
// 100,000 steps, against 16 s of CPU optimised). The stop falls between two steps either way.
long long last_stage_steps() {
  return sanitized_run() ? 5000 : 50000;
}

/// Starts `blockdem run` in the background, sends `sig` once the last stage has run 1,500 of its
/// steps (VTK frame 3: frames 0-2 are the start and the first two stages' ends, 1,000 steps in
/// all; `vtk_interval` is 2,500 steps), and returns the exit status (-1: no normal exit). A
/// file the run writes inside the stage, not a delay, tells that the stage has begun: under
/// heavy load a fixed delay once ended before its first step. `name`, if given, receives the
/// running process's name (/proc/PID/comm, what ps, top and pgrep show).
int run_and_signal(const fs::path& scenario, const fs::path& out, int sig,
                   std::string* name = nullptr) {
  std::vector<std::string> args = {BLOCKDEM_CLI_PATH, "run",        scenario.string(),
                                   "--out",           out.string(), "--quiet",
                                   "--no-figures",    "--threads",  "2"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return -2;
  const auto start = std::chrono::steady_clock::now();
  auto waited = [&] { return std::chrono::steady_clock::now() - start > std::chrono::seconds(60); };
  const fs::path inside_last_stage = out / "vtk" / "blocks_000003.vtu";
  while (!fs::exists(inside_last_stage) && !waited())
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  if (name != nullptr) {
    std::ifstream comm("/proc/" + std::to_string(pid) + "/comm");
    std::getline(comm, *name);
  }
  ::kill(pid, sig);
  int status = 0;
  while (::waitpid(pid, &status, WNOHANG) == 0) {
    if (waited()) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

void expect_interrupted_record(const fs::path& out) {
  const auto summary = nlohmann::json::parse(read_file_bytes(out / "summary.json"));
  EXPECT_EQ(summary.at("status"), "interrupted");
  EXPECT_EQ(summary.at("stages").back().at("status"), "interrupted");
  const long long steps = summary.at("stages").back().at("steps").get<long long>();
  EXPECT_GT(steps, 0) << "stopped inside the stage";
  EXPECT_LT(steps, last_stage_steps());
  EXPECT_GE(summary.at("files").size(), 3u) << "the files written so far are recorded";
  EXPECT_TRUE(fs::exists(out / "checkpoint.bdck"));
}

// Reference: the same scenario run without a stop. Tolerance: none (byte-identical outputs).
TEST(RestartSignals, SigintStopsWith130AndTheResumedRunIsBitIdentical) {
  const fs::path scenario = write_restart_scenario("signal", 0, last_stage_steps());
  const fs::path reference = fresh_dir("signal_reference");
  const CommandOutput full = run_cli("run '" + scenario.string() + "' --out '" +
                                     reference.string() + "' --quiet --no-figures --threads 1");
  ASSERT_EQ(full.exit_code, 0) << full.err;

  const fs::path out = fresh_dir("signal_interrupted");
  ASSERT_EQ(run_and_signal(scenario, out, SIGINT), 130);
  expect_interrupted_record(out);
  const CommandOutput resumed = run_cli("run '" + scenario.string() + "' --out '" + out.string() +
                                        "' --quiet --no-figures --threads 1 --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  expect_same_outputs(reference, out);
}

// Also: the running program is named blockdem (it starts itself again to choose how its threads
// wait, apps/cli/main.cpp; started as /proc/self/exe, ps and top showed it as "exe").
TEST(RestartSignals, SigtermStopsWith143AndAnInterruptedRecord) {
  const fs::path scenario = write_restart_scenario("signal_term", 0, last_stage_steps());
  const fs::path out = fresh_dir("signal_term");
  std::string name;
  ASSERT_EQ(run_and_signal(scenario, out, SIGTERM, &name), 143);
  EXPECT_EQ(name, fs::path(BLOCKDEM_CLI_PATH).filename().string().substr(0, 15));
  expect_interrupted_record(out);
}

}  // namespace
}  // namespace blockdem::test
