// A dynamic stage's moving base against closed forms.
//
// Newmark (1965), "Effects of earthquakes on dams and embankments", Geotechnique 15(2), 139-160:
// a rigid block on a horizontal base with friction coefficient mu, the base given a rectangular
// acceleration pulse a0 > mu g for t0 seconds. While the block slips, friction accelerates it at
// mu g, so the relative acceleration is a0 - mu g during the pulse and -mu g after it: the
// relative velocity peaks at (a0 - mu g) t0 and returns to zero at t_s = t0 a0 / (mu g), after a
// total slip of (a0 - mu g) t0^2 / 2 * a0 / (mu g). Tolerance 1% on both (the joint's elastic
// shear stretch, mu m g / K_s, is below 1e-5 of the slip; the time step is below 1e-3 of t_s).
// Below the yield acceleration (a0 < mu g) the block moves with the base: the relative
// displacement is the elastic stretch, below 1e-6 m.
//
// The base follows a piecewise-linear record exactly: its displacement at the stage end equals
// u(T) = ∫_0^T (T - s) a(s) ds (Simpson's rule per segment, exact for the quadratic integrand)
// to 1e-9 relative.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "blockdem/dynamics/base_motion.hpp"
#include "blockdem/numerics/units.hpp"
#include "blockdem/run/scene_builders.hpp"
#include "blockdem/scenario/scenario.hpp"
#include "blockdem/world/stage.hpp"
#include "support/cli_runner.hpp"
#include "support/input_error.hpp"
#include "support/temp_path.hpp"

