// Shear force and twisting moment together in face contacts (mode face_integrated): a cube on a
// base pushed and turned at once slides about the instantaneous centre of its motion with the
// force and moment of Coulomb's law at every point of the joint; a push without a turn gives the
// same forces as a joint without twist.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "validation/scenes.hpp"

namespace blockdem::test {
namespace {

constexpr double kSide = 0.046;                 // cube side a (m)
constexpr double kOverlap = 1e-5;               // closure of the joint (m)
constexpr double kNormal = 10e9;                // k_n (Pa/m)
constexpr double kShear = 1e9;                  // k_s (Pa/m)
constexpr double kFriction = 40.0;              // φ (degrees)
constexpr double kDensity = 1207.0;             // (kg/m^3)
constexpr double kStress = kNormal * kOverlap;  // uniform σ_n (Pa)

double friction() {
  return std::tan(kFriction * std::numbers::pi / 180.0);
}
double force_limit() {  // μ σ_n A (N)
  return friction() * kStress * kSide * kSide;
}
double moment_limit() {  // μ σ_n ∫ r dA of the square (N m)
  return friction() * kStress * std::pow(kSide, 3) *
         (std::numbers::sqrt2 + std::log(1.0 + std::numbers::sqrt2)) / 6.0;
}

// The oracle: full slip of the uniformly pressed square about the centre p, turning with sense
// s about +z: the traction on the cube is -μ σ_n ŵ, w = s z × (y - p); force and moment about
// the square's centre c, by the midpoint rule on an 400 x 400 grid (about 1e-5 relative).
struct Resultants {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  double moment = 0.0;
};
Resultants instantaneous_centre_solution(const Eigen::Vector3d& c, const Eigen::Vector3d& p,
                                         double sense) {
  Resultants r;
  constexpr int n = 400;
  const double h = kSide / n;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const Eigen::Vector3d y =
          c + Eigen::Vector3d((i + 0.5) * h - kSide / 2, (j + 0.5) * h - kSide / 2, 0.0);
      const Eigen::Vector3d d = y - p;
      const Eigen::Vector3d w = sense * Eigen::Vector3d(-d.y(), d.x(), 0.0);
      const Eigen::Vector3d t = friction() * kStress * h * h * w / w.norm();
      r.force -= t;
      r.moment -= (y - c).x() * t.y() - (y - c).y() * t.x();
    }
  }
  return r;
}

// A cube (index 1) on a fixed base (index 0), the joint closed by kOverlap and held so (the
// cube's vertical translation and its tilts are blocked): uniform σ_n over the square.
World pressed_cube(WorldSettings s, const Eigen::Vector3d& force, double torque_z) {
  s.time_step = 2e-5;
  s.damping = 0.0;
  World w = linear_world(kNormal, kShear, kFriction, s);
  w.add_block(box_block({0.2, 0.2, 0.05}, {0, 0, -0.025}, kDensity, Motion::fixed, "base"));
  Block cube = box_block(Eigen::Vector3d::Constant(kSide), {0, 0, kSide / 2 - kOverlap}, kDensity);
  cube.blocked_translation = {false, false, true};
  cube.blocked_rotation = {true, true, false};
  cube.set_external_force(force);
  cube.set_external_torque(Eigen::Vector3d(0, 0, torque_z));
  w.add_block(cube);
  return w;
}

