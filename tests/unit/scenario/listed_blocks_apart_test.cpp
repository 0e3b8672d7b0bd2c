// A long [[blocks]] list is parsed a run of tables at a time; the scenario read that way is the
// one read from the whole file's TOML tree, and every error is the whole tree's. The oracle is
// the same file with its headers written "[[ blocks ]]" (the same TOML, but no line is exactly
// "[[blocks]]", so the file is read whole).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <string_view>

#include "blockdem/run/scene_builders.hpp"

namespace blockdem {
namespace listed_blocks_apart_test {
namespace {

// 2 500 blocks (three runs of 1 024 tables), a servo block with its table as a header, a table
// between two blocks and the stages after the list.
std::string long_list(const std::string& tail = "") {
  std::string s = R"(title = "long list"
[[materials]]
name = "rock"
density = 2600.0
[[joint_laws]]
name = "j"
normal = { law = "linear", stiffness = 1e10 }
shear = { law = "linear", stiffness = 1e9, friction_deg = 30 }
[[blocks]]
name = "base"
material = "rock"
size = [200.0, 2.0, 0.2]
position = [100.0, 0.0, -0.1]
motion = "fixed"
)";
  for (int i = 0; i < 2499; ++i) {
    s += "[[blocks]]\nname = \"c" + std::to_string(i) + "\"\n";
    s += i % 7 == 0 ? "density = 2000.0\n" : "material = \"rock\"\n";
    if (i % 11 == 0) s += "group = \"g" + std::to_string(i % 3) + "\"\n";
    s += i % 5 == 0 ? "size = [0.05, 0.05, 0.05]\n" : "size = [0.04, 0.05, 0.05]\n";
    s += "position = [" + std::to_string(0.08 * i) + ", 0.0, 0.026]\n";
    if (i == 1500) {
      s += "motion = \"servo\"\n[blocks.servo]\naxis = [0, 0, -1]\ntarget_force = 100.0\n";
      s += "gain = 1e-6\nmax_speed = 0.01\n";
    }
    if (i == 1800) s += "[output]\nvtk = false\nhistory_interval = 7\n";
  }
  s += R"([[joints]]
groups = ["", ""]
law = "j"
[[stages]]
name = "settle"
gravity = [0, 0, -9.81]
max_steps = 10
)";
  return s + tail;
}

// The same TOML with no line that is exactly "[[blocks]]".
std::string spaced(std::string s) {
  for (auto at = s.find("[[blocks]]"); at != std::string::npos; at = s.find("[[blocks]]", at + 1))
    s.replace(at, 10, "[[ blocks ]]");
  return s;
}

std::string error_of(const std::string& text) {
  try {
    parse_scenario(text, "long.toml");
  } catch (const ScenarioError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return "";
}

// The syntax error of the whole file's TOML tree, as the reader words it.
std::string whole_tree_error(const std::string& text) {
  try {
    const toml::table tree = toml::parse(std::string_view(text), std::string_view("long.toml"));
    ADD_FAILURE() << "no TOML error, " << tree.size() << " keys";
  } catch (const toml::parse_error& e) {
    return "long.toml: TOML syntax error at line " + std::to_string(e.source().begin.line) +
           ", column " + std::to_string(e.source().begin.column) + ": " +
           std::string(e.description());
  }
  return "";
}

TEST(ListedBlocksApart, TheScenarioIsTheWholeTreesBitForBit) {
  const std::string text = long_list();
  const Scenario got = parse_scenario(text, "long.toml");
  const Scenario want = parse_scenario(spaced(text), "long.toml");
  ASSERT_EQ(got.blocks.size(), 2500u);
  ASSERT_EQ(want.blocks.size(), 2500u);
  for (std::size_t i = 0; i < got.blocks.size(); ++i) {
    const Block& a = got.blocks[i];
    const Block& b = want.blocks[i];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.group(), b.group());
    EXPECT_EQ(a.density, b.density);
    EXPECT_EQ(a.mass, b.mass);
    EXPECT_EQ(a.inertia, b.inertia);
    EXPECT_EQ(a.position, b.position);
    EXPECT_EQ(a.initial_position, b.initial_position);
    EXPECT_EQ(a.orientation.coeffs(), b.orientation.coeffs());
    EXPECT_EQ(a.motion, b.motion);
    EXPECT_EQ(a.servo().axis, b.servo().axis);
    EXPECT_EQ(a.servo().target_force, b.servo().target_force);
    EXPECT_TRUE(std::ranges::equal(a.shape.vertices(), b.shape.vertices()));
    EXPECT_TRUE(a.world_planes.empty());
  }
  EXPECT_EQ(got.blocks[1501].motion, Motion::servo);
  EXPECT_EQ(got.blocks[12].group(), "g2");
  // Identical boxes share one shape across the runs of tables, as in the whole tree.
  EXPECT_TRUE(got.blocks[2].shape.shares_data_with(got.blocks[2400].shape));
  EXPECT_EQ(got.title, want.title);
  EXPECT_EQ(got.output.vtk, false);
  EXPECT_EQ(got.output.history_interval, 7);
  EXPECT_EQ(got.output.history_interval, want.output.history_interval);
  ASSERT_EQ(got.stages.size(), 1u);
  EXPECT_EQ(got.stages[0].max_steps, want.stages[0].max_steps);
  EXPECT_EQ(got.joint_rules.size(), want.joint_rules.size());
  EXPECT_EQ(got.materials, want.materials);
  EXPECT_EQ(got.warnings, want.warnings);
}

TEST(ListedBlocksApart, ErrorsAreTheWholeTrees) {
  const std::string text = long_list();
  // A block's error in the third run of tables, and a setting after the list, which is read
  // first.
  std::string bad = text;
  bad.replace(bad.find("name = \"c2200\""), 14, "name = \"c2200\"\ncolour = 3");
  EXPECT_EQ(error_of(bad),
            "long.toml: blocks[2202].colour: unknown key (misspelt, or not a "
            "setting of this table)");
  EXPECT_EQ(error_of(bad + "[settings]\ndamping = 2.0\n"),
            "long.toml: settings.damping: must be in [0, 1)");
  // A name given twice in two runs of tables.
  std::string twice = text;
  twice.replace(twice.find("name = \"c2300\""), 14, "name = \"c5\"");
  EXPECT_EQ(error_of(twice), "long.toml: blocks[2302].name: block \"c5\" is defined twice");
  // A table given in two runs of tables; a syntax error late in the file; a multi-line array
  // open across a "[[blocks]]" line (c1022 is the last table of the first run of tables): the
  // whole file's error, at its line in the file.
  const std::string again = text + "[output]\nvtk = true\n";
  std::string syntax = text;
  syntax.replace(syntax.find("name = \"c2400\""), 14, "name = \"c2400");
  std::string open = text;
  const std::string row = "position = [" + std::to_string(0.08 * 1022) + ", 0.0, 0.026]";
  open.replace(open.find(row), row.size(), row.substr(0, row.size() - 7));
  for (const std::string& t : {again, syntax, open}) {
    const std::string want = whole_tree_error(t);
    EXPECT_NE(want.find("TOML syntax error at line "), std::string::npos);
    EXPECT_EQ(error_of(t), want);
  }
  const std::string line = std::to_string(
      1 + std::count(syntax.begin(), syntax.begin() + syntax.find("name = \"c2400"), '\n'));
  EXPECT_NE(error_of(syntax).find("TOML syntax error at line " + line + ","), std::string::npos);
}

TEST(ListedBlocksApart, AMultiLineStringHoldingAHeaderLineIsNotCut) {
  // The "[[blocks]]" line inside the title is text, not a header: one block.
  const std::string text = std::string("title = \"\"\"\n[[blocks]]\n\"\"\"\n") + R"(
[[joint_laws]]
name = "j"
normal = { law = "linear", stiffness = 1e10 }
shear = { law = "linear", stiffness = 1e9, friction_deg = 30 }
[[blocks]]
name = "a"
density = 2600.0
size = [0.1, 0.1, 0.1]
[[stages]]
name = "settle"
gravity = [0, 0, -9.81]
)";
  const Scenario sc = parse_scenario(text, "title.toml");
  ASSERT_EQ(sc.blocks.size(), 1u);
  EXPECT_EQ(sc.title, "[[blocks]]\n");
}

}  // namespace
}  // namespace listed_blocks_apart_test
}  // namespace blockdem
