// Twisting resistance of face contacts in the world's step: a cube pressed on a base and turned
// about the contact normal. Closed forms of the torsional spring (elastic moment k_s J θ, full-slip
// moment μ σ_n ∫ r dA), torque balance, energy over undamped cycles, objectivity, and shear
// without twist unchanged.
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

// Square of side a about its centre: J = a⁴/6, ∫ r dA = a³ (√2 + ln(1 + √2))/6.
double square_polar_moment() {
  return std::pow(kSide, 4) / 6.0;
}
double square_radial_moment() {
  return std::pow(kSide, 3) * (std::numbers::sqrt2 + std::log(1.0 + std::numbers::sqrt2)) / 6.0;
}
double friction() {
  return std::tan(kFriction * std::numbers::pi / 180.0);
}
// The full-slip moment μ σ_n ∫ r dA (N m).
double slip_moment() {
  return friction() * kStress * square_radial_moment();
}

// A cube (index 1) on a fixed base (index 0), the joint closed by kOverlap. `turn_only` holds
// the cube's translations and its rotations about x and y, so that it can only turn about the
// contact normal z.
World twisted_cube(WorldSettings s, bool turn_only, double torque_z, double damping) {
  s.damping = damping;
  World w = linear_world(kNormal, kShear, kFriction, s);
  w.add_block(box_block({0.2, 0.2, 0.05}, {0, 0, -0.025}, kDensity, Motion::fixed, "base"));
  Block cube = box_block(Eigen::Vector3d::Constant(kSide), {0, 0, kSide / 2 - kOverlap}, kDensity);
  if (turn_only) {
    cube.blocked_translation = {true, true, true};
    cube.blocked_rotation = {true, true, false};
  }
  cube.set_external_torque(Eigen::Vector3d(0, 0, torque_z));
  w.add_block(cube);
  return w;
}

double turn_of(const World& w) {
  return w.blocks()[1].rotation_since_start().z();
}

// Elastic: under a torque T below the slip moment the cube comes to rest at θ = T/(k_s J).
// Reference: the closed form with J = a⁴/6 (issue: within 1%).
void expect_elastic_turn(WorldSettings s) {
  const double torque = 0.5 * slip_moment();
  World w = twisted_cube(s, true, torque, 0.7);
  for (int k = 0; k < 3000; ++k) w.step();
  ASSERT_EQ(w.contact_count(), 1u);
  const double expected = torque / (kShear * square_polar_moment());
  EXPECT_NEAR(turn_of(w), expected, 0.01 * expected);
  // The joint's moment on the cube balances the applied torque (the cube is at rest), and is
  // k_s J θ against the turn.
  const double moment = w.contacts()[0]->twist.moment;
  EXPECT_NEAR(moment, -torque, 0.01 * torque);
  EXPECT_NEAR(moment, -kShear * square_polar_moment() * turn_of(w), 0.01 * torque);
}

TEST(TwistInWorld, ElasticMomentIsShearStiffnessTimesPolarMomentTimesTurn) {
  WorldSettings s;
  s.time_step = 2e-5;
  expect_elastic_turn(s);  // face_integrated: twist on by default
}

TEST(TwistInWorld, PointContactTwistIsOptInWithTheSameClosedForm) {
  WorldSettings s;
  s.time_step = 2e-5;
  s.contact_mode = ContactMode::boon2012;
  EXPECT_FALSE(s.twist_enabled()) << "off in the paper's mode unless asked for";
  s.twist = true;
  expect_elastic_turn(s);

  // Off: the same torque turns the cube without resistance (it does not come to rest).
  s.twist = false;
  World w = twisted_cube(s, true, 0.5 * slip_moment(), 0.7);
  for (int k = 0; k < 3000; ++k) w.step();
  EXPECT_EQ(w.contacts()[0]->twist.moment, 0.0);
  EXPECT_GT(turn_of(w), 0.1);
}

