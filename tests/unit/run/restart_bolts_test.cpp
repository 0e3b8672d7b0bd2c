// Checkpoints of a run with rock bolts (scenarios/examples/roof_wedge_bolted.toml: a roof wedge
// held by three grouted bolts that the excavation stage installs): every field of each bolt is in
// the world's state, and bolts.csv and the bolts' VTK frames continue, so a run stopped after the
// bolts went in, or continued from a kept checkpoint into another folder with another thread
// count, ends byte for byte as the run that was never stopped.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "blockdem/io/atomic_file.hpp"
#include "restart_support.hpp"
#include "support/cli_runner.hpp"

namespace blockdem::test::restart_bolts {
namespace {

namespace fs = std::filesystem;

const fs::path& bolted_file() {
  static const fs::path file =
      fs::path(BLOCKDEM_SOURCE_DIR) / "scenarios/examples/roof_wedge_bolted.toml";
  return file;
}

std::string run_args(const fs::path& out, int threads) {
  return "run '" + bolted_file().string() + "' --out '" + out.string() +
         "' --quiet --no-figures --threads " + std::to_string(threads);
}

nlohmann::json summary_of(const fs::path& dir) {
  return nlohmann::json::parse(read_file_bytes(dir / "summary.json"));
}

// The bolts' own outputs, beside what expect_same_outputs compares.
void expect_same_bolts(const fs::path& a, const fs::path& b) {
  for (const char* name : {"bolts.csv", "vtk/bolts.pvd"}) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(fs::exists(a / name));
    EXPECT_EQ(read_file_bytes(a / name), read_file_bytes(b / name));
  }
  EXPECT_EQ(summary_of(a).at("stages").back().at("bolts"),
            summary_of(b).at("stages").back().at("bolts"));
}

// The reference: the bolted wedge with a checkpoint every 600 steps (the last two kept).
class RestartBolts : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    reference_ = fresh_dir("bolts_reference");
    const CommandOutput r = run_cli(run_args(reference_, 1) + " --checkpoint-every 600");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto stages = summary_of(reference_).at("stages");
    ASSERT_EQ(stages.size(), 2u);
    settle_steps_ = stages[0].at("steps").get<long long>();
    bolt_steps_ = stages[1].at("steps").get<long long>();
    ASSERT_GT(bolt_steps_, 1200) << "the checkpoints must fall inside the bolted stage";
    kept_ = fresh_dir("bolts_kept");
    fs::create_directories(kept_);
    fs::copy_file(reference_ / "checkpoint.bdck", kept_ / "last.bdck");
    fs::copy_file(reference_ / "checkpoint.bdck.prev", kept_ / "previous.bdck");
  }
  static inline fs::path reference_, kept_;
  static inline long long settle_steps_ = 0, bolt_steps_ = 0;
};

// A stop half way through the stage that installed the bolts, resumed with 2 threads. Reference:
// the uninterrupted run (bytes).
TEST_F(RestartBolts, AStopAfterTheBoltsWentInResumesBitIdentical) {
  const fs::path out = fresh_dir("bolts_stopped");
  const long long stop = settle_steps_ + bolt_steps_ / 2;
  ::setenv("BLOCKDEM_TEST_KILL_RANK", ("0:" + std::to_string(stop) + ":TERM").c_str(), 1);
  const CommandOutput stopped = run_cli(run_args(out, 1));
  ::unsetenv("BLOCKDEM_TEST_KILL_RANK");
  ASSERT_EQ(stopped.exit_code, 143) << stopped.err;
  EXPECT_EQ(summary_of(out).at("stages").back().at("status"), "interrupted");
  const CommandOutput resumed = run_cli(run_args(out, 2) + " --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  expect_same_outputs(reference_, out);
  expect_same_bolts(reference_, out);
}

// Either kept checkpoint (both inside the bolted stage), continued into another folder with 1 or
// 2 threads. Reference: the uninterrupted run (bytes).
TEST_F(RestartBolts, EitherKeptCheckpointContinuesBitIdentical) {
  for (const char* which : {"last.bdck", "previous.bdck"}) {
    for (int threads : {1, 2}) {
      SCOPED_TRACE(std::string(which) + ", threads " + std::to_string(threads));
      const fs::path out = fresh_dir("bolts_continued");
      const CommandOutput r =
          run_cli(run_args(out, threads) + " --restart '" + (kept_ / which).string() + "'");
      ASSERT_EQ(r.exit_code, 0) << r.err;
      expect_same_outputs(reference_, out);
      expect_same_bolts(reference_, out);
    }
  }
}

}  // namespace
}  // namespace blockdem::test::restart_bolts
