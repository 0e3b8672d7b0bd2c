// Checkpoint and restart through the program: a run continued from any of its checkpoints, with
// 1 or 2 threads, ends with byte-identical outputs to the run that was never stopped; unusable
// checkpoints are refused (exit 2, nothing touched); the run record lists what the run wrote.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "blockdem/io/atomic_file.hpp"
#include "restart_support.hpp"
#include "support/cli_runner.hpp"

namespace blockdem::test {
namespace {

namespace fs = std::filesystem;

// The reference: a run with checkpoints every 450 steps (at 450, 900, ... and at the stage
// ends 400 and 1000), which keeps the last two.
class Restart : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scenario_ = write_restart_scenario("restart_reference", 0);
    reference_ = fresh_dir("restart_reference_out");
    const CommandOutput r =
        run_cli("run '" + scenario_.string() + "' --out '" + reference_.string() +
                "' --quiet --no-figures --threads 1 --checkpoint-every 450");
    reference_exit_ = r.exit_code;
    ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 3) << r.err;
    kept_ = fresh_dir("restart_kept");
    fs::create_directories(kept_);
    fs::copy_file(reference_ / "checkpoint.bdck", kept_ / "last.bdck");
    fs::copy_file(reference_ / "checkpoint.bdck.prev", kept_ / "previous.bdck");
  }
  static inline fs::path scenario_, reference_, kept_;
  static inline int reference_exit_ = -1;
};

// Reference: the uninterrupted run. Tolerance: none (byte-identical CSV, VTK and summary.json
// but for the wall time and thread count).
TEST_F(Restart, ContinuingFromEitherKeptCheckpointWithOneOrTwoThreadsIsBitIdentical) {
  for (const char* which : {"last.bdck", "previous.bdck"}) {
    for (int threads : {1, 2}) {
      SCOPED_TRACE(std::string(which) + ", threads " + std::to_string(threads));
      const fs::path out = fresh_dir("restart_continued");
      const CommandOutput r =
          run_cli("run '" + scenario_.string() + "' --out '" + out.string() +
                  "' --quiet --no-figures --threads " + std::to_string(threads) + " --restart '" +
                  (kept_ / which).string() + "'");
      EXPECT_EQ(r.exit_code, reference_exit_) << r.err;
      expect_same_outputs(reference_, out);
    }
  }
}

// A stop in the first stage, before any table has rows: the checkpoint carries the tables as
// they are on disk, headers included. Reference: the uninterrupted run (bytes).
TEST_F(Restart, ResumingAStopInTheFirstStageIsBitIdentical) {
  const fs::path out = fresh_dir("restart_first_stage");
  ::setenv("BLOCKDEM_TEST_KILL_RANK", "0:200:TERM", 1);
  const CommandOutput stopped = run_cli("run '" + scenario_.string() + "' --out '" + out.string() +
                                        "' --quiet --no-figures --threads 1");
  ::unsetenv("BLOCKDEM_TEST_KILL_RANK");
  ASSERT_EQ(stopped.exit_code, 143) << stopped.err;
  const CommandOutput r = run_cli("run '" + scenario_.string() + "' --out '" + out.string() +
                                  "' --quiet --no-figures --threads 2 --resume");
  EXPECT_EQ(r.exit_code, reference_exit_) << r.err;
  expect_same_outputs(reference_, out);
}

TEST_F(Restart, CheckpointsDoNotChangeTheRun) {
  const fs::path out = fresh_dir("restart_plain");
  const CommandOutput r = run_cli("run '" + scenario_.string() + "' --out '" + out.string() +
                                  "' --quiet --no-figures --threads 2");
  EXPECT_EQ(r.exit_code, reference_exit_) << r.err;
  expect_same_outputs(reference_, out);
  EXPECT_FALSE(fs::exists(out / "checkpoint.bdck")) << "no checkpoint unless asked";
}