namespace blockdem::test::base_motion_validation {
namespace {

namespace fs = std::filesystem;
constexpr double kG = 9.81;
constexpr double kFrictionDeg = 30.0;

// A 0.4 x 0.4 x 0.2 m block resting on a fixed 3 x 1 x 0.1 m base plate (group "base"),
// settled under gravity, then `stage`.
std::string sliding_block(const std::string& mode, const std::string& stage) {
  std::ostringstream s;
  s << "[settings]\ndamping = 0.7\ncontact_mode = \"" << mode << "\"\n"
    << "[[materials]]\nname = \"rock\"\ndensity = 2500.0\n"
    << "[[joint_laws]]\nname = \"joint\"\nnormal = { law = \"linear\", stiffness = 1e10 }\n"
    << "shear = { law = \"linear\", stiffness = 1e10, friction_deg = " << kFrictionDeg << " }\n"
    << "[[blocks]]\nname = \"plate\"\ngroup = \"base\"\nmaterial = \"rock\"\n"
    << "size = [3.0, 1.0, 0.1]\nposition = [0.0, 0.0, -0.05]\nmotion = \"fixed\"\n"
    << "[[blocks]]\nname = \"block\"\nmaterial = \"rock\"\nsize = [0.4, 0.4, 0.2]\n"
    << "position = [0.0, 0.0, 0.1]\n"
    << "[[stages]]\nname = \"settle\"\ngravity = [0.0, 0.0, " << -kG << "]\n"
    << stage;
  return s.str();
}

std::string rectangular_stage(double a0, double t0, double duration) {
  std::ostringstream s;
  s.precision(17);
  s << "[[stages]]\nname = \"shake\"\nkind = \"dynamic\"\nduration = " << duration << "\n"
    << "base_motion = { group = \"base\", pulse = \"rectangular\", amplitude_m_s2 = " << a0
    << ", duration = " << t0 << ", direction = [1, 0, 0] }\n";
  return s.str();
}

// The dynamic stage's record of one material point of the block, the centre of its bottom face
// (on the joint: the block's rocking on its joint springs moves the centroid but hardly that
// point): its displacement relative to the base along a direction, its extreme, and when its
// relative velocity came back to zero after the slip.
struct Shaken {
  double relative_slip = 0.0;     ///< (m), at the stage end
  double largest_relative = 0.0;  ///< max |relative displacement| over the stage (m)
  double stop_time = -1.0;        ///< stage time at which v_rel returned to 0 (s); -1: never
  double stage_time = 0.0;
  Eigen::Vector3d base_shift = Eigen::Vector3d::Zero();
};

/// `foot`: from the block's centroid to the centre of its bottom face at the dynamic stage's
/// start (world frame, m).
Shaken run_scenario_stages(const Scenario& sc, const std::string& base_block,
                           const Eigen::Vector3d& along, const Eigen::Vector3d& foot) {
  World world = build_world(sc);
  const int block = world.find_block("block"), plate = world.find_block(base_block);
  Shaken out;
  Eigen::Vector3d foot0 = Eigen::Vector3d::Zero(), plate0 = Eigen::Vector3d::Zero();
  Eigen::Vector3d foot_body = Eigen::Vector3d::Zero();  // the point in the block's body frame
  double t0 = 0.0;
  double v_prev = 0.0, t_prev = 0.0;
  bool slipping = false;
  const auto relative = [&](const World& w) {
    const Block& b = w.blocks()[static_cast<std::size_t>(block)];
    const Block& p = w.blocks()[static_cast<std::size_t>(plate)];
    return ((b.to_world(foot_body) - foot0) - (p.position - plate0)).dot(along);
  };
  const StepFn on_step = [&](const World& w, const Stage& st, std::int64_t) {
    if (st.kind != Stage::Kind::dynamic) return;
    const Block& b = w.blocks()[static_cast<std::size_t>(block)];
    const Block& p = w.blocks()[static_cast<std::size_t>(plate)];
    out.largest_relative = std::max(out.largest_relative, std::abs(relative(w)));
    // Velocities at t_{n+1/2}: the step's mid time.
    const double v = (b.point_velocity(b.to_world(foot_body)) - p.velocity).dot(along);
    const double t = w.time() - 0.5 * w.last_time_step() - t0;
    if (v < -1e-3) slipping = true;
    if (slipping && out.stop_time < 0.0 && v >= 0.0)
      out.stop_time = t_prev + (t - t_prev) * (-v_prev) / (v - v_prev);
    v_prev = v;
    t_prev = t;
  };
  for (const Stage& st : sc.stages) {
    if (st.kind == Stage::Kind::dynamic) {
      const Block& b = world.blocks()[static_cast<std::size_t>(block)];
      foot0 = b.position + foot;
      foot_body = b.orientation.conjugate() * foot;
      plate0 = world.blocks()[static_cast<std::size_t>(plate)].position;
      t0 = world.time();
    }
    const StageResult r = run_stage(world, st, {}, nullptr, {}, nullptr, on_step);
    EXPECT_TRUE(r.converged) << st.name << ": " << r.message;
  }
  const Block& p = world.blocks()[static_cast<std::size_t>(plate)];
  out.relative_slip = relative(world);
  out.base_shift = p.position - plate0;
  out.stage_time = world.time() - t0;
  // After the stage the base is fixed again where the motion left it.
  EXPECT_EQ(p.motion, Motion::fixed);
  EXPECT_EQ(p.velocity, Eigen::Vector3d::Zero());
  // The damping before the stage is back.
  EXPECT_EQ(world.settings().damping, 0.7);
  return out;
}

Shaken run_shaken(const std::string& text, const std::string& file) {
  return run_scenario_stages(parse_scenario(text, file), "plate", Eigen::Vector3d::UnitX(),
                             Eigen::Vector3d(0.0, 0.0, -0.1));
}

class NewmarkPulse : public ::testing::TestWithParam<const char*> {};

TEST_P(NewmarkPulse, SlipAndStopTimeMatchNewmark) {
  const double mu = std::tan(deg_to_rad(kFrictionDeg));
  const double a0 = 2.0 * mu * kG, t0 = 0.1;
  const double stop = t0 * a0 / (mu * kG);
  const double slip = (a0 - mu * kG) * t0 * t0 / 2.0 * a0 / (mu * kG);
  const Shaken s =
      run_shaken(sliding_block(GetParam(), rectangular_stage(a0, t0, 1.5 * stop)), "newmark.toml");
  // The block lags behind the base: its slip relative to the base is along -x.
  std::printf("[newmark %s] slip %.6g m (closed form %.6g), stop %.6g s (closed form %.6g)\n",
              GetParam(), -s.relative_slip, slip, s.stop_time, stop);
  EXPECT_NEAR(-s.relative_slip, slip, 0.01 * slip);
  EXPECT_NEAR(s.stop_time, stop, 0.01 * stop);
}

TEST_P(NewmarkPulse, BelowTheYieldAccelerationTheBlockMovesWithTheBase) {
  const double mu = std::tan(deg_to_rad(kFrictionDeg));
  const double a0 = 0.4 * mu * kG, t0 = 0.1;
  const Shaken s =
      run_shaken(sliding_block(GetParam(), rectangular_stage(a0, t0, 0.2)), "no_slip.toml");
  std::printf("[no slip %s] largest relative displacement %.3g m, base moved %.6g m\n", GetParam(),
              s.largest_relative, s.base_shift.x());
  EXPECT_LT(s.largest_relative, 1e-6);
  // The base moved as the pulse says: a0 t0^2 / 2 + a0 t0 (T - t0).
  const double T = s.stage_time;
  EXPECT_NEAR(s.base_shift.x(), 0.5 * a0 * t0 * t0 + a0 * t0 * (T - t0), 1e-12);
  EXPECT_EQ(s.base_shift.y(), 0.0);
  EXPECT_EQ(s.base_shift.z(), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Modes, NewmarkPulse, ::testing::Values("boon2012", "face_integrated"));

TEST(BaseMotionRecord, BaseFollowsTheRecordExactly) {
  const fs::path dir = temp_path("base_motion_record");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::vector<double> t = {0.0, 0.013, 0.037, 0.05, 0.081, 0.1};
  const std::vector<Eigen::Vector3d> a = {
      Eigen::Vector3d(0.0, 0.0, 0.0),  Eigen::Vector3d(2.0, -1.0, 0.3),
      Eigen::Vector3d(-1.5, 0.5, 0.0), Eigen::Vector3d(3.0, 0.0, -0.2),
      Eigen::Vector3d(-0.5, 1.0, 0.1), Eigen::Vector3d(0.7, 0.0, 0.0)};
  {
    std::ofstream csv(dir / "accel.csv");
    csv.precision(17);
    csv << "# a synthetic record\ntime_s,ax_m_s2,ay_m_s2,az_m_s2\n";
    for (std::size_t i = 0; i < t.size(); ++i)
      csv << t[i] << "," << a[i].x() << "," << a[i].y() << "," << a[i].z() << "\n";
  }
  const std::string stage =
      "[[stages]]\nname = \"shake\"\nkind = \"dynamic\"\nduration = 0.123\n"
      "base_motion = { group = \"base\", file = \"accel.csv\" }\n";
  const Shaken s =
      run_shaken(sliding_block("face_integrated", stage), (dir / "case.toml").string());
  // The oracle: u(T) = ∫_0^T (T - s) a(s) ds, Simpson per segment; after the record the base
  // keeps its final velocity, so the integrand's last part is exact the same way (a = 0).
  const double T = s.stage_time;
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i + 1 < t.size(); ++i) {
    const double h = t[i + 1] - t[i], mid = 0.5 * (t[i] + t[i + 1]);
    u +=
        h / 6.0 *
        ((T - t[i]) * a[i] + 4.0 * (T - mid) * 0.5 * (a[i] + a[i + 1]) + (T - t[i + 1]) * a[i + 1]);
  }
  std::printf(
      "[record] T = %.9g s: base moved (%.12g, %.12g, %.12g), closed form (%.12g, %.12g, "
      "%.12g)\n",
      T, s.base_shift.x(), s.base_shift.y(), s.base_shift.z(), u.x(), u.y(), u.z());
  EXPECT_LE((s.base_shift - u).norm(), 1e-9 * u.norm());
}

// The example scenarios/examples/slope_shaken.toml: a block on a plane dipping psi = 20 degrees
// towards +x, friction phi = 30 degrees, the plane shaken horizontally along x by a record.
// Newmark's rigid block on an incline under horizontal base acceleration: in the plane's frame the
// block feels gravity and the inertial force -m a_b. With a_u = -a_x the base's acceleration up the
// slope (horizontal), the normal force is m (g cos psi - a_u sin psi) and the downslope driving
// force m (g sin psi + a_u cos psi), so the block slides down the plane when
//   a_u > a_y = g (tan phi cos psi - sin psi) / (cos psi + tan phi sin psi) = g tan(phi - psi),
// and while it slides its acceleration relative to the plane, along the slope, is
//   s'' = (cos psi + tan phi sin psi) (a_u - a_y) = cos(phi - psi) / cos(phi) (a_u - a_y),
// until its relative velocity s' returns to zero (it cannot slide up the slope: that needs
// a_u < -g tan(phi + psi), far beyond the record). (Newmark 1965 for the rigid block; the
// inclined, horizontally shaken form as in Kramer, Geotechnical Earthquake Engineering, 1996,
// section 10.6.1.) The oracle integrates s'' with a 1e-5 s step (midpoint accelerations).
// Tolerance 3% on the permanent slip: the block is elastic on its joint (it rocks on the plane's
// shear and normal springs), and it slides in a few excursions each of which starts and stops on
// a spring.
double newmark_incline_slip(const BaseMotion& record, double psi, double phi, double T) {
  const double g = kG;
  const double a_y = g * std::tan(phi - psi);
  const double k = std::cos(phi - psi) / std::cos(phi);
  const double h = 1e-5;
  double s = 0.0, v = 0.0;
  for (double t = 0.0; t < T; t += h) {
    const double a_u = -record.at(t + 0.5 * h).acceleration.x();
    if (v > 0.0 || a_u > a_y) {
      const double v_new = std::max(0.0, v + h * k * (a_u - a_y));
      s += 0.5 * h * (v + v_new);
      v = v_new;
    }
  }
  return s;
}

TEST(SlopeShaken, PermanentDisplacementMatchesNewmark) {
  const std::string file =
      std::string(BLOCKDEM_SOURCE_DIR) + "/scenarios/examples/slope_shaken.toml";
  const Scenario sc = load_scenario(file);
  const double psi = deg_to_rad(20.0), phi = deg_to_rad(30.0);
  const Eigen::Vector3d down(std::cos(psi), 0.0, -std::sin(psi));
  // The bottom face's centre: 0.05 m (half the block's thickness) below the centroid, normal to
  // the plane.
  const Eigen::Vector3d normal(std::sin(psi), 0.0, std::cos(psi));
  const Shaken s = run_scenario_stages(sc, "plane", down, -0.05 * normal);
  const Stage& shake = sc.stages.back();
  const double newmark = newmark_incline_slip(*shake.base_motion, psi, phi, s.stage_time);
  std::printf(
      "[slope_shaken] permanent slip down the plane %.6g m, Newmark %.6g m (a_y = %.4g "
      "m/s^2)\n",
      s.relative_slip, newmark, kG * std::tan(phi - psi));
  EXPECT_GT(newmark, 0.01);
  EXPECT_NEAR(s.relative_slip, newmark, 0.03 * newmark);
}

// Bad input to `blockdem run`: exit 2, a message naming the file, the key and the reason,
// nothing written.
struct BadCase {
  const char* name;
  const char* csv;    ///< the record, or "" for none
  const char* stage;  ///< the dynamic stage's base_motion
  std::vector<std::string> fragments;
};

class BaseMotionInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(BaseMotionInput, IsRefusedWithExitTwoAndNothingWritten) {
  const BadCase& c = GetParam();
  const fs::path dir = fresh_case_dir("base_motion_input", c.name);
  if (std::string(c.csv).size() > 0) std::ofstream(dir / "accel.csv") << c.csv;
  const fs::path file = dir / "case.toml";
  std::ofstream(file) << sliding_block("boon2012", std::string("[[stages]]\nname = \"shake\"\n"
                                                               "kind = \"dynamic\"\n") +
                                                       c.stage + "\n");
  const fs::path out = dir / "out";
  const CommandOutput r =
      run_cli("run '" + file.string() + "' --out '" + out.string() + "' --quiet --no-figures");
  std::vector<std::string> fragments = c.fragments;
  fragments.push_back(file.string());
  expect_input_error(r, out, fragments);
}

INSTANTIATE_TEST_SUITE_P(
    Catalogue, BaseMotionInput,
    ::testing::Values(
        BadCase{"non_monotonic",
                "time_s,ax_m_s2,ay_m_s2,az_m_s2\n0,0,0,0\n0.2,1,0,0\n0.1,0,0,0\n",
                "base_motion = { group = \"base\", file = \"accel.csv\" }",
                {"stages[2].base_motion.file", "accel.csv:4", "increase"}},
        BadCase{"non_finite",
                "time_s,ax_m_s2,ay_m_s2,az_m_s2\n0,0,0,0\n0.1,nan,0,0\n0.2,0,0,0\n",
                "base_motion = { group = \"base\", file = \"accel.csv\" }",
                {"stages[2].base_motion.file", "accel.csv:3", "ax_m_s2", "finite"}},
        BadCase{"zero_duration_pulse",
                "",
                "base_motion = { group = \"base\", pulse = \"rectangular\", amplitude_m_s2 = 1.0, "
                "duration = 0.0 }",
                {"stages[2].base_motion.duration", "> 0"}},
        BadCase{"no_such_group",
                "",
                "base_motion = { group = \"ground\", pulse = \"sine\", amplitude_m_s2 = 1.0, "
                "period = 0.5 }",
                {"stages[2].base_motion.group", "\"ground\""}},
        BadCase{"density_scaling",
                "",
                "density_scaling = true\nbase_motion = { group = \"base\", pulse = \"ricker\", "
                "amplitude_m_s2 = 1.0, frequency = 5 }",
                {"stages[2].density_scaling", "dynamic"}}),
    [](const ::testing::TestParamInfo<BadCase>& i) { return std::string(i.param.name); });

}  // namespace
}  // namespace blockdem::test::base_motion_validation

