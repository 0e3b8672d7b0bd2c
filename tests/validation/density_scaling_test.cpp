// Density scaling of quasi-static stages (docs/stability.md) and the block that sets the time
// step. Statics does not depend on inertia: a stack of blocks of very different sizes, run to a
// tight equilibrium with and without scaling, carries the same contact forces (the weight above
// each contact, a closed form, for the column; the unscaled run as the oracle for the wall);
// a duration stage runs unscaled; a strength-reduction factor keeps its bracket.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "blockdem/numerics/units.hpp"
#include "blockdem/world/stage.hpp"
#include "blockdem/world/time_step_report.hpp"
#include "stability_support.hpp"
#include "validation/scenes.hpp"

// A namespace of this file's own: the unity build compiles it with other test files.
namespace blockdem::density_scaling_test {

using test::box_block;
using test::linear_world;

constexpr double kDensity = 2500.0;  // (kg/m^3)
constexpr double kNormal = 1e10;     // (Pa/m)

/// A stage run to a tight equilibrium (unbalanced ratio 1e-9: forces to about 1e-9 relative).
Stage tight_settle(bool scaling) {
  Stage s;
  s.name = "settle";
  s.gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
  s.unbalanced_tolerance = 1e-9;
  s.kinetic_tolerance = 1e-14;
  s.max_steps = 2000000;
  s.density_scaling = scaling;
  return s;
}

/// A column of 0.5 x 0.5 m boxes on a fixed base, heights from 0.5 m down to 1 cm.
World column() {
  WorldSettings settings;
  settings.damping = 0.7;
  World w = linear_world(kNormal, 1e9, 40.0, settings);
  w.add_block(box_block({1.0, 1.0, 0.1}, {0, 0, -0.05}, kDensity, Motion::fixed, "base"));
  const std::vector<double> heights = {0.5, 0.01, 0.3, 0.02, 0.4};
  double z = 0.0;
  for (std::size_t i = 0; i < heights.size(); ++i) {
    w.add_block(box_block({0.5, 0.5, heights[i]}, {0, 0, z + heights[i] / 2}, kDensity,
                          Motion::free, "layer_" + std::to_string(i)));
    z += heights[i];
  }
  return w;
}

/// Two boxes of different widths side by side (2 mm apart) on a fixed base, a thin slab across
/// both, and a small block on the slab off its middle: the slab's load splits between its
/// supports by their stiffness (statically indeterminate).
World wall() {
  WorldSettings settings;
  settings.damping = 0.7;
  World w = linear_world(kNormal, 1e9, 40.0, settings);
  w.add_block(box_block({2.0, 1.0, 0.1}, {0, 0, -0.05}, kDensity, Motion::fixed, "base"));
  w.add_block(box_block({0.6, 0.4, 0.4}, {-0.3, 0, 0.2}, kDensity, Motion::free, "left"));
  w.add_block(box_block({0.3, 0.4, 0.4}, {0.152, 0, 0.2}, kDensity, Motion::free, "right"));
  w.add_block(box_block({0.9, 0.4, 0.02}, {-0.15, 0, 0.41}, kDensity, Motion::free, "slab"));
  w.add_block(box_block({0.2, 0.2, 0.2}, {0.1, 0, 0.52}, kDensity, Motion::free, "top"));
  return w;
}

/// The contact forces on b of every contact, in (a, b) order.
std::vector<Eigen::Vector3d> forces(const World& w) {
  std::vector<Eigen::Vector3d> out;
  for (const Contact* c : w.contacts()) out.push_back(c->force_on_b());
  return out;
}

/// The largest difference of two runs' contact forces over the largest force (-).
double relative_difference(const World& a, const World& b) {
  const std::vector<Eigen::Vector3d> fa = forces(a), fb = forces(b);
  EXPECT_EQ(fa.size(), fb.size());
  double largest = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < std::min(fa.size(), fb.size()); ++i) {
    largest = std::max(largest, fa[i].norm());
    worst = std::max(worst, (fa[i] - fb[i]).norm());
  }
  return worst / largest;
}

TEST(DensityScaling, ColumnReachesTheWeightAboveEachContact) {
  World plain = column(), scaled = column();
  const StageResult rp = run_stage(plain, tight_settle(false));
  const StageResult rs = run_stage(scaled, tight_settle(true));
  ASSERT_TRUE(rp.converged) << rp.message;
  ASSERT_TRUE(rs.converged) << rs.message;
  EXPECT_FALSE(plain.density_scaled());
  EXPECT_TRUE(scaled.density_scaled());
  // The slivers' inertia is raised (the 1 cm layer's five times), the heaviest block's not;
  // the weight is not.
  EXPECT_GT(scaled.blocks()[2].mass_scale, 4.0);
  EXPECT_EQ(scaled.blocks()[1].mass_scale, 1.0);
  EXPECT_EQ(scaled.blocks()[2].mass, plain.blocks()[2].mass);
  // Closed form: each contact carries the weight of the layers above it.
  const std::vector<const Contact*> contacts = scaled.contacts();
  ASSERT_EQ(contacts.size(), 5u);
  for (const Contact* c : contacts) {
    double above = 0.0;
    for (std::size_t i = static_cast<std::size_t>(c->b); i < scaled.blocks().size(); ++i)
      above += scaled.blocks()[i].mass * 9.81;
    EXPECT_NEAR(c->force_on_b().z(), above, 1e-6 * above) << c->a << "-" << c->b;
  }
  EXPECT_LT(relative_difference(plain, scaled), 1e-6);
  // The point of it: fewer steps.
  std::printf("column: %lld steps unscaled, %lld scaled\n", static_cast<long long>(rp.steps),
              static_cast<long long>(rs.steps));
  EXPECT_LT(rs.steps, rp.steps);
}