// The record in summary.json: every other file the run wrote, with its size and checksum, and
// nothing else (checkpoints carry their own checksum).
TEST_F(Restart, SummaryListsEveryFileWithSizeAndChecksum) {
  const auto summary = nlohmann::json::parse(read_file_bytes(reference_ / "summary.json"));
  std::map<std::string, bool> listed;
  for (const auto& f : summary.at("files")) {
    const std::string rel = f.at("path");
    const std::string bytes = read_file_bytes(reference_ / rel);
    EXPECT_EQ(f.at("bytes").get<std::size_t>(), bytes.size()) << rel;
    EXPECT_EQ(f.at("fnv1a64").get<std::string>(), hex64(fnv1a64(bytes))) << rel;
    listed[rel] = true;
  }
  for (const char* rel :
       {"history.csv", "time_history.csv", "blocks.csv", "contacts.csv", "vtk/blocks.pvd",
        "vtk/contacts.pvd", "vtk/blocks_000000.vtu", "vtk/contacts_000000.vtu"})
    EXPECT_TRUE(listed.count(rel)) << rel;
  // Nothing else: every file in the folder but summary.json and the checkpoints, counted here.
  std::size_t on_disk = 0, frames = 0;
  for (const auto& e : fs::recursive_directory_iterator(reference_)) {
    if (!e.is_regular_file()) continue;
    const std::string rel = fs::relative(e.path(), reference_).generic_string();
    if (rel == "summary.json" || rel.starts_with("checkpoint.bdck")) continue;
    ++on_disk;
    EXPECT_TRUE(listed.count(rel)) << rel;
    frames += rel.ends_with(".vtu") ? 1 : 0;
  }
  EXPECT_EQ(listed.size(), on_disk);
  // Frames: the three stage ends and one every 250 steps, each as blocks and contacts.
  EXPECT_GE(frames, 2u * (3u + 4u));
}

// A new run in a used folder: the earlier run's files go (also those its summary lists), the
// user's own files stay and are not claimed by the record.
TEST_F(Restart, ANewRunClearsTheEarlierRunButNotOtherFiles) {
  const fs::path out = fresh_dir("restart_reused");
  fs::copy(reference_, out, fs::copy_options::recursive);
  {
    std::ofstream(out / "notes.txt") << "mine\n";
    std::ofstream(out / "vtk" / "blocks_0099.vtk") << "stale\n";
  }
  const CommandOutput r = run_cli("run '" + scenario_.string() + "' --out '" + out.string() +
                                  "' --quiet --no-figures --threads 1");
  EXPECT_EQ(r.exit_code, reference_exit_) << r.err;
  EXPECT_TRUE(fs::exists(out / "notes.txt"));
  EXPECT_FALSE(fs::exists(out / "vtk" / "blocks_0099.vtk"));
  EXPECT_FALSE(fs::exists(out / "checkpoint.bdck")) << "the earlier run's checkpoint";
  const auto summary = nlohmann::json::parse(read_file_bytes(out / "summary.json"));
  for (const auto& f : summary.at("files")) EXPECT_NE(f.at("path"), "notes.txt");
}

struct BadCheckpoint {
  const char* name;
  const char* reason;  // expected in the message
};

// Unusable checkpoints: exit 2, a message naming the file and the reason, and the folder of the
// run being continued left exactly as it was.
TEST_F(Restart, UnusableCheckpointsAreRefusedAndNothingIsTouched) {
  const std::string good = read_file_bytes(kept_ / "last.bdck");
  const std::map<std::string, std::string> variants = {
      {"truncated", good.substr(0, good.size() - 100)},
      {"corrupt",
       [&] {
         std::string s = good;
         s[s.size() / 2] = static_cast<char>(s[s.size() / 2] ^ 0x5a);
         return s;
       }()},
      {"wrong_version",
       [&] {
         std::string s = good;
         s[12] = 99;  // the format version field
         return s;
       }()},
      {"foreign", std::string("PK\x03\x04 not a checkpoint at all, but long enough to read")},
  };
  const std::map<std::string, std::string> reasons = {{"truncated", "truncated"},
                                                      {"corrupt", "checksum"},
                                                      {"wrong_version", "format version 99"},
                                                      {"foreign", "magic"}};
  const fs::path out = fresh_dir("restart_refused");
  fs::copy(reference_, out, fs::copy_options::recursive);
  const auto before = folder_digest(out);
  for (const auto& [name, bytes] : variants) {
    SCOPED_TRACE(name);
    const fs::path bad = kept_ / (name + ".bdck");
    std::ofstream(bad, std::ios::binary) << bytes;
    const CommandOutput r = run_cli("run '" + scenario_.string() + "' --out '" + out.string() +
                                    "' --quiet --no-figures --restart '" + bad.string() + "'");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(bad.string()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(reasons.at(name)), std::string::npos) << r.err;
    EXPECT_EQ(folder_digest(out), before) << "a refused restart must not touch the folder";
  }
  // Another scenario (one more step in a stage), and other result-changing options.
  const fs::path other = write_restart_scenario("restart_other", 1);
  for (const std::string& command :
       {"run '" + other.string() + "'", "run '" + scenario_.string() + "' --max-steps 5000"}) {
    SCOPED_TRACE(command);
    const CommandOutput r =
        run_cli(command + " --out '" + out.string() + "' --quiet --no-figures --restart '" +
                (kept_ / "last.bdck").string() + "'");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("another scenario"), std::string::npos) << r.err;
    EXPECT_EQ(folder_digest(out), before);
  }
}