// Full slip: a torque 1.2 times the slip moment spins the cube; the joint's moment stays at
// μ σ_n ∫ r dA of the square. Reference: closed form (issue: within 2%; the cells' ∫ σ_n r dA is
// quadrature to about 1e-4).
TEST(TwistInWorld, FullSlipMomentIsFrictionTimesStressTimesRadialMoment) {
  for (const ContactMode mode : {ContactMode::face_integrated, ContactMode::boon2012}) {
    WorldSettings s;
    s.time_step = 2e-5;
    s.contact_mode = mode;
    s.twist = true;
    World w = twisted_cube(s, true, 1.2 * slip_moment(), 0.0);
    double previous = 0.0;
    for (int k = 0; k < 600; ++k) {
      w.step();
      previous = turn_of(w);
    }
    w.step();
    ASSERT_EQ(w.contact_count(), 1u) << to_string(mode);
    const Contact& c = *w.contacts()[0];
    EXPECT_NEAR(std::abs(c.twist.moment), slip_moment(), 0.02 * slip_moment()) << to_string(mode);
    EXPECT_LT(c.twist.moment, 0.0) << "the moment on the cube resists its turn";
    EXPECT_GT(turn_of(w), previous) << "the cube keeps turning at full slip";
  }
}

// Torque balance: a free cube dropped with a spin and a tilt onto the base under gravity. At
// every step the joint's loads on the two blocks have zero resultant force and zero resultant
// moment about the origin (torques are about the centroids at the start of the step). Reference:
// Newton's third law for the pair; round-off: 1e-9 of the largest term.
TEST(TwistInWorld, LoadsOnTheTwoBlocksAreEqualAndOpposite) {
  WorldSettings s;
  s.time_step = 2e-5;
  s.gravity = Eigen::Vector3d(0, 0, -9.81);
  World w = linear_world(kNormal, kShear, kFriction, s);
  w.add_block(box_block({0.2, 0.2, 0.05}, {0, 0, -0.025}, kDensity, Motion::fixed, "base"));
  Block cube = box_block(Eigen::Vector3d::Constant(kSide), {0, 0, kSide / 2 - 1e-7}, kDensity);
  cube.angular_velocity = Eigen::Vector3d(0.02, -0.01, 4.0);
  cube.velocity = Eigen::Vector3d(0.001, 0.0, 0.0);
  cube.angular_momentum = cube.world_inertia() * cube.angular_velocity;
  w.add_block(cube);
  int checked = 0;
  for (int k = 0; k < 400; ++k) {
    const Eigen::Vector3d xa = w.blocks()[0].position, xb = w.blocks()[1].position;
    w.step();
    if (w.contact_count() != 1 || w.contacts()[0]->twist.moment == 0.0) continue;
    // The loads of this step (step() leaves them on the blocks): the base receives contact
    // loads only, the cube no external torque.
    const Block& a = w.blocks()[0];
    const Block& b = w.blocks()[1];
    const Eigen::Vector3d moment =
        a.torque + xa.cross(a.contact_force) + b.torque + xb.cross(b.contact_force);
    const double scale =
        std::max({a.torque.norm(), b.torque.norm(), xb.norm() * b.contact_force.norm()});
    EXPECT_LT((a.contact_force + b.contact_force).norm(), 1e-9 * b.contact_force.norm());
    EXPECT_LT(moment.norm(), 1e-9 * scale) << "step " << k;
    ++checked;
  }
  EXPECT_GT(checked, 100) << "the joint must carry a twisting moment";
}

// Energy: a cube started with a spin about the normal and no damping oscillates on the torsional
// spring. Over ten undamped cycles the spring creates no work: the kinetic energy never exceeds
// its start value, and the half range of the turn is ω0 sqrt(I/(k_s J)) (energy
// ½ I ω0² = ½ k_s J θ²; the spin is set after a step, so the spring's rest turn is offset by
// ω0 dt, hence the half range). Reference: conservation of energy; tolerance 1% (leapfrog at ~70
// steps a cycle).
TEST(TwistInWorld, UndampedTwistCyclesCreateNoEnergy) {
  WorldSettings s;
  s.time_step = 2e-5;
  World w = twisted_cube(s, true, 0.0, 0.0);
  for (int k = 0; k < 5; ++k) w.step();  // the contact forms at rest
  Block& cube = w.blocks()[1];
  const double omega0 = 2.0;  // rad/s: amplitude ~5e-4 rad, far below slip
  cube.angular_velocity = Eigen::Vector3d(0, 0, omega0);
  cube.angular_momentum = cube.world_inertia() * cube.angular_velocity;
  const double inertia = cube.inertia.z();
  const double start = 0.5 * inertia * omega0 * omega0;
  const double stiffness = kShear * square_polar_moment();
  const double period = 2.0 * std::numbers::pi * std::sqrt(inertia / stiffness);
  const int steps = static_cast<int>(10.0 * period / s.time_step);
  double max_kinetic = 0.0, max_turn = -1.0, min_turn = 1.0;
  for (int k = 0; k < steps; ++k) {
    w.step();
    max_kinetic = std::max(max_kinetic, w.blocks()[1].kinetic_energy());
    max_turn = std::max(max_turn, turn_of(w));
    min_turn = std::min(min_turn, turn_of(w));
  }
  ASSERT_EQ(w.contact_count(), 1u);
  EXPECT_LT(max_kinetic, start * 1.01);
  const double amplitude = omega0 * std::sqrt(inertia / stiffness);
  EXPECT_NEAR(0.5 * (max_turn - min_turn), amplitude, 0.01 * amplitude);
}