// Pushed with 0.8 μ F_n and turned with 0.8 of the twist limit: each alone would be carried, but
// not both (the separate caps would hold the cube still). The cube slides and turns; while the
// slip is under way (steps 300 to 900, the cube still well on the base), the joint's force and
// moment on the cube are the instantaneous-centre solution for the cube's own motion (centre
// p = x_p + n × v / ω from the velocity v at the force point and the spin ω). Reference:
// Coulomb's law at every point, integrated on a fine grid; the mean over every tenth step within
// 2% of μ F_n and of μ σ_n ∫ r dA (a single step scatters by about 2%: the velocities are at
// half steps and the joint alternates between sliding and sticking steps).
TEST(ShearTwistInWorld, CombinedSlipIsTheInstantaneousCentreSolution) {
  World w = pressed_cube(WorldSettings{}, Eigen::Vector3d(0.8 * force_limit(), 0, 0),
                         0.8 * moment_limit());
  Eigen::Vector3d force_error = Eigen::Vector3d::Zero();
  double moment_error = 0.0, largest_force = 0.0, largest_moment = 0.0;
  int samples = 0;
  for (int k = 0; k <= 900; ++k) {
    w.step();
    if (k < 300 || k % 10 != 0) continue;
    ASSERT_EQ(w.contact_count(), 1u);
    const Contact& c = *w.contacts()[0];
    const Block& cube = w.blocks()[1];
    ASSERT_TRUE(c.integrated);
    const Eigen::Vector3d& n = c.geometry.normal;
    const Eigen::Vector3d v = cube.point_velocity(c.force_point());
    const double omega = cube.angular_velocity.dot(n);
    ASSERT_GT(v.norm(), 1e-3) << "the cube slides";
    ASSERT_GT(omega, 1e-2) << "and turns";
    const Eigen::Vector3d p = c.force_point() + n.cross(v) / omega;
    const Resultants o = instantaneous_centre_solution(c.force_point(), p, 1.0);
    force_error += c.shear.force - o.force;
    moment_error += c.twist.moment - o.moment;
    largest_force = std::max(largest_force, c.shear.force.norm());
    largest_moment = std::max(largest_moment, std::abs(c.twist.moment));
    ++samples;
  }
  EXPECT_LT(force_error.norm() / samples, 0.02 * force_limit());
  EXPECT_LT(std::abs(moment_error) / samples, 0.02 * moment_limit());
  // Inside both separate limits, so the separate caps alone would not have let it slip.
  EXPECT_LT(largest_force, 0.8 * force_limit());
  EXPECT_LT(largest_moment, 0.8 * moment_limit());
}

// A push without a turn, past slip and below it, on a cube free to tilt under gravity (so the
// pressure is not uniform and the joint partly slips pointwise): the shear force, force point
// and the cube's motion with twist on equal those with twist off, to 1e-9; no moment arises.
TEST(ShearTwistInWorld, ShearWithoutTwistIsUnchanged) {
  for (const double push : {0.5, 1.5}) {
    std::vector<World> worlds;
    for (const bool twist : {false, true}) {
      WorldSettings s;
      s.time_step = 2e-5;
      s.twist = twist;
      s.gravity = Eigen::Vector3d(0, 0, -9.81);
      World w = linear_world(kNormal, kShear, kFriction, s);
      w.add_block(box_block({0.2, 0.2, 0.05}, {0, 0, -0.025}, kDensity, Motion::fixed, "base"));
      Block cube = box_block(Eigen::Vector3d::Constant(kSide), {0, 0, kSide / 2 - 1e-8}, kDensity);
      const double weight = cube.mass * 9.81;
      cube.set_external_force(Eigen::Vector3d(push * friction() * weight, 0.0, 0.0));
      w.add_block(cube);
      for (int k = 0; k < 2000; ++k) w.step();
      worlds.push_back(std::move(w));
    }
    ASSERT_EQ(worlds[0].contact_count(), 1u);
    ASSERT_EQ(worlds[1].contact_count(), 1u);
    const Contact& off = *worlds[0].contacts()[0];
    const Contact& on = *worlds[1].contacts()[0];
    const double scale = off.shear.force.norm();
    ASSERT_GT(scale, 0.0);
    EXPECT_LT((on.shear.force - off.shear.force).norm(), 1e-9 * scale) << push;
    EXPECT_LT((on.force_point() - off.force_point()).norm(), 1e-9 * kSide) << push;
    EXPECT_NEAR(on.normal_force, off.normal_force, 1e-9 * off.normal_force) << push;
    const Block& b_off = worlds[0].blocks()[1];
    const Block& b_on = worlds[1].blocks()[1];
    EXPECT_LT((b_on.position - b_off.position).norm(), 1e-9 * kSide) << push;
    EXPECT_LT(std::abs(on.twist.moment), 1e-9 * moment_limit()) << push;
  }
}

}  // namespace
}  // namespace blockdem::test
