// Checkpoints of a voussoir beam run ([voussoir], Boon et al. 2015, Table 2 case 1): the beam's
// recorder keeps its reference pose and the levels it measured in the checkpoint, so a run
// stopped inside a load level, or continued from a kept checkpoint into another folder with
// another thread count, ends byte for byte as the run that was never stopped (its history.csv,
// blocks.csv and joints.csv of the levels, the run's other tables and VTK frames, and
// summary.json with the beam's g_max, thrust and fits). Its stages are built by the table, so
// only the same file restarts it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "blockdem/io/atomic_file.hpp"
#include "restart_support.hpp"
#include "support/cli_runner.hpp"

namespace blockdem::test::restart_voussoir {
namespace {

namespace fs = std::filesystem;

const fs::path& beam_file() {
  static const fs::path file = fs::path(BLOCKDEM_SOURCE_DIR) / "scenarios/boon2015/T2-1.toml";
  return file;
}

std::string run_args(const fs::path& scenario, const fs::path& out, int threads) {
  return "run '" + scenario.string() + "' --out '" + out.string() +
         "' --quiet --no-figures --threads " + std::to_string(threads);
}

// The beam's own tables, beside what expect_same_outputs compares.
void expect_same_beam_tables(const fs::path& a, const fs::path& b) {
  for (const char* name : {"history.csv", "blocks.csv", "joints.csv"}) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(fs::exists(a / name));
    EXPECT_EQ(read_file_bytes(a / name), read_file_bytes(b / name));
  }
  const auto summary = nlohmann::json::parse(read_file_bytes(b / "summary.json"));
  EXPECT_EQ(summary.at("status"), "completed");
  EXPECT_DOUBLE_EQ(summary.at("g_max").get<double>(), 40.0) << "every level carried";
  EXPECT_EQ(summary.at("voussoir").at("levels").size(), 10u) << "preload and nine levels";
}

// The reference: the beam run with a checkpoint every 9,000 steps (the last two kept); the
// checkpoints do not change the run.
class RestartVoussoir : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    reference_ = fresh_dir("voussoir_reference");
    const CommandOutput r =
        run_cli(run_args(beam_file(), reference_, 1) + " --checkpoint-every 9000");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    kept_ = fresh_dir("voussoir_kept");
    fs::create_directories(kept_);
    fs::copy_file(reference_ / "checkpoint.bdck", kept_ / "last.bdck");
    fs::copy_file(reference_ / "checkpoint.bdck.prev", kept_ / "previous.bdck");
  }
  static inline fs::path reference_, kept_;
};

// Reference: the uninterrupted run. Tolerance: none (bytes).
TEST_F(RestartVoussoir, AStopInsideALoadLevelResumesBitIdentical) {
  const fs::path out = fresh_dir("voussoir_stopped");
  // Step 20,000 lies inside the fifth stage, 15 g: four levels are measured before it.
  ::setenv("BLOCKDEM_TEST_KILL_RANK", "0:20000:TERM", 1);
  const CommandOutput stopped = run_cli(run_args(beam_file(), out, 1));
  ::unsetenv("BLOCKDEM_TEST_KILL_RANK");
  ASSERT_EQ(stopped.exit_code, 143) << stopped.err;
  EXPECT_NE(stopped.err.find("continue with --restart"), std::string::npos) << stopped.err;
  const auto interrupted = nlohmann::json::parse(read_file_bytes(out / "summary.json"));
  EXPECT_EQ(interrupted.at("stages").back().at("name"), "15g");
  const CommandOutput resumed = run_cli(run_args(beam_file(), out, 2) + " --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  expect_same_outputs(reference_, out);
  expect_same_beam_tables(reference_, out);
}

// Either kept checkpoint, continued into another folder with 1 or 2 threads. Reference: the
// uninterrupted run (bytes).
TEST_F(RestartVoussoir, EitherKeptCheckpointContinuesBitIdentical) {
  for (const char* which : {"last.bdck", "previous.bdck"}) {
    for (int threads : {1, 2}) {
      SCOPED_TRACE(std::string(which) + ", threads " + std::to_string(threads));
      const fs::path out = fresh_dir("voussoir_continued");
      const CommandOutput r = run_cli(run_args(beam_file(), out, threads) + " --restart '" +
                                      (kept_ / which).string() + "'");
      ASSERT_EQ(r.exit_code, 0) << r.err;
      expect_same_outputs(reference_, out);
      expect_same_beam_tables(reference_, out);
    }
  }
}

// The stages come from the [voussoir] table: a file with another beam (another joint stiffness)
// is another scenario from its first stage on. Refused: exit 2, the checkpoint named, nothing
// written.
TEST_F(RestartVoussoir, AnotherBeamIsRefused) {
  std::string text = read_file_bytes(beam_file());
  const std::string from = "stiffness = 10e9";
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, from.size(), "stiffness = 11e9");
  const fs::path other = temp_path("voussoir_other.toml");
  std::ofstream(other) << text;
  const fs::path out = fresh_dir("voussoir_refused");
  const CommandOutput r =
      run_cli(run_args(other, out, 1) + " --restart '" + (kept_ / "last.bdck").string() + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("last.bdck"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace blockdem::test::restart_voussoir
