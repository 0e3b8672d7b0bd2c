// What a restart compares (docs/restart.md, "Branching"): the scenario up to each stage, from the
// parsed file. Reference: the definition. Equal trees hash alike whatever their text; a change
// moves exactly the hashes of the stages from where it is on; `whole` is the hash earlier
// versions wrote (the file's bytes, then the options).
#include <gtest/gtest.h>

#include <string>

#include "blockdem/io/atomic_file.hpp"
#include "blockdem/io/checkpoint_file.hpp"
#include "blockdem/run/scenario_fingerprint.hpp"

namespace blockdem {
namespace scenario_fingerprint_test {

const std::string kBase = R"(title = "t"
[settings]
damping = 0.7
[[materials]]
name = "rock"
density = 2500.0
[[stages]]
name = "settle"
gravity = [0.0, 0.0, -9.81]
[[stages]]
name = "tilt"
ramp_steps = 2000
[[stages]]
name = "fos"
kind = "strength_reduction"
factor_bounds = [1.0, 3.0]
)";

TEST(ScenarioFingerprint, CommentsSpacingAndKeyOrderDoNotCount) {
  const std::string same = R"(# the same tree
title   = "t"
[[materials]]
density = 2500.0   # kg/m3
name = "rock"
[settings]
damping = 0.7
[[stages]]
gravity = [0.0, 0.0, -9.81]
name = "settle"
[[stages]]
ramp_steps = 2000
name = "tilt"
[[stages]]
name = "fos"
factor_bounds = [1.0, 3.0]
kind = "strength_reduction"
)";
  const auto a = scenario_fingerprint(kBase, "max_steps=0");
  const auto b = scenario_fingerprint(same, "max_steps=0");
  ASSERT_EQ(a.by_stage.size(), 4u);
  EXPECT_EQ(a.by_stage, b.by_stage);
  EXPECT_NE(a.whole, b.whole);  // the bytes differ
  EXPECT_EQ(a.whole, fnv1a64("max_steps=0", fnv1a64(kBase)));
}

TEST(ScenarioFingerprint, AChangeMovesTheStagesFromWhereItIs) {
  const auto a = scenario_fingerprint(kBase, "max_steps=0");
  std::string later = kBase;
  later.replace(later.find("[1.0, 3.0]"), 10, "[1.2, 3.0]");
  const auto b = scenario_fingerprint(later, "max_steps=0");
  for (int k = 0; k < 3; ++k) EXPECT_EQ(a.by_stage[k], b.by_stage[k]) << k;
  EXPECT_NE(a.by_stage[3], b.by_stage[3]);
  // A stage added at the end: the first four agree.
  const auto c = scenario_fingerprint(kBase + "[[stages]]\nname = \"more\"\n", "max_steps=0");
  ASSERT_EQ(c.by_stage.size(), 5u);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(a.by_stage[k], c.by_stage[k]) << k;
  // A number's type counts: 2000 and 2000.0 differ from stage 2 on.
  std::string typed = kBase;
  typed.replace(typed.find("ramp_steps = 2000"), 17, "ramp_steps = 2000.0");
  const auto d = scenario_fingerprint(typed, "max_steps=0");
  EXPECT_EQ(a.by_stage[1], d.by_stage[1]);
  EXPECT_NE(a.by_stage[2], d.by_stage[2]);
  // A setting, or an option, moves every one.
  std::string setting = kBase;
  setting.replace(setting.find("0.7"), 3, "0.8");
  const auto e = scenario_fingerprint(setting, "max_steps=0");
  const auto f = scenario_fingerprint(kBase, "max_steps=100");
  for (int k = 0; k < 4; ++k) {
    EXPECT_NE(a.by_stage[k], e.by_stage[k]) << k;
    EXPECT_NE(a.by_stage[k], f.by_stage[k]) << k;
  }
}

TEST(ScenarioFingerprint, ACheckpointIsAcceptedWhereTheScenarioAgreesUpToItsStage) {
  const auto a = scenario_fingerprint(kBase, "max_steps=0");
  std::string later = kBase;
  later.replace(later.find("[1.0, 3.0]"), 10, "[1.2, 3.0]");
  const auto b = scenario_fingerprint(later, "max_steps=0");
  const std::vector<std::string> names = {"settle", "tilt", "fos"};
  // Written by `a` at the start of stage 3 (0-based level 2), continued by `b`.
  const std::string said = check_restart_point(b, "c.bdck", a.at(2, false), 2, false, names);
  EXPECT_NE(said.find("stages 1 to 2 are the same"), std::string::npos) << said;
  EXPECT_NE(said.find("from stage 3 'fos' on, the stages are this file's"), std::string::npos)
      << said;
  // Inside stage 3: stage 3 must agree too.
  EXPECT_THROW(check_restart_point(b, "c.bdck", a.at(2, true), 2, true, names), CheckpointError);
  // A hash that says "the start of stage 2" on a point inside stage 3: refused.
  EXPECT_THROW(check_restart_point(b, "c.bdck", a.at(1, false), 2, false, names), CheckpointError);
  // An earlier version's checkpoint of this very file.
  EXPECT_NE(check_restart_point(a, "c.bdck", a.whole, 2, true, names).find("byte for byte"),
            std::string::npos);
  EXPECT_THROW(check_restart_point(b, "c.bdck", a.whole, 2, true, names), CheckpointError);
}

TEST(ScenarioFingerprint, AFileThatDoesNotParseHasItsBytesOnly) {
  const auto a = scenario_fingerprint("title = ", "max_steps=0");
  EXPECT_TRUE(a.by_stage.empty());
  EXPECT_EQ(a.at(3, true), a.whole);
  EXPECT_EQ(a.accepted(), std::vector<std::uint64_t>{a.whole});
}

}  // namespace scenario_fingerprint_test
}  // namespace blockdem
