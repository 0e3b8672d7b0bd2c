// The warning of a strength-reduction or collapse search with the point contact (contact_mode
// "boon2012") on blocks that are not boxes (docs/stability.md, "Contact mode"): given for a rock
// mass cut by an inclined joint set, not in face_integrated mode, not without a search and not
// for boxes; `blockdem run` prints it on stderr, once.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "../../validation/stability_support.hpp"
#include "blockdem/run/scene_builders.hpp"
#include "support/temp_path.hpp"

namespace blockdem {
namespace {

// A 4 m cube of rock cut by one joint set dipping 40 degrees (prisms, not boxes), on a fixed
// base, settled under gravity; `stages` appended as TOML.
std::string rock_mass(const std::string& mode, const std::string& stages) {
  return "title = \"rock mass\"\n[settings]\ndamping = 0.7\ncontact_mode = \"" + mode +
         "\"\nrounding_distance = 0.01\n"
         "[[joint_laws]]\nname = \"joint\"\nnormal = { law = \"linear\", stiffness = 1e9 }\n"
         "shear = { law = \"linear\", stiffness = 1e8, friction_deg = 40 }\n"
         "[rock_mass]\nregion = { min = [0, 0, 0], max = [4, 4, 4] }\ndensity = 2500.0\n"
         "law = \"joint\"\n"
         "[[joint_sets]]\ndip_deg = 40\ndip_direction_deg = 90\nspacing = 2.0\n"
         "[[boundaries]]\nfaces = [\"z_min\"]\ncondition = \"fixed\"\n"
         "[[stages]]\nname = \"settle\"\ngravity = [0, 0, -9.81]\n" +
         stages;
}

const std::string kStrength = "[[stages]]\nname = \"fos\"\nkind = \"strength_reduction\"\n";
const std::string kCollapse =
    "[[stages]]\nname = \"raise\"\ngravity = [0, 0, -98.1]\nfind_collapse = true\n";

// The warnings of the scenario that mention the point contact.
std::vector<std::string> point_contact_warnings(const std::string& text) {
  const Scenario sc = parse_scenario(text, "case.toml");
  std::vector<std::string> found;
  std::copy_if(sc.warnings.begin(), sc.warnings.end(), std::back_inserter(found),
               [](const std::string& w) { return w.find("boon2012") != std::string::npos; });
  return found;
}

TEST(PointContactWarning, StrengthReductionOnARockMassInBoon2012) {
  const auto w = point_contact_warnings(rock_mass("boon2012", kStrength));
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("stage \"fos\" searches for a factor of safety"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("not boxes (block \"rock_"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("face_integrated"), std::string::npos) << w[0];
}

TEST(PointContactWarning, CollapseSearchOnARockMassInBoon2012) {
  const auto w = point_contact_warnings(rock_mass("boon2012", kCollapse));
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("stage \"raise\" searches for a collapse load"), std::string::npos) << w[0];
}

TEST(PointContactWarning, NotInFaceIntegratedModeNorWithoutASearchNorForBoxes) {
  EXPECT_TRUE(point_contact_warnings(rock_mass("face_integrated", kStrength)).empty());
  EXPECT_TRUE(point_contact_warnings(rock_mass("boon2012", "")).empty());
  // A box on an incline (boxes only: the base and the block), in boon2012 with a search.
  std::string boxes = test::incline_scenario(30, 40, 0.1, 0.02, kStrength);
  const std::string fi = "contact_mode = \"face_integrated\"";
  boxes.replace(boxes.find(fi), fi.size(), "contact_mode = \"boon2012\"");
  EXPECT_TRUE(point_contact_warnings(boxes).empty());
}

// Six faces do not make a box: a free parallelepiped (a cube sheared by 0.05 m over its height)
// is warned of; a box turned about an oblique axis is still a box.
TEST(PointContactWarning, ASixFacedBlockThatIsNotABoxIsWarnedOfATurnedBoxIsNot) {
  std::string boxes = test::incline_scenario(30, 40, 0.1, 0.02, kStrength);
  const std::string fi = "contact_mode = \"face_integrated\"";
  boxes.replace(boxes.find(fi), fi.size(), "contact_mode = \"boon2012\"");
  const std::string sheared =
      "[[blocks]]\nname = \"sheared\"\nmaterial = \"rock\"\nshape = \"vertices\"\n"
      "vertices = [[0, 0, 0], [0.1, 0, 0], [0.1, 0.1, 0], [0, 0.1, 0], [0.05, 0, 0.1], "
      "[0.15, 0, 0.1], [0.15, 0.1, 0.1], [0.05, 0.1, 0.1]]\nposition = [3.0, 0.0, 1.0]\n";
  const std::string turned =
      "[[blocks]]\nname = \"turned\"\nmaterial = \"rock\"\nsize = [0.1, 0.2, 0.3]\n"
      "position = [-3.0, 0.0, 1.0]\nrotation_deg = 37\nrotation_axis = [1, 2, 3]\n";
  // The blocks go before the stages (a TOML array of tables may be split, but keep it tidy).
  const auto with = [&](const std::string& block) {
    std::string text = boxes;
    text.insert(text.find("[[stages]]"), block);
    return text;
  };
  const auto w = point_contact_warnings(with(sheared));
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("not boxes (block \"sheared\")"), std::string::npos) << w[0];
  EXPECT_TRUE(point_contact_warnings(with(turned)).empty());
}

TEST(PointContactWarning, RunPrintsItOnStderrOnce) {
  const auto dir = test::temp_path("point_contact_warning");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto file = dir / "rock.toml";
  std::ofstream(file) << rock_mass("boon2012", kStrength);
  const auto err = dir / "err.txt";
  // Ten steps a stage: the settling stage does not converge (exit 3); the warning comes first.
  const std::string cmd = std::string(BLOCKDEM_CLI_PATH) + " run " + file.string() + " --out " +
                          (dir / "out").string() + " --quiet --no-figures --max-steps 10 2>" +
                          err.string();
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 3);
  std::ifstream in(err);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string line = "blockdem: warning: " + file.string() + ": stage \"fos\" searches";
  const auto at = text.find(line);
  ASSERT_NE(at, std::string::npos) << text;
  EXPECT_EQ(text.find(line, at + 1), std::string::npos) << "once: " << text;
}

}  // namespace
}  // namespace blockdem
