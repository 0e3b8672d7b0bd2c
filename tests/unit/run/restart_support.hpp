// Shared by the restart tests: a small scenario with contact shear history and continuously
// yielding joints, fresh output folders, and comparisons of run folders.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "blockdem/io/atomic_file.hpp"
#include "support/temp_path.hpp"

namespace blockdem::test {

/// An absent folder of this process's own, temp/blockdem_<pid>_<name>, removed at exit.
inline std::filesystem::path fresh_dir(const std::string& name) {
  const std::filesystem::path dir = temp_path(name);
  std::filesystem::remove_all(dir);
  return dir;
}

/// Three blocks on a fixed base with continuously yielding joints (their friction grows with
/// plastic slip from zero, so the blocks slip and the joints keep a slip history): settle,
/// gravity tilted by 31 degrees over a ramp, then an equilibrium stage. `extra_steps` lengthens
/// the first stage (another scenario). `last_steps` > 0 makes the last stage a long steps stage.
/// Outputs inside the stages too: a VTK frame every 250 steps (2500 with a long last stage) and a
/// time_history.csv row every 10 steps, capped at 60 rows (its interval doubles several times).
inline std::filesystem::path write_restart_scenario(const std::string& name, int extra_steps,
                                                    long long last_steps = 0) {
  const std::filesystem::path file = temp_path(name + ".toml");
  std::ofstream f(file);
  f << "title = \"restart test\"\n"
       "[settings]\ndamping = 0.3\n"
       "[output]\nvtk_interval = "
    << (last_steps > 0 ? 2500 : 250)
    << "\nhistory_interval = 10\nhistory_max_rows = 60\n"
       "[[materials]]\nname = \"rock\"\ndensity = 2600.0\n"
       "[[joint_laws]]\nname = \"joint\"\nnormal = { law = \"linear\", stiffness = 1e10 }\n"
       "shear = { law = \"continuously_yielding\", friction_deg = 35 }\n"
       "[[blocks]]\nname = \"base\"\nmaterial = \"rock\"\nsize = [1.0, 0.4, 0.05]\n"
       "position = [0.0, 0.0, -0.025]\nmotion = \"fixed\"\n"
       "[[blocks]]\nname = \"b1\"\nmaterial = \"rock\"\nsize = [0.1, 0.1, 0.05]\n"
       "position = [0.0, 0.0, 0.025]\n"
       "[[blocks]]\nname = \"b2\"\nmaterial = \"rock\"\nsize = [0.1, 0.1, 0.05]\n"
       "position = [0.01, 0.0, 0.075]\n"
       "[[blocks]]\nname = \"b3\"\nmaterial = \"rock\"\nsize = [0.1, 0.1, 0.05]\n"
       "position = [0.2, 0.0, 0.025]\n"
       "[[stages]]\nname = \"settle\"\nkind = \"steps\"\nsteps = "
    << 400 + extra_steps
    << "\ngravity = [0.0, 0.0, -9.81]\n"
       "[[stages]]\nname = \"tilt\"\nkind = \"steps\"\nsteps = 600\nramp_steps = 300\n"
       "gravity = [5.05, 0.0, -8.41]\n";
  if (last_steps > 0) {
    f << "[[stages]]\nname = \"long\"\nkind = \"steps\"\nsteps = " << last_steps
      << "\nmax_steps = " << last_steps << "\n";
  } else {
    f << "[[stages]]\nname = \"rest\"\nmax_steps = 600\n";
  }
  return file;
}

/// Relative path -> FNV-1a 64 of the content, for every file under `dir`.
inline std::map<std::string, std::string> folder_digest(const std::filesystem::path& dir) {
  std::map<std::string, std::string> digest;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    digest[std::filesystem::relative(e.path(), dir).generic_string()] =
        hex64(fnv1a64(read_file_bytes(e.path())));
  }
  return digest;
}

/// The run outputs of two folders are byte-identical: every CSV file (time_history.csv too), every
/// VTK frame and .pvd collection, and summary.json but for the fields that describe the machine
/// (wall time, threads).
inline void expect_same_outputs(const std::filesystem::path& a, const std::filesystem::path& b) {
  auto outputs = [](const std::filesystem::path& dir) {
    auto d = folder_digest(dir);
    std::erase_if(d, [](const auto& kv) {
      return !(kv.first.ends_with(".csv") || kv.first.ends_with(".vtk") ||
               kv.first.ends_with(".vtu") || kv.first.ends_with(".pvd"));
    });
    return d;
  };
  const auto da = outputs(a);
  EXPECT_GE(da.size(), 8u) << "history, time history, blocks, contacts, VTK frames and lists";
  EXPECT_TRUE(da.count("time_history.csv") && da.count("vtk/blocks.pvd") &&
              da.count("vtk/contacts.pvd"));
  EXPECT_EQ(da, outputs(b));
  auto summary = [](const std::filesystem::path& dir) {
    auto j = nlohmann::json::parse(read_file_bytes(dir / "summary.json"));
    j.erase("wall_time_s");
    j.erase("threads");
    return j.dump(2);
  };
  EXPECT_EQ(summary(a), summary(b));
}

}  // namespace blockdem::test
