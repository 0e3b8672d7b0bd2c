// The scenario key `twist` of [settings]: its default follows the contact mode (on in
// face_integrated, off in the paper's boon2012), it can be set either way, and a value that is not
// a boolean is an error naming the file and the key.
#include <gtest/gtest.h>

#include <string>

#include "blockdem/run/scene_builders.hpp"

namespace blockdem {
namespace {

std::string scenario_with(const std::string& settings) {
  return "title = \"twist\"\n[settings]\n" + settings + R"(
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
}

bool twist_of(const std::string& settings) {
  return parse_scenario(scenario_with(settings), "case.toml").settings.twist_enabled();
}

TEST(TwistKey, DefaultFollowsTheContactModeAndCanBeSet) {
  EXPECT_TRUE(twist_of("contact_mode = \"face_integrated\""));
  EXPECT_FALSE(twist_of("contact_mode = \"boon2012\""));
  EXPECT_TRUE(twist_of("contact_mode = \"boon2012\"\ntwist = true"));
  EXPECT_FALSE(twist_of("contact_mode = \"face_integrated\"\ntwist = false"));
}

TEST(TwistKey, NonBooleanIsAnErrorNamingFileAndKey) {
  try {
    parse_scenario(scenario_with("twist = \"yes\""), "case.toml");
    FAIL() << "no error for twist = \"yes\"";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(std::string(e.file()), "case.toml");
    EXPECT_EQ(std::string(e.key()), "settings.twist") << e.what();
    EXPECT_NE(std::string(e.reason()).find("true or false"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace blockdem
