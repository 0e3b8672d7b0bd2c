// Bad scenario input: every error names the file, the key and the reason; the CLI exits
// non-zero and writes nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <ostream>
#include <string>

#include "blockdem/run/scene_builders.hpp"
#include "support/temp_path.hpp"

// A namespace of this file's own: the unity build (cmake/build_speed.cmake) compiles it together
// with other test files that define helpers of the same names.
namespace blockdem::scenario_errors_test {
namespace {

const char* kGood = R"(
title = "two blocks"
[[materials]]
name = "rock"
density = 2600
[[joint_laws]]
name = "j"
normal = { law = "linear", stiffness = 1e10 }
shear = { law = "linear", stiffness = 1e9, friction_deg = 30 }
[[blocks]]
name = "base"
material = "rock"
size = [1, 1, 0.2]
position = [0, 0, -0.1]
motion = "fixed"
[[blocks]]
name = "top"
material = "rock"
size = [0.2, 0.2, 0.2]
position = [0, 0, 0.1]
[[stages]]
name = "settle"
gravity = [0, 0, -9.81]
)";

// Parses `text` and returns the ScenarioError, or fails the test if there is none.
ScenarioError error_of(const std::string& text) {
  try {
    const Scenario sc = parse_scenario(text, "case.toml");
    build_world(sc);
  } catch (const ScenarioError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return ScenarioError("", "", "");
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

TEST(ScenarioErrors, GoodScenarioBuilds) {
  const Scenario sc = parse_scenario(kGood, "case.toml");
  EXPECT_EQ(sc.blocks.size(), 2u);
  EXPECT_NO_THROW(build_world(sc));
}

// The strength keys of a shear table reach the law: tan(phi), c, sigma_t and tan(phi_r).
TEST(ScenarioErrors, StrengthKeysReachTheJointLaw) {
  const Scenario sc =
      parse_scenario(replace(kGood, "friction_deg = 30",
                             "friction_deg = 30, cohesion = 2e5, tensile_strength = 1e5, "
                             "residual_friction_deg = 25"),
                     "case.toml");
  const JointStrength& s = strength_of(sc.joint_laws.at(0).shear);
  EXPECT_EQ(s.friction_coefficient, std::tan(30.0 * std::numbers::pi / 180.0));
  EXPECT_EQ(s.cohesion, 2e5);
  EXPECT_EQ(s.tensile_strength, 1e5);
  EXPECT_EQ(s.residual_friction(), std::tan(25.0 * std::numbers::pi / 180.0));
  EXPECT_NO_THROW(build_world(sc));
}

struct BadCase {
  const char* name;
  std::string text;
  const char* key;
  const char* reason_word;
};

/// The case by its name: GoogleTest otherwise prints the parameter's bytes, pointers included, and
/// the CTest names made from them would change with every build (tests/costs/ matches by name).
void PrintTo(const BadCase& c, std::ostream* os) {
  *os << c.name;
}

class ScenarioErrorCases : public ::testing::TestWithParam<BadCase> {};

TEST_P(ScenarioErrorCases, NamesFileKeyAndReason) {
  const BadCase& c = GetParam();
  const ScenarioError e = error_of(c.text);
  EXPECT_EQ(e.file(), "case.toml");
  EXPECT_EQ(e.key(), c.key) << e.what();
  EXPECT_NE(std::string(e.reason()).find(c.reason_word), std::string::npos) << e.what();
}

INSTANTIATE_TEST_SUITE_P(
    Bad, ScenarioErrorCases,
    ::testing::Values(
        BadCase{"unknown_key", replace(kGood, "density = 2600", "density = 2600\ndensty = 1"),
                "materials[1].densty", "unknown key"},
        BadCase{"wrong_type", replace(kGood, "density = 2600", "density = \"heavy\""),
                "materials[1].density", "must be a number"},
        BadCase{"negative_density", replace(kGood, "density = 2600", "density = -5"),
                "materials[1].density", "positive"},
        BadCase{"non_convex_vertices",
                replace(kGood, "size = [0.2, 0.2, 0.2]\nposition = [0, 0, 0.1]",
                        "shape = \"vertices\"\nvertices = "
                        "[[0,0,0],[1,0,0],[0,1,0],[1,1,0],[0,0,1],[1,0,1],[0,1,1],"
                        "[1,1,1],[0.5,0.5,0.5]]\nposition = [-0.5, -0.5, 0.0]"),
                "blocks[2].vertices", "not convex"},
        BadCase{"unbounded_planes",
                replace(kGood, "size = [0.2, 0.2, 0.2]\nposition = [0, 0, 0.1]",
                        "shape = \"planes\"\nplanes = "
                        "[[1,0,0,0.1],[-1,0,0,0.1],[0,1,0,0.1],[0,-1,0,0.1],[0,0,-1,0]]"),
                "blocks[2].planes", "unbounded"},
        BadCase{"deep_overlap", replace(kGood, "position = [0, 0, 0.1]", "position = [0, 0, 0.0]"),
                "blocks[2]", "overlap"},
        BadCase{"unknown_motion", replace(kGood, "motion = \"fixed\"", "motion = \"frozen\""),
                "blocks[1].motion", "must be one of"},
        BadCase{"density_scaling_in_time",
                replace(kGood, "name = \"settle\"",
                        "name = \"settle\"\nkind = \"duration\"\nduration = 0.01\n"
                        "density_scaling = true"),
                "stages[1].density_scaling", "duration"},
        BadCase{"bad_friction", replace(kGood, "friction_deg = 30", "friction_deg = 95"),
                "joint_laws[1].shear.law", "friction"},
        BadCase{"negative_cohesion",
                replace(kGood, "friction_deg = 30", "friction_deg = 30, cohesion = -1e5"),
                "joint_laws[1].shear.law", "'cohesion'"},
        BadCase{
            "residual_above_peak",
            replace(kGood, "friction_deg = 30", "friction_deg = 30, residual_friction_deg = 35"),
            "joint_laws[1].shear.law", "'residual_friction_deg'"},
        BadCase{"negative_stiffness", replace(kGood, "stiffness = 1e10", "stiffness = -1e10"),
                "joint_laws[1].normal.law", "stiffness"},
        BadCase{"unknown_material",
                replace(kGood, "material = \"rock\"\nsize = [0.2",
                        "material = \"granite\"\nsize = [0.2"),
                "blocks[2].material", "no material"},
        BadCase{"syntax", replace(kGood, "[[stages]]", "[[stages]"), "", "syntax"},
        BadCase{"no_stages", std::string(kGood).substr(0, std::string(kGood).find("[[stages]]")),
                "stages", "at least one"},
        BadCase{"voussoir_zero_blocks",
                "[voussoir]\nblocks = 0\nnormal = {law=\"linear\"}\nshear = {law=\"linear\"}\n",
                "voussoir.blocks", "at least one"},
        BadCase{"voussoir_negative_size",
                "[voussoir]\nblock_depth = -0.02\nnormal = {law=\"linear\"}\nshear = "
                "{law=\"linear\"}\n",
                "voussoir.block_depth", "positive"},
        BadCase{"voussoir_g_below_1",
                "[voussoir]\ng_levels = [0.5, 2]\nnormal = {law=\"linear\"}\nshear = "
                "{law=\"linear\"}\n",
                "voussoir.g_levels", "at least 1"},
        BadCase{"voussoir_unreachable_preload",
                "[voussoir]\npreload_force = 1e12\nnormal = {law=\"linear\"}\nshear = "
                "{law=\"linear\"}\n",
                "voussoir.preload_force", "cannot be reached"},
        // Beams too large to build (a billion blocks; a span of 1e308 m) or too small to resolve.
        BadCase{"voussoir_a_billion_blocks",
                "[voussoir]\nblocks = 1000000000\nnormal = {law=\"linear\"}\nshear = "
                "{law=\"linear\"}\n",
                "voussoir.blocks", "at most 1000"},
        BadCase{"voussoir_huge_block",
                "[voussoir]\nblock_length = 1e308\nnormal = {law=\"linear\"}\nshear = "
                "{law=\"linear\"}\n",
                "voussoir.block_length", "between 0.001 and 1000 m"},
        BadCase{"voussoir_tiny_block",
                "[voussoir]\nblock_depth = 1e-300\nnormal = {law=\"linear\"}\nshear = "
                "{law=\"linear\"}\n",
                "voussoir.block_depth", "between 0.001 and 1000 m"},
        BadCase{"voussoir_long_span",
                "[voussoir]\nblocks = 1000\nblock_length = 1000.0\nnormal = {law=\"linear\"}\n"
                "shear = {law=\"linear\"}\n",
                "voussoir.block_length", "at most 10000 m"}),
    [](const ::testing::TestParamInfo<BadCase>& p) { return std::string(p.param.name); });

// The CLI: non-zero exit, the message on stderr, and no output folder.
TEST(ScenarioErrors, CliExitsNonZeroAndWritesNothing) {
  const auto dir = test::temp_path("scenario_errors");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto file = dir / "bad.toml";
  std::ofstream(file) << replace(kGood, "density = 2600", "density = -5");
  const auto out = dir / "out";
  const std::string cmd = std::string(BLOCKDEM_CLI_PATH) + " run " + file.string() + " --out " +
                          out.string() + " 2> " + (dir / "err.txt").string();
  const int status = std::system(cmd.c_str());
  EXPECT_NE(status, 0);
  std::ifstream err(dir / "err.txt");
  const std::string text((std::istreambuf_iterator<char>(err)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("bad.toml: materials[1].density"), std::string::npos) << text;
  EXPECT_FALSE(std::filesystem::exists(out)) << "no output may be written for a bad scenario";
}

TEST(ScenarioErrors, ReproduceRejectsUnknownCase) {
  const auto out = test::temp_path("reproduce_bad_case");
  std::filesystem::remove_all(out);
  const std::string cmd = std::string(BLOCKDEM_CLI_PATH) +
                          " reproduce boon2015 --case T9-9 --quiet --no-figures --out " +
                          out.string() + " 2>/dev/null";
  EXPECT_NE(std::system(cmd.c_str()), 0);
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace blockdem::scenario_errors_test
