// Deep initial overlaps judged by the stress their closure would carry: rejected (naming both
// blocks) above 100 times the weight of a rock column as high as the model, accepted below.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "blockdem/run/scene_builders.hpp"

namespace blockdem::test {
namespace {

// A 0.1 m cube placed `overlap` into a fixed base 0.05 m thick; linear joint k_n = 1e10 Pa/m.
// Model height H = 0.05 + 0.1 - overlap, so the limit is 100 rho g H = 100 x 2600 x 9.81 x
// ~0.15 = 3.8e5 Pa; the closure stress is k_n x overlap.
Scenario cube_into_base(double overlap) {
  std::ostringstream s;
  s.precision(17);
  s << "[[materials]]\nname = \"rock\"\ndensity = 2600.0\n"
       "[[joint_laws]]\nname = \"joint\"\nnormal = { law = \"linear\", stiffness = 1e10 }\n"
       "shear = { law = \"linear\", stiffness = 1e9, friction_deg = 35 }\n"
       "[[blocks]]\nname = \"base\"\nmaterial = \"rock\"\nsize = [1.0, 1.0, 0.05]\n"
       "position = [0.0, 0.0, -0.025]\nmotion = \"fixed\"\n"
       "[[blocks]]\nname = \"cube\"\nmaterial = \"rock\"\nsize = [0.1, 0.1, 0.1]\n"
       "position = [0.0, 0.0, "
    << 0.05 - overlap
    << "]\n"
       "[[stages]]\nname = \"settle\"\ngravity = [0.0, 0.0, -9.81]\n";
  return parse_scenario(s.str(), "cube.toml");
}

TEST(InitialOverlap, AClosureStressAboveTheBoundIsAnInputErrorNamingTheBlocks) {
  // 1 mm: 1e7 Pa, 26 times the bound, while only 1/87 of the cube's bounding radius (the
  // radius rule alone, 0.25 of it, would let it through).
  const Scenario sc = cube_into_base(1e-3);
  try {
    build_world(sc);
    FAIL() << "a 1 mm overlap at k_n = 1e10 Pa/m must be refused";
  } catch (const ScenarioError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("\"base\""), std::string::npos) << what;
    EXPECT_NE(what.find("\"cube\""), std::string::npos) << what;
    EXPECT_NE(what.find("Pa"), std::string::npos) << what;
  }
}

TEST(InitialOverlap, AClosureStressBelowTheBoundIsAccepted) {
  // 1 micrometre: 1e4 Pa, a fortieth of the bound.
  EXPECT_NO_THROW(build_world(cube_into_base(1e-6)));
}

}  // namespace
}  // namespace blockdem::test