// Gravity is ramped in both runs: the shear springs are incremental, so a hyperstatic stack
// keeps a self-equilibrated shear that depends on the loading path (under gravity applied at
// once, 0.2 N here against 2.5 kN, 9e-5 of the largest force, differs between the two runs).
TEST(DensityScaling, WallReachesTheUnscaledForces) {
  World plain = wall(), scaled = wall();
  Stage sp = tight_settle(false), ss = tight_settle(true);
  sp.ramp_steps = ss.ramp_steps = 20000;
  const StageResult rp = run_stage(plain, sp);
  const StageResult rs = run_stage(scaled, ss);
  ASSERT_TRUE(rp.converged) << rp.message;
  ASSERT_TRUE(rs.converged) << rs.message;
  EXPECT_TRUE(scaled.density_scaled());
  EXPECT_LT(relative_difference(plain, scaled), 1e-6);
  std::printf("wall: %lld steps unscaled, %lld scaled\n", static_cast<long long>(rp.steps),
              static_cast<long long>(rs.steps));
}

// The default: on in equilibrium stages, off in duration and steps stages and in a collapse
// search; a duration stage after a scaled one runs with the true masses again.
TEST(DensityScaling, DurationStageDoesNotScale) {
  Stage settle = tight_settle(false);
  settle.density_scaling.reset();
  settle.unbalanced_tolerance = 1e-4;
  settle.kinetic_tolerance = 1e-8;
  EXPECT_TRUE(settle.scales_density());
  Stage dynamic;
  dynamic.name = "dynamic";
  dynamic.kind = Stage::Kind::duration;
  dynamic.duration = 1e-3;
  EXPECT_FALSE(dynamic.scales_density());
  Stage steps;
  steps.kind = Stage::Kind::steps;
  steps.steps = 10;
  EXPECT_FALSE(steps.scales_density());
  Stage search = settle;
  search.find_collapse = true;
  EXPECT_FALSE(search.scales_density());

  World w = column();
  ASSERT_TRUE(run_stage(w, settle).converged);
  EXPECT_TRUE(w.density_scaled());
  run_stage(w, dynamic);
  EXPECT_FALSE(w.density_scaled());
  for (const Block& b : w.blocks()) {
    EXPECT_EQ(b.mass_scale, 1.0) << b.name;
    EXPECT_EQ(b.inertia_scale, 1.0) << b.name;
  }
  // Asked for explicitly, a duration stage refuses it.
  dynamic.density_scaling = true;
  EXPECT_THROW(dynamic.validate(), std::invalid_argument);
}

// Five 0.2 m cubes and one 0.2 x 0.2 x 0.002 m plate on a fixed base: the plate sets the step.
// A cube's own step is the rotational one, sqrt(I/K_r) with I = ρa⁵/6, K_r = k a² (3a²/4 + a²/12):
// sqrt(ρ a / (5 k)).
TEST(TimeStepReport, NamesTheSliver) {
  World w = linear_world(kNormal, 1e9, 40.0);
  w.add_block(box_block({3.0, 1.0, 0.1}, {0, 0, -0.05}, kDensity, Motion::fixed, "base"));
  for (int i = 0; i < 5; ++i)
    w.add_block(box_block({0.2, 0.2, 0.2}, {-1.2 + 0.4 * i, 0, 0.1}, kDensity, Motion::free,
                          "cube_" + std::to_string(i)));
  w.add_block(box_block({0.2, 0.2, 0.002}, {0.9, 0, 0.001}, kDensity, Motion::free, "sliver"));
  const TimeStepReport r = time_step_report(w);
  EXPECT_EQ(r.name, "sliver");
  EXPECT_EQ(r.block, 6);
  EXPECT_EQ(r.free_blocks, 6u);
  EXPECT_NEAR(r.volume, 0.2 * 0.2 * 0.002, 1e-15);
  EXPECT_NEAR(r.aspect_ratio, 100.0, 1e-9);
  EXPECT_NEAR(r.median_step, std::sqrt(kDensity * 0.2 / (5.0 * kNormal)), 1e-12 * r.median_step);
  EXPECT_TRUE(r.outlier);
  EXPECT_NEAR(r.time_step, w.settings().safety_factor * r.critical_step, 1e-20);
  // Unscaled, the world's first step is the sliver's.
  EXPECT_NEAR(w.next_time_step(), r.time_step, 1e-12 * r.time_step);
  EXPECT_NE(describe(r).find("'sliver'"), std::string::npos);
  EXPECT_NE(outlier_warning(r).find("min_block_volume"), std::string::npos);
  // Scaled, the step follows the median cube's.
  w.set_density_scaling(true);
  EXPECT_NEAR(w.next_time_step(), w.settings().safety_factor * r.median_step,
              1e-12 * r.median_step);
  // Without the sliver, no block is an outlier.
  w.remove_blocks({6});
  EXPECT_FALSE(time_step_report(w).outlier);
}