namespace blockdem::test::base_motion_restart {
namespace {

namespace fs = std::filesystem;

std::string file_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A dynamic stage continued from a checkpoint taken inside it ends with the same time_history.csv
// (bytes) and the same summary.json stages as the run never stopped: the base's motion is a
// function of the stage time and of the base's position before each step, both in the checkpoint.
TEST(BaseMotionRestart, ContinuingInsideTheDynamicStageIsBitIdentical) {
  const fs::path dir = fresh_case_dir("base_motion_restart", "case");
  const fs::path file = dir / "case.toml";
  std::ofstream(file)
      << "[settings]\ndamping = 0.7\n[[materials]]\nname = \"rock\"\ndensity = 2500.0\n"
      << "[[joint_laws]]\nname = \"joint\"\nnormal = { law = \"linear\", stiffness = 1e10 }\n"
      << "shear = { law = \"linear\", stiffness = 1e10, friction_deg = 30 }\n"
      << "[[blocks]]\nname = \"plate\"\ngroup = \"base\"\nmaterial = \"rock\"\n"
      << "size = [3.0, 1.0, 0.1]\nposition = [0.0, 0.0, -0.05]\nmotion = \"fixed\"\n"
      << "[[blocks]]\nname = \"block\"\nmaterial = \"rock\"\nsize = [0.4, 0.4, 0.2]\n"
      << "position = [0.0, 0.0, 0.1]\n"
      << "[output]\nhistory_interval = 7\nhistory_blocks = [\"block\", \"plate\"]\n"
      << "[[stages]]\nname = \"settle\"\ngravity = [0.0, 0.0, -9.81]\n"
      << "[[stages]]\nname = \"shake\"\nkind = \"dynamic\"\nduration = 0.15\n"
      << "base_motion = { group = \"base\", pulse = \"sine\", amplitude_m_s2 = 6.0, period = 0.1 "
         "}\n"
      << "[[stages]]\nname = \"rest\"\nmax_steps = 300\n";
  const fs::path reference = dir / "reference";
  const auto run = [&](const fs::path& out, const std::string& extra) {
    return run_cli("run '" + file.string() + "' --out '" + out.string() +
                   "' --quiet --no-figures --threads 1 " + extra);
  };
  const CommandOutput r = run(reference, "");
  ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 3) << r.err;
  const auto summary = nlohmann::json::parse(file_bytes(reference / "summary.json"));
  const auto& stages = summary["stages"];
  ASSERT_EQ(stages.size(), 3u);
  const std::int64_t settle = stages[0]["steps"], shake = stages[1]["steps"];
  std::printf("[restart] settle %lld steps, shake %lld steps\n", static_cast<long long>(settle),
              static_cast<long long>(shake));
  ASSERT_GT(shake, 20);
  // Stopped (SIGTERM: a checkpoint, exit 143) half way through the shake stage, then resumed.
  const fs::path out = dir / "continued";
  const std::string at = std::to_string(settle + shake / 2);
  ::setenv("BLOCKDEM_TEST_KILL_RANK", ("0:" + at + ":TERM").c_str(), 1);
  const CommandOutput stopped = run(out, "");
  ::unsetenv("BLOCKDEM_TEST_KILL_RANK");
  ASSERT_EQ(stopped.exit_code, 143) << stopped.err;
  const CommandOutput c = run(out, "--resume");
  EXPECT_EQ(c.exit_code, r.exit_code) << c.err;
  EXPECT_EQ(file_bytes(reference / "time_history.csv"), file_bytes(out / "time_history.csv"));
  const auto continued = nlohmann::json::parse(file_bytes(out / "summary.json"));
  EXPECT_EQ(summary["stages"].dump(), continued["stages"].dump());
  // The base columns are there and the permanent displacements are reported.
  EXPECT_NE(file_bytes(reference / "time_history.csv").find("base_ax_m_s2"), std::string::npos);
  EXPECT_TRUE(stages[1].contains("permanent_displacements"));
}

}  // namespace
}  // namespace blockdem::test::base_motion_restart