// A stop inside an excavation stage: the key blocks at its end are measured from the stage's
// start, which the checkpoint carries (not from where the run was resumed). Reference: the
// uninterrupted run (bytes, summary.json's key_blocks included).
TEST(RestartExcavation, KeyBlocksOfAResumedExcavationStageAreMeasuredFromItsStart) {
  const fs::path file = fresh_dir("restart_excavation.toml");
  {
    std::ofstream f(file);
    f << R"(title = "a block left without support"
[settings]
damping = 0.0
[[joint_laws]]
name = "joint"
normal = { law = "linear", stiffness = 1e9 }
shear = { law = "linear", stiffness = 1e8, friction_deg = 30 }
[rock_mass]
region = { min = [0, 0, 0], max = [2, 1, 2] }
density = 2500
law = "joint"
[[joint_sets]]
name = "bedding"
dip_deg = 0
dip_direction_deg = 0
spacing = 100
origin = [1, 0.5, 1]
[[joint_sets]]
name = "cross"
dip_deg = 90
dip_direction_deg = 90
spacing = 100
origin = [1, 0.5, 1]
[[excavations]]
name = "cut"
shape = "planes"
planes = [[-1, 0, 0, -1], [0, 0, 1, 1]]
[[boundaries]]
faces = ["z_min"]
condition = "fixed"
[[stages]]
name = "settle"
kind = "steps"
steps = 300
gravity = [0, 0, -9.81]
[[stages]]
name = "cut"
kind = "duration"
duration = 0.2
excavation = "cut"
)";
  }
  const fs::path reference = fresh_dir("restart_excavation_reference");
  const CommandOutput full = run_cli("run '" + file.string() + "' --out '" + reference.string() +
                                     "' --quiet --no-figures --threads 1");
  ASSERT_EQ(full.exit_code, 0) << full.err;
  const auto summary = nlohmann::json::parse(std::ifstream(reference / "summary.json"));
  ASSERT_EQ(summary["key_blocks"].size(), 1u) << summary.dump();
  // The block above the cut falls freely for the stage (no friction without normal force):
  // g t^2 / 2 = 0.196 m, to the time step's order.
  EXPECT_NEAR(summary["key_blocks"][0]["displacement_m"].get<double>(), 0.5 * 9.81 * 0.04, 0.005);
  // The duration stage is done (converged) with a block falling: not in equilibrium.
  EXPECT_TRUE(summary["stages"][1]["converged"].get<bool>());
  EXPECT_FALSE(summary["stages"][1]["in_equilibrium"].get<bool>());
  const fs::path out = fresh_dir("restart_excavation_resumed");
  const std::int64_t stop = summary["stages"][0]["steps"].get<std::int64_t>() +
                            summary["stages"][1]["steps"].get<std::int64_t>() / 2;
  ::setenv("BLOCKDEM_TEST_KILL_RANK", ("0:" + std::to_string(stop) + ":TERM").c_str(), 1);
  const CommandOutput stopped = run_cli("run '" + file.string() + "' --out '" + out.string() +
                                        "' --quiet --no-figures --threads 1");
  ::unsetenv("BLOCKDEM_TEST_KILL_RANK");
  ASSERT_EQ(stopped.exit_code, 143) << stopped.err;
  const CommandOutput r = run_cli("run '" + file.string() + "' --out '" + out.string() +
                                  "' --quiet --no-figures --threads 1 --resume");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  expect_same_outputs(reference, out);
  // --resume again, on the completed run: nothing to resume and nothing touched (every file keeps
  // its bytes), exit 0 with a message naming --restart for a branch.
  const auto before = folder_digest(out);
  const CommandOutput again = run_cli("run '" + file.string() + "' --out '" + out.string() +
                                      "' --quiet --no-figures --threads 1 --resume");
  EXPECT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.err.find("nothing to resume"), std::string::npos) << again.err;
  EXPECT_NE(again.err.find("--restart"), std::string::npos) << again.err;
  EXPECT_EQ(folder_digest(out), before);
}

}  // namespace
}  // namespace blockdem::test
