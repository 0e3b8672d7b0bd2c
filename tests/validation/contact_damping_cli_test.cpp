// `blockdem run` with contact damping and acceleration records: bad input refused (exit 2, a
// message naming file, key and reason, nothing written), the dashpot's energy in the outputs, a
// restart inside a damped dynamic stage bit-identical to the run never stopped, and a restart
// refused when the stage's acceleration record changed since the checkpoint.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "shaken_block.hpp"
#include "support/cli_runner.hpp"
#include "support/input_error.hpp"
#include "support/temp_path.hpp"

namespace blockdem::test::contact_damping_cli_test {
namespace {

namespace fs = std::filesystem;

std::string file_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A block on a fixed plate (group "base"), settled, then shaken by `motion` for 0.15 s, then 300
// steps of rest; `settings`: extra [settings] lines.
std::string shaken_block(const std::string& settings, const std::string& motion) {
  return shaken_block_scenario(settings, "history_interval = 7\nhistory_blocks = [\"block\"]\n",
                               "[[stages]]\nname = \"shake\"\nkind = \"dynamic\"\n"
                               "duration = 0.15\nbase_motion = " +
                                   motion + "\n[[stages]]\nname = \"rest\"\nmax_steps = 300\n");
}

const char* const kSine =
    "{ group = \"base\", pulse = \"sine\", amplitude_m_s2 = 6.0, period = 0.1 }";
const char* const kRecord = "{ group = \"base\", file = \"accel.csv\" }";

CommandOutput run(const fs::path& file, const fs::path& out, const std::string& extra) {
  return run_cli("run '" + file.string() + "' --out '" + out.string() +
                 "' --quiet --no-figures --threads 1 " + extra);
}

// Stops a run (SIGTERM: a checkpoint, exit 143) at `step`.
CommandOutput run_stopped_at(const fs::path& file, const fs::path& out, std::int64_t step) {
  ::setenv("BLOCKDEM_TEST_KILL_RANK", ("0:" + std::to_string(step) + ":TERM").c_str(), 1);
  const CommandOutput r = run(file, out, "");
  ::unsetenv("BLOCKDEM_TEST_KILL_RANK");
  return r;
}

struct BadCase {
  const char* name;
  const char* settings;  ///< [settings] lines
  const char* stage;     ///< extra lines of the dynamic stage
  std::vector<std::string> fragments;
};

class ContactDampingInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(ContactDampingInput, IsRefusedWithExitTwoAndNothingWritten) {
  const BadCase& c = GetParam();
  const fs::path dir = fresh_case_dir("contact_damping_input", c.name);
  const fs::path file = dir / "case.toml";
  std::ofstream(file) << shaken_block(c.settings, std::string(kSine) + "\n" + c.stage);
  const fs::path out = dir / "out";
  const CommandOutput r = run(file, out, "");
  std::vector<std::string> fragments = c.fragments;
  fragments.push_back(file.string());
  expect_input_error(r, out, fragments);
}

INSTANTIATE_TEST_SUITE_P(
    Catalogue, ContactDampingInput,
    ::testing::Values(
        BadCase{
            "negative", "contact_damping = -0.05\n", "", {"settings.contact_damping", "[0, 1)"}},
        BadCase{"critical", "contact_damping = 1.0\n", "", {"settings.contact_damping", "[0, 1)"}},
        BadCase{
            "not_a_number", "contact_damping = nan\n", "", {"settings.contact_damping", "finite"}},
        BadCase{"infinite", "contact_damping = inf\n", "", {"settings.contact_damping", "finite"}},
        BadCase{"in_a_stage",
                "",
                "contact_damping = 0.05\n",
                {"stages[2].contact_damping", "unknown key"}}),
    [](const ::testing::TestParamInfo<BadCase>& i) { return std::string(i.param.name); });

// With ζ = 0.05 the outputs carry the dashpot's energy (time_history.csv's contact_damping_J,
// summary.json's energy_J.contact_damping, positive: the block rocks and slips on its joint); a
// run stopped inside the dynamic stage and resumed ends with the same time_history.csv (bytes)
// and the same summary.json stages as the run never stopped (the checkpoint keeps the halves
// of the dashpots' work the next step adds).
TEST(ContactDampingRestart, ContinuingInsideTheDynamicStageIsBitIdentical) {
  const fs::path dir = fresh_case_dir("contact_damping_restart", "case");
  const fs::path file = dir / "case.toml";
  std::ofstream(file) << shaken_block("contact_damping = 0.05\n", kSine);
  const fs::path reference = dir / "reference";
  const CommandOutput r = run(file, reference, "");
  ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 3) << r.err;
  const std::string history = file_bytes(reference / "time_history.csv");
  EXPECT_NE(history.find("damping_dissipation_J,contact_damping_J,energy_residual_J"),
            std::string::npos);
  const auto summary = nlohmann::json::parse(file_bytes(reference / "summary.json"));
  EXPECT_GT(summary["energy_J"]["contact_damping"].get<double>(), 0.0);
  const auto& stages = summary["stages"];
  ASSERT_EQ(stages.size(), 3u);
  const std::int64_t settle = stages[0]["steps"], shake = stages[1]["steps"];
  const fs::path out = dir / "continued";
  const CommandOutput stopped = run_stopped_at(file, out, settle + shake / 2);
  ASSERT_EQ(stopped.exit_code, 143) << stopped.err;
  const CommandOutput c = run(file, out, "--resume");
  EXPECT_EQ(c.exit_code, r.exit_code) << c.err;
  EXPECT_EQ(history, file_bytes(out / "time_history.csv"));
  const auto continued = nlohmann::json::parse(file_bytes(out / "summary.json"));
  EXPECT_EQ(summary["stages"].dump(), continued["stages"].dump());
  EXPECT_EQ(summary["energy_J"].dump(), continued["energy_J"].dump());
}

// A checkpoint taken inside a dynamic stage whose record has since been edited is refused: exit
// 2, a message naming the record, and the output folder as the stopped run left it. The same
// record unchanged resumes (exit 0 or 3).
TEST(AccelerationRecordFingerprint, EditedRecordRefusesTheRestart) {
  const fs::path dir = fresh_case_dir("acceleration_record_fingerprint", "case");
  const fs::path file = dir / "case.toml";
  const std::string record =
      "time_s,ax_m_s2,ay_m_s2,az_m_s2\n0,0,0,0\n0.05,6,0,0\n0.1,-6,0,0\n0.15,0,0,0\n";
  std::ofstream(dir / "accel.csv") << record;
  std::ofstream(file) << shaken_block("", kRecord);
  // The step half way through the shake stage, from a run never stopped.
  const CommandOutput whole = run(file, dir / "reference", "");
  ASSERT_TRUE(whole.exit_code == 0 || whole.exit_code == 3) << whole.err;
  const auto summary = nlohmann::json::parse(file_bytes(dir / "reference" / "summary.json"));
  const std::int64_t settle = summary["stages"][0]["steps"], shake = summary["stages"][1]["steps"];
  const fs::path out = dir / "out";
  const CommandOutput stopped = run_stopped_at(file, out, settle + shake / 2);
  ASSERT_EQ(stopped.exit_code, 143) << stopped.err;
  const auto files_now = [&] {
    std::map<std::string, std::string> all;
    for (const auto& e : fs::recursive_directory_iterator(out))
      if (e.is_regular_file()) all[e.path().string()] = file_bytes(e.path());
    return all;
  };
  const auto before = files_now();
  ASSERT_FALSE(before.empty());
  // One sample changed: 6 m/s² to 5 m/s².
  std::ofstream(dir / "accel.csv")
      << "time_s,ax_m_s2,ay_m_s2,az_m_s2\n0,0,0,0\n0.05,5,0,0\n0.1,-6,0,0\n0.15,0,0,0\n";
  const CommandOutput refused = run(file, out, "--resume");
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  EXPECT_NE(refused.err.find("accel.csv"), std::string::npos) << refused.err;
  EXPECT_EQ(before, files_now()) << "a refused restart wrote into the output folder";
  // The record as it was: the restart goes on.
  std::ofstream(dir / "accel.csv") << record;
  const CommandOutput resumed = run(file, out, "--resume");
  EXPECT_TRUE(resumed.exit_code == 0 || resumed.exit_code == 3) << resumed.err;
}

}  // namespace
}  // namespace blockdem::test::contact_damping_cli_test
