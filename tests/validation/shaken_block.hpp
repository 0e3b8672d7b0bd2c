// A scene for the dynamic-stage tests: a 0.4 x 0.4 x 0.2 m block (2500 kg/m^3) on a fixed
// 3 x 1 x 0.1 m plate (group "base"), a linear joint (k_n = k_s = 1e10 Pa/m, friction 30°),
// settled under gravity with local damping 0.7 before the stages given.
#pragma once

#include <string>

namespace blockdem::test {

/// The scenario's text: `settings` and `output` are extra lines of [settings] and [output],
/// `stages` the [[stages]] after the settling one.
inline std::string shaken_block_scenario(const std::string& settings, const std::string& output,
                                         const std::string& stages) {
  return "[settings]\ndamping = 0.7\n" + settings +
         "[[materials]]\nname = \"rock\"\ndensity = 2500.0\n"
         "[[joint_laws]]\nname = \"joint\"\nnormal = { law = \"linear\", stiffness = 1e10 }\n"
         "shear = { law = \"linear\", stiffness = 1e10, friction_deg = 30 }\n"
         "[[blocks]]\nname = \"plate\"\ngroup = \"base\"\nmaterial = \"rock\"\n"
         "size = [3.0, 1.0, 0.1]\nposition = [0.0, 0.0, -0.05]\nmotion = \"fixed\"\n"
         "[[blocks]]\nname = \"block\"\nmaterial = \"rock\"\nsize = [0.4, 0.4, 0.2]\n"
         "position = [0.0, 0.0, 0.1]\n"
         "[output]\n" +
         output + "[[stages]]\nname = \"settle\"\ngravity = [0.0, 0.0, -9.81]\n" + stages;
}

}  // namespace blockdem::test