// The same scene through `blockdem run`: its first lines name the sliver and warn (the warning
// also with --quiet).
TEST(TimeStepReport, RunNamesTheSliverOnStderr) {
  std::ostringstream toml;
  toml << "title = \"cubes and a sliver\"\n[settings]\ndamping = 0.7\n"
       << "[[materials]]\nname = \"rock\"\ndensity = 2500\n"
       << "[[joint_laws]]\nname = \"j\"\nnormal = { law = \"linear\", stiffness = 1e10 }\n"
       << "shear = { law = \"linear\", stiffness = 1e9, friction_deg = 40 }\n"
       << "[[blocks]]\nname = \"base\"\nmaterial = \"rock\"\nsize = [3, 1, 0.1]\n"
       << "position = [0, 0, -0.05]\nmotion = \"fixed\"\n";
  for (int i = 0; i < 5; ++i)
    toml << "[[blocks]]\nname = \"cube_" << i << "\"\nmaterial = \"rock\"\nsize = [0.2, 0.2, 0.2]\n"
         << "position = [" << -1.2 + 0.4 * i << ", 0, 0.1]\n";
  toml << "[[blocks]]\nname = \"sliver\"\nmaterial = \"rock\"\nsize = [0.2, 0.2, 0.002]\n"
       << "position = [0.9, 0, 0.001]\n"
       << "[[stages]]\nname = \"settle\"\ngravity = [0, 0, -9.81]\n";
  const auto dir = test::temp_path("time_step_report_cli");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto file = dir / "sliver.toml";
  std::ofstream(file) << toml.str();
  for (const bool quiet : {false, true}) {
    const auto err = dir / "err.txt";
    const std::string cmd = std::string(BLOCKDEM_CLI_PATH) + " run " + file.string() + " --out " +
                            (dir / "out").string() + " --no-figures --max-steps 10" +
                            (quiet ? " --quiet" : "") + " 2>" + err.string();
    const int status = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    std::ifstream in(err);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text.find("blockdem: time step set by block 'sliver' (#6: 8e-05 m3, aspect ratio "
                        "100)") != std::string::npos,
              !quiet)
        << text;
    EXPECT_NE(text.find("blockdem: warning: block 'sliver' (8e-05 m3, aspect ratio 100) allows"),
              std::string::npos)
        << text;
  }
}

// A 0.1 m block and a 4 mm sliver of the same plan side by side on an incline (psi 30, phi 40,
// each alone: F = tan 40 / tan 30 = 1.453): the factor with scaling (the default) lies in the
// bracket of the unscaled search.
TEST(DensityScaling, StrengthReductionKeepsTheBracket) {
  const auto scenario = [](bool scaling) {
    std::string text = test::incline_scenario(30.0, 40.0, 0.1, 0.02, "");
    const std::string blocks =
        "[[blocks]]\nname = \"sliver\"\nmaterial = \"rock\"\nsize = [0.1, 0.1, 0.004]\n"
        "position = [0.3, 0.0, 0.002]\n"
        "[[blocks]]\nname = \"other\"\nmaterial = \"rock\"\nsize = [0.1, 0.1, 0.02]\n"
        "position = [-0.3, 0.0, 0.01]\n";
    text.insert(text.find("[[stages]]"), blocks);
    text +=
        "[[stages]]\nname = \"srm\"\nkind = \"strength_reduction\"\n"
        "factor_bounds = [0.8, 3.0]\ntolerance = 0.01\nmax_steps = 60000\n"
        "density_scaling = " +
        std::string(scaling ? "true" : "false") + "\n";
    return text;
  };
  const RunResult plain = test::run_text(scenario(false), "density_srm_plain");
  const RunResult scaled = test::run_text(scenario(true), "density_srm_scaled");
  ASSERT_EQ(plain.status, RunStatus::completed) << plain.message;
  ASSERT_EQ(scaled.status, RunStatus::completed) << scaled.message;
  EXPECT_EQ(scaled.summary["time_step"]["block"], "sliver");
  const auto& p = plain.summary["factor_of_safety"];
  EXPECT_GE(*scaled.factor_of_safety, p["last_stable"].get<double>());
  EXPECT_LE(*scaled.factor_of_safety, p["first_failed"].get<double>());
  std::printf("planar with a sliver: F = %.4f unscaled, %.4f scaled; steps %lld, %lld\n",
              *plain.factor_of_safety, *scaled.factor_of_safety,
              static_cast<long long>(plain.steps), static_cast<long long>(scaled.steps));
}

}  // namespace blockdem::density_scaling_test
