// Inputs that once cost unbounded work, wrapped round, or ended in "internal error": each exits 2
// with a message naming the file (or option), the key and the reason, and writes nothing; a
// folder the system will not let the run write, or memory it will not give, exits 4; numbers in
// messages read as %g.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "support/cli_runner.hpp"
#include "support/input_error.hpp"
#include "support/sanitized_run.hpp"

namespace blockdem::input_bounds_test {

namespace fs = std::filesystem;

// A 4 m cube of rock cut by bedding at 1.3 m, the base fixed.
const std::string kRockMass = R"([settings]
damping = 0.7
[[joint_laws]]
name = "j"
normal = { law = "linear", stiffness = 1e9 }
shear = { law = "linear", stiffness = 1e8, friction_deg = 35 }
[rock_mass]
region = { min = [0, 0, 0], max = [4, 4, 4] }
density = 2500
law = "j"
[[joint_sets]]
name = "bedding"
dip_deg = 0
dip_direction_deg = 0
spacing = 1.3
[[boundaries]]
faces = ["z_min"]
[[stages]]
name = "settle"
gravity = [0, 0, -9.81]
max_steps = 3000
)";

const std::string kJ2 =
    "[[joint_sets]]\nname = \"J2\"\ndip_deg = 90\ndip_direction_deg = 90\nspacing = 1.0\n";

struct Case {
  const char* name;
  std::string from;  ///< text of kRockMass to replace ("" appends `to`)
  std::string to;
  std::vector<std::string> fragments;  ///< expected in the message (besides the file)
};

fs::path scratch(const std::string& name) {
  return test::fresh_case_dir("input_bounds", name);
}

std::string mutate(const Case& c) {
  if (c.from.empty()) return kRockMass + c.to;
  std::string s = kRockMass;
  const auto at = s.find(c.from);
  EXPECT_NE(at, std::string::npos) << c.name << ": '" << c.from << "' is not in the scenario";
  if (at != std::string::npos) s.replace(at, c.from.size(), c.to);
  return s;
}

// An input error (test::expect_input_error) whose message is an error's, not a warning's.
void expect_refused(const test::CommandOutput& r, const fs::path& out,
                    const std::vector<std::string>& fragments) {
  test::expect_input_error(r, out, fragments);
  EXPECT_EQ(r.err.rfind("blockdem: error:", 0), 0u) << r.err;
}

test::CommandOutput run(const fs::path& file, const fs::path& out, const std::string& extra = "") {
  return test::run_cli("run '" + file.string() + "' --out '" + out.string() +
                       "' --quiet --no-figures " + extra);
}

class BoundedInput : public ::testing::TestWithParam<Case> {};