// The energy ledger with twist: the cube, undamped, turned by a torque of 0.8 of the slip moment
// (the dynamic overshoot carries it past the cap: it slips), then released. The work of the
// torque equals the kinetic energy plus the energy stored in the joint (the torsional spring's
// M² / (2 k_s J) with the normal spring's) plus the slip work |M| dθ_slip of every step.
// References: conservation of energy, to 2e-4 of the torque's work at every step (central
// differences, about 70 steps a cycle; 3e-5 measured, while leaving the spring's energy out
// misses by more than 5e-2); and until the release, while the cube slips one way only, Coulomb's
// slip work: μ σ_n ∫ r dA times the slip turn, the spring's turn θ_n - ω dt (the forces of a step
// act at the turn before the step's rotation ω dt) less its elastic part -M / (k_s J), within
// 1e-9 (round-off).
TEST(TwistInWorld, EnergyLedgerClosesWithTheTwistSpringAndItsSlip) {
  for (const ContactMode mode : {ContactMode::face_integrated, ContactMode::boon2012}) {
    WorldSettings s;
    s.time_step = 2e-5;
    s.contact_mode = mode;
    s.twist = true;
    World w = twisted_cube(s, true, 0.0, 0.0);
    for (int k = 0; k < 5; ++k) w.step();  // the contact forms at rest
    const double normal_energy = w.energy_budget().elastic;
    w.blocks()[1].set_external_torque(Eigen::Vector3d(0, 0, 0.8 * slip_moment()));
    const double stiffness = kShear * square_polar_moment();
    double worst = 0.0, most_stored = 0.0, coulomb = 0.0, slipped = 0.0;
    for (int k = 0; k < 400; ++k) {
      if (k == 200) {  // released
        w.blocks()[1].set_external_torque(Eigen::Vector3d::Zero());
        const double spring_turn = turn_of(w) - w.blocks()[1].angular_velocity.z() * s.time_step;
        coulomb = slip_moment() * (spring_turn + w.contacts()[0]->twist.moment / stiffness);
        slipped = w.energy_budget().friction_dissipation;
      }
      w.step();
      const EnergyBudget& e = w.energy_budget();
      worst = std::max(worst, std::abs(e.residual()));
      most_stored = std::max(most_stored, e.elastic - normal_energy);
    }
    ASSERT_EQ(w.contact_count(), 1u) << to_string(mode);
    const EnergyBudget& e = w.energy_budget();
    EXPECT_GT(e.load_work, 0.0) << to_string(mode);
    EXPECT_GT(slipped, 0.05 * e.load_work) << to_string(mode) << ": it slipped";
    EXPECT_GT(most_stored, 0.05 * e.load_work) << to_string(mode) << ": the spring held energy";
    EXPECT_LT(worst, 2e-4 * e.load_work) << to_string(mode);
    EXPECT_NEAR(slipped, coulomb, 1e-9 * slipped) << to_string(mode);
  }
}

