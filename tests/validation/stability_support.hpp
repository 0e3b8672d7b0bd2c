// Scenario text for the stability tests: a box on a flat fixed base under gravity tilted by the
// incline angle psi (the same statics as a box on a plane dipping psi under vertical gravity).
#pragma once

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "blockdem/run/scenario_runner.hpp"
#include "blockdem/run/scene_builders.hpp"
#include "blockdem/voussoir/measures.hpp"
#include "support/temp_path.hpp"

namespace blockdem::test {

/// A box `b` (along the dip) × 0.1 × `h` m on a 1 m base; gravity g (sin psi, 0, -cos psi);
/// joint friction phi; `stages` appended as TOML.
inline std::string incline_scenario(double psi_deg, double phi_deg, double b, double h,
                                    const std::string& stages, double time_step = 0.0,
                                    double cohesion = 0.0) {
  const double psi = psi_deg * 3.14159265358979323846 / 180.0;
  std::ostringstream s;
  s.precision(12);
  s << "title = \"box on an incline\"\n[settings]\ndamping = 0.7\ncontact_mode = "
       "\"face_integrated\"\n"
    << (time_step > 0.0 ? "time_step = " + std::to_string(time_step) + "\n" : std::string())
    << "[[materials]]\nname = \"rock\"\ndensity = 2500.0\n"
    << "[[joint_laws]]\nname = \"joint\"\nnormal = { law = \"linear\", stiffness = 1e10 }\n"
    << "shear = { law = \"linear\", stiffness = 1e9, friction_deg = " << phi_deg
    << (cohesion > 0.0 ? ", cohesion = " + std::to_string(cohesion) : std::string()) << " }\n"
    << "[[blocks]]\nname = \"base\"\nmaterial = \"rock\"\nsize = [1.0, 0.3, 0.05]\n"
    << "position = [0.0, 0.0, -0.025]\nmotion = \"fixed\"\n"
    << "[[blocks]]\nname = \"block\"\nmaterial = \"rock\"\nsize = [" << b << ", 0.1, " << h
    << "]\nposition = [0.0, 0.0, " << h / 2 << "]\n"
    << "[[stages]]\nname = \"settle\"\ngravity = [0.0, 0.0, -9.81]\n"
    << "[[stages]]\nname = \"tilt\"\ngravity = [" << 9.81 * std::sin(psi) << ", 0.0, "
    << -9.81 * std::cos(psi) << "]\nramp_steps = 2000\nmax_steps = 100000\n"
    << stages;
  return s.str();
}

/// The temporary folder of run_text's run `name` (one per process: suites run side by side).
inline std::filesystem::path run_folder(const std::string& name) {
  return temp_path(name);
}

/// Runs scenario text into a fresh temporary folder, removed when the process ends (kept with
/// BLOCKDEM_KEEP_TEST_FILES).
inline RunResult run_text(const std::string& text, const std::string& name) {
  const Scenario sc = parse_scenario(text, name + ".toml");
  const auto out = run_folder(name);
  std::filesystem::remove_all(out);
  return run_scenario(sc, out);
}

}  // namespace blockdem::test