TEST(BoundedInput, TheRockMassRuns) {
  const fs::path dir = scratch("good");
  std::ofstream(dir / "case.toml") << kRockMass;
  const auto r = run(dir / "case.toml", dir / "out");
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST_P(BoundedInput, ExitsTwoNamingFileKeyAndReasonAndWritesNothing) {
  const Case& c = GetParam();
  const fs::path dir = scratch(c.name);
  const fs::path file = dir / "case.toml";
  std::ofstream(file) << mutate(c);
  std::vector<std::string> fragments = c.fragments;
  fragments.push_back(file.string());
  expect_refused(run(file, dir / "out"), dir / "out", fragments);
}

INSTANTIATE_TEST_SUITE_P(
    Catalogue, BoundedInput,
    ::testing::Values(
        Case{"spacing_1e_300",
             "spacing = 1.3",
             "spacing = 1e-300",
             {"joint_sets[1].spacing", "\"bedding\"", "4e+300 blocks", "max_blocks = 2000000"}},
        Case{"exponential_mean_1e_9",
             "spacing = 1.3",
             "spacing = { mean = 1e-9, distribution = \"exponential\", seed = 3 }",
             {"joint_sets[1].spacing", "4e+09 joint planes", "max_blocks"}},
        Case{"discs_of_a_micrometre",
             "spacing = 1.3",
             "spacing = 1.3\nextent = { radius = 1e-6, seed = 5 }",
             {"joint_sets[1].extent", "max_joints = 1000000"}},
        Case{"random_origin_far_away",
             "spacing = 1.3",
             "spacing = { mean = 1.3, distribution = \"exponential\", seed = 3 }\n"
             "origin = [0, 0, 1e12]",
             {"joint_sets[1].origin", "7.69e+11"}},
        Case{"max_blocks_setting",
             "law = \"j\"\n",
             "law = \"j\"\nmax_blocks = 4\n",
             {"joint_sets[1].spacing", "about 5 blocks", "max_blocks = 4"}},
        Case{"max_blocks_zero",
             "law = \"j\"\n",
             "law = \"j\"\nmax_blocks = 0\n",
             {"rock_mass.max_blocks", "at least 1"}},
        Case{"joint_set_twice", "", kJ2 + kJ2, {"joint_sets[3].name", "\"J2\"", "twice"}},
        Case{"tunnel_sides_wrap",
             "",
             "[[excavations]]\ncentre = [2, 0, 2]\nradius = 1\nsides = 4294967300\n",
             {"excavations[1].sides", "[4, 256]", "4294967300"}},
        Case{"excavation_of_1001_planes",
             "",
             "[[excavations]]\nshape = \"planes\"\nplanes = [" +
                 [] {
                   std::string rows;
                   for (int i = 0; i < 1001; ++i) rows += "[0, 0, 1, 3.5], ";
                   return rows;
                 }() +
                 "]\n",
             {"excavations[1].planes", "1001 planes", "limit of 1000"}},
        Case{"face_names_listed",
             "faces = [\"z_min\"]",
             "faces = [\"west\"]",
             {"boundaries[1].faces", "\"west\"", "\"x_min\", \"x_max\""}},
        Case{"dip_direction_misspelt",
             "dip_direction_deg = 0",
             "dip_direction = 0",
             {"joint_sets[1].dip_direction_deg", "is required", "\"dip_direction\"",
              "did you mean \"dip_direction_deg\""}},
        Case{"stage_misspelt", "[[stages]]", "[[stage]]", {"stage:", "did you mean \"stages\""}},
        Case{"shear_stiffness_1e_308",
             "stiffness = 1e8",
             "stiffness = 1e-308",
             {"joint_laws[1].shear", "stiffness", "at least 1 Pa/m", "1e-308"}},
        Case{"strength_reduction_tolerance",
             "",
             "[[stages]]\nname = \"fos\"\nkind = \"strength_reduction\"\ntolerance = 1e-300\n",
             {"stages[2].tolerance", "at least 4e-12", "got 1e-300"}},
        Case{"collapse_tolerance",
             "max_steps = 3000\n",
             "max_steps = 3000\nfind_collapse = true\ncollapse_tolerance = 1e-300\n",
             {"stages[1].collapse_tolerance", "got 1e-300"}},
        Case{"every_block_fixed_after_excavation",
             "",
             "[[excavations]]\nname = \"top\"\nshape = \"box\"\n"
             "min = [-1, -1, 0.7]\nmax = [5, 5, 5]\n[[stages]]\nname = \"dig\"\n"
             "kind = \"excavation\"\nexcavation = \"top\"\nmax_steps = 100\n",
             {"stages[2].excavation", "every free block", "nothing can move"}}),
    [](const ::testing::TestParamInfo<Case>& p) { return std::string(p.param.name); });

// A voussoir beam's collapse search brackets up to its highest level (40 g for the full beam):
// a bracket of 1e-300 g is below what doubles resolve there.
TEST(BoundedInput, VoussoirCollapseToleranceBelowResolutionExitsTwo) {
  const fs::path dir = scratch("voussoir_collapse_tolerance");
  std::ofstream(dir / "beam.toml")
      << "[voussoir]\nfind_collapse = true\ncollapse_tolerance = 1e-300\n"
         "normal = { law = \"linear\", stiffness = 1e10 }\n"
         "shear = { law = \"linear\", stiffness = 1e9, friction_deg = "
         "40 }\n";
  expect_refused(run(dir / "beam.toml", dir / "out"), dir / "out",
                 {"beam.toml", "voussoir.collapse_tolerance", "at least 4e-11", "1e-300"});
}

// Options: each refused before anything is read or written, naming the option.
TEST(BoundedInput, BadOptionsExitTwoNamingTheOption) {
  const fs::path dir = scratch("options");
  std::ofstream(dir / "case.toml") << kRockMass;
  for (const auto& [option, fragment] : std::vector<std::pair<std::string, std::string>>{
           {"--checkpoint-seconds nan",
            "--checkpoint-seconds: must be a finite positive number of seconds, got nan"},
           {"--checkpoint-seconds inf",
            "--checkpoint-seconds: must be a finite positive number of seconds, got inf"},
           {"--threads 2147483647", "--threads: at most"},
           {"--threads 100000", "--threads: at most"},
           {"--threads 0", "--threads: must be a finite positive number of threads, got 0"},
           {"--max-steps 0", "--max-steps: must be a finite positive number of steps, got 0"}}) {
    const auto r = run(dir / "case.toml", dir / "out", option);
    expect_refused(r, dir / "out", {fragment});
    EXPECT_LT(r.err.size(), 300u) << "a short message, not a range to 300 digits: " << r.err;
  }
}

// A folder the system will not create is not a defect of the program: exit code 4, from `run`,
// `generate` and `lab` alike.
TEST(BoundedInput, AnOutputFolderThatCannotBeWrittenExitsFour) {
  const fs::path dir = scratch("unwritable");
  std::ofstream(dir / "case.toml") << kRockMass;
  const std::string out = "/proc/blockdem-cannot-be-here";
  for (const auto& r :
       {run(dir / "case.toml", out),
        test::run_cli("generate '" + (dir / "case.toml").string() + "' --out " + out),
        test::run_cli("lab compression --normal 'law=linear,stiffness=1e10' --max-closure 1e-4 "
                      "--out " +
                      out)}) {
    EXPECT_EQ(r.exit_code, 4) << r.err;
    EXPECT_EQ(r.err.rfind("blockdem: error:", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(out), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  }
}

// Memory the system will not give is not a defect either: a rock mass of a million blocks
// (max_blocks raised) under a 400 MB address-space limit exits 4 with a message, not 1. Skipped
// under a sanitizer, whose shadow memory needs more address space than the limit.
TEST(BoundedInput, OutOfMemoryExitsFour) {
  if (test::sanitized_run()) GTEST_SKIP() << "a sanitizer reserves more address space";
  const fs::path dir = scratch("out_of_memory");
  std::string text = kRockMass;
  text.replace(text.find("max = [4, 4, 4]"), 15, "max = [10, 10, 10]");
  text.replace(text.find("spacing = 1.3"), 13, "spacing = 0.1");
  text.replace(text.find("law = \"j\"\n"), 10, "law = \"j\"\nmax_blocks = 100000000\n");
  for (const char* direction : {"0", "90"}) {
    text += "[[joint_sets]]\ndip_deg = 90\ndip_direction_deg = " + std::string(direction) +
            "\nspacing = 0.1\n";
  }
  std::ofstream(dir / "case.toml") << text;
  const fs::path err = dir / "err.txt";
  const std::string command = "ulimit -v 400000; exec '" + std::string(BLOCKDEM_CLI_PATH) +
                              "' run '" + (dir / "case.toml").string() + "' --out '" +
                              (dir / "out").string() + "' --quiet --no-figures 2>'" + err.string() +
                              "'";
  const int status = std::system(("bash -c \"" + command + "\"").c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 4);
  std::ifstream in(err);
  const std::string message((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(message.rfind("blockdem: error: out of memory", 0), 0u) << message;
}

// A stage that does not converge says its tolerances in %g: 1e-08, not 0.000000.
TEST(BoundedInput, TolerancesInMessagesReadAsG) {
  const fs::path dir = scratch("percent_g");
  std::ofstream(dir / "case.toml") << mutate(Case{"", "max_steps = 3000", "max_steps = 20", {}});
  const auto r = run(dir / "case.toml", dir / "out");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("(tolerance 1e-08)"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("0.000000"), std::string::npos) << r.err;
}

}  // namespace blockdem::input_bounds_test