// Objectivity: the cube and a free base turning together about the contact normal (a rigid
// rotation of the pair) create no twisting moment and no shear force; the cube turning alone does
// (the check can fail). Reference: zero, to 1e-12 of the slip moment.
TEST(TwistInWorld, RigidRotationOfBothBlocksCreatesNoMomentOrShear) {
  for (const bool together : {true, false}) {
    WorldSettings s;
    s.time_step = 2e-5;
    World w = linear_world(kNormal, kShear, kFriction, s);
    Block base = box_block({0.2, 0.2, 0.05}, {0, 0, -0.025}, kDensity, Motion::free, "base");
    Block cube =
        box_block(Eigen::Vector3d::Constant(kSide), {0, 0, kSide / 2 - kOverlap}, kDensity);
    // Held along z (the joint stays closed) and turning only about z.
    for (Block* b : {&base, &cube}) {
      b->blocked_translation = {true, true, true};
      b->blocked_rotation = {true, true, false};
    }
    cube.angular_velocity = Eigen::Vector3d(0, 0, 3.0);
    base.angular_velocity = together ? cube.angular_velocity : Eigen::Vector3d::Zero();
    for (Block* b : {&base, &cube}) b->angular_momentum = b->world_inertia() * b->angular_velocity;
    w.add_block(base);
    w.add_block(cube);
    for (int k = 0; k < 200; ++k) w.step();
    ASSERT_EQ(w.contact_count(), 1u);
    const Contact& c = *w.contacts()[0];
    if (together) {
      EXPECT_LT(std::abs(c.twist.moment), 1e-12 * slip_moment());
      EXPECT_LT(c.shear.force.norm(), 1e-12 * slip_moment() / kSide);
      EXPECT_GT(w.blocks()[1].rotation_since_start().z(), 0.01) << "the pair did turn";
    } else {
      EXPECT_GT(std::abs(c.twist.moment), 1e-3 * slip_moment());
    }
  }
}

// Shear without twist: a cube pushed sideways (no spin about the normal) gives the same shear
// force, force point and path with twist on as with twist off. Reference: the run without
// twist; tolerance 1e-9 (relative).
TEST(TwistInWorld, ShearWithoutTwistIsUnchanged) {
  auto run = [](bool twist) {
    WorldSettings s;
    s.gravity = Eigen::Vector3d(0, 0, -9.81);
    s.damping = 0.7;
    s.twist = twist;
    World w = linear_world(kNormal, kShear, kFriction, s);
    w.add_block(box_block({0.2, 0.2, 0.05}, {0, 0, -0.025}, kDensity, Motion::fixed, "base"));
    Block cube = box_block(Eigen::Vector3d::Constant(kSide), {0, 0, kSide / 2 - 1e-7}, kDensity);
    cube.set_external_force(Eigen::Vector3d(0.3, 0.0, 0.0));  // below tan 40° x the weight
    w.add_block(cube);
    for (int k = 0; k < 300; ++k) w.step();
    return w;
  };
  const World with = run(true), without = run(false);
  ASSERT_EQ(with.contact_count(), 1u);
  ASSERT_EQ(without.contact_count(), 1u);
  const Contact& a = *with.contacts()[0];
  const Contact& b = *without.contacts()[0];
  ASSERT_GT(b.shear.force.norm(), 0.1);
  EXPECT_LT((a.shear.force - b.shear.force).norm(), 1e-9 * b.shear.force.norm());
  EXPECT_LT((a.force_point() - b.force_point()).norm(), 1e-9 * kSide);
  EXPECT_LT((with.blocks()[1].position - without.blocks()[1].position).norm(), 1e-9 * kSide);
}

// The world checkpoint keeps the twisting moment: a restore gives it back exactly.
TEST(TwistInWorld, CheckpointKeepsTheTwistingMoment) {
  WorldSettings s;
  s.time_step = 2e-5;
  World w = twisted_cube(s, true, 0.5 * slip_moment(), 0.7);
  for (int k = 0; k < 150; ++k) w.step();
  w.save_checkpoint();
  const double moment = w.contacts()[0]->twist.moment;
  ASSERT_NE(moment, 0.0);
  for (int k = 0; k < 30; ++k) w.step();
  ASSERT_NE(w.contacts()[0]->twist.moment, moment);
  w.restore_checkpoint();
  ASSERT_EQ(w.contact_count(), 1u);
  EXPECT_EQ(w.contacts()[0]->twist.moment, moment);
}

}  // namespace
}  // namespace blockdem::test
