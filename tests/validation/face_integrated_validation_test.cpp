// Mode face_integrated against closed forms: pressure distributions under an
// eccentric load, equality with the point contact under uniform closure, the exponential law
// against a high-order quadrature, and energy conservation of an undamped rocking block.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "blockdem/collision/boon2012.hpp"
#include "blockdem/collision/face_contact.hpp"
#include "blockdem/contact/normal_integral.hpp"
#include "blockdem/numerics/units.hpp"
#include "blockdem/world/stage.hpp"
#include "scenes.hpp"

namespace blockdem {
namespace {

struct Resultant {
  double force = 0.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double compressed_area = 0.0;
  double peak = 0.0;
};

// What the world does for one face contact: cells, then the law over each.
Resultant integrate(const std::vector<Halfspace>& a, const std::vector<Halfspace>& b,
                    const Eigen::Vector3d& origin, const Eigen::Vector3d& normal,
                    const NormalLaw& law) {
  const FaceContactGeometry g = face_contact_geometry(a, b, origin, normal, 10.0);
  EXPECT_TRUE(g.face_type);
  Resultant r;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (const auto& c : g.cells) {
    const auto p = integrate_normal_stress_over_polygon(law, c.vertices, c.closures);
    r.force += p.force;
    r.compressed_area += p.compressed_area;
    r.peak = std::max(r.peak, p.peak_stress);
    if (p.centre_of_pressure) moment += p.force * *p.centre_of_pressure;
  }
  r.centre = moment / r.force;
  return r;
}

// A small fixed base A (La x Wa, vertical sides, top at z = 0) under a larger block B tilted by θ
// about y, whose bottom face is the plane z = -d0 + x tanθ. Over A's top face the closure along
// +z is g(x) = d0 - x tanθ, x in [-La/2, La/2]: B's bottom face covers A's top, and A's vertical
// sides bound the contact exactly.
struct Tilted {
  std::vector<Halfspace> base, block;
  double x0 = 0.0, length = 0.0, width = 0.0, d0 = 0.0, slope = 0.0;
  double closure(double x) const { return d0 - slope * x; }
};

Tilted tilted_block(double La, double Wa, double theta, double d0) {
  Tilted t;
  t.base = copy_planes(
      Polyhedron::box({La, Wa, 0.05}).transformed(Eigen::Matrix3d::Identity(), {0, 0, -0.025}));
  const Eigen::Matrix3d r = Eigen::AngleAxisd(-theta, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Polyhedron p =
      Polyhedron::box({3 * La, 3 * Wa, 0.05}).transformed(r, Eigen::Vector3d::Zero());
  // The bottom plane n·x = d meets the z axis at z = d / n_z; move it to z = -d0.
  const Halfspace* bottom = nullptr;
  for (const auto& h : p.planes()) {
    if (bottom == nullptr || h.normal.z() < bottom->normal.z()) bottom = &h;
  }
  const double z_axis = bottom->offset / bottom->normal.z();
  t.block = copy_planes(p.transformed(Eigen::Matrix3d::Identity(), {0, 0, -d0 - z_axis}));
  t.x0 = -La / 2;
  t.length = La;
  t.width = Wa;
  t.d0 = d0;
  t.slope = std::tan(theta);
  return t;
}

// Trapezoidal distribution: the whole face is compressed. Linear law: with g(x) = d0 - s x on
// [-L/2, L/2], F = k W L d0 and x̄ = -k W s (L³/12) / F (the linear part only moves the centre).
// Tolerance 1e-9.
TEST(FaceIntegrated, TrapezoidalPressureMatchesClosedForm) {
  const double k = 10e9;
  const Tilted t = tilted_block(0.08, 0.04, 1e-4, 2e-5);  // g from 2.4e-5 down to 1.6e-5
  const Resultant r = integrate(t.base, t.block, Eigen::Vector3d(0, 0, -1e-5),
                                Eigen::Vector3d::UnitZ(), LinearNormal{k});
  const double l = t.length;
  ASSERT_GT(t.closure(l / 2), 0.0) << "the whole face must be compressed";
  const double force = k * t.width * l * t.d0;
  const double xbar = -k * t.width * t.slope * l * l * l / 12 / force;
  EXPECT_NEAR(r.force, force, 1e-9 * force);
  EXPECT_NEAR(r.centre.x(), xbar, 1e-9 * l);
  EXPECT_NEAR(r.centre.y(), 0.0, 1e-9 * l);
  EXPECT_NEAR(r.compressed_area, l * t.width, 1e-9 * l * t.width);
  EXPECT_NEAR(r.peak, k * t.closure(-l / 2), 1e-9 * k * t.d0);
}

// Triangular distribution: the joint is open beyond x_open = d0/s; the compressed length is
// c = x_open + L/2, F = k W g_max c / 2 with g_max = g(-L/2), acting c/3 from the compressed
// edge. Tolerance 1e-9.
TEST(FaceIntegrated, TriangularPressureMatchesClosedForm) {
  const double k = 10e9;
  const Tilted t = tilted_block(0.08, 0.04, 1e-3, 1e-5);  // open beyond x = 0.01 m
  const Resultant r = integrate(t.base, t.block, Eigen::Vector3d(0, 0, -5e-6),
                                Eigen::Vector3d::UnitZ(), LinearNormal{k});
  const double c = t.d0 / t.slope + t.length / 2;
  ASSERT_LT(c, t.length);
  const double g_max = t.closure(-t.length / 2);
  const double force = k * t.width * g_max * c / 2;
  EXPECT_NEAR(r.force, force, 1e-9 * force);
  EXPECT_NEAR(r.centre.x(), -t.length / 2 + c / 3, 1e-9 * c);
  EXPECT_NEAR(r.compressed_area, t.width * c, 1e-9 * t.width * c);
}

// The exponential law over the trapezoid against 40-point Gauss-Legendre in x (the closure
// depends on x only): relative agreement 1e-8 for eq. 3.
TEST(FaceIntegrated, ExponentialLawMatchesHighOrderQuadrature) {
  const NormalLaw law = ExponentialNormal::eq3();
  const Tilted t = tilted_block(0.08, 0.04, 2e-4, 2e-5);  // g from 2.8e-5 to 1.2e-5
  const Resultant r =
      integrate(t.base, t.block, Eigen::Vector3d(0, 0, -1e-5), Eigen::Vector3d::UnitZ(), law);
  // Gauss-Legendre nodes by Newton on P_40.
  const int n = 40;
  double force = 0.0, moment = 0.0;
  for (int i = 1; i <= n; ++i) {
    double x = std::cos(kPi * (i - 0.25) / (n + 0.5)), dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = x;
      for (int m = 2; m <= n; ++m) {
        const double p2 = ((2 * m - 1) * x * p1 - (m - 1) * p0) / m;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    const double w = 2 / ((1 - x * x) * dp * dp);
    const double xs = 0.5 * t.length * x;
    const double sigma = normal_stress(law, t.closure(xs));
    force += w * 0.5 * t.length * sigma * t.width;
    moment += w * 0.5 * t.length * sigma * t.width * xs;
  }
  EXPECT_NEAR(r.force, force, 1e-8 * force);
  EXPECT_NEAR(r.centre.x(), moment / force, 1e-8 * t.length);
}

// Uniform closure: face integration gives exactly σ_n(δ) A, the point contact's force.
TEST(FaceIntegrated, UniformClosureGivesThePointContactForce) {
  const double h = 3e-5;
  const auto a = copy_planes(Polyhedron::box({1, 1, 1}));
  const auto b = copy_planes(
      Polyhedron::box({1, 1, 1}).transformed(Eigen::Matrix3d::Identity(), {0.2, 0.1, 1 - h}));
  const ContactGeometry g = boon2012_contact(a, b, 4.0, Boon2012Settings{});
  ASSERT_TRUE(g.touching);
  for (const NormalLaw& law :
       {NormalLaw(LinearNormal{1e10}), NormalLaw(ExponentialNormal::eq4())}) {
    const double point = normal_stress(law, g.overlap) * g.area;
    const Resultant r = integrate(a, b, g.point, g.normal, law);
    EXPECT_NEAR(r.force, point, 1e-12 * point);
    EXPECT_NEAR(r.compressed_area, g.area, 1e-12);
  }
}

// A block under an eccentric vertical load P at offset e on a fixed base (linear law, no
// gravity). Equilibrium: the centre of pressure is at e (statics), and the block's tilt and the
// peak closure follow the closed form of a rigid footing on a Winkler foundation:
// e <= L/6: θ = 12 P e / (k W L³), peak closure P/(k W L) + θ L/2;
// e > L/6: contact length c = 3 (L/2 - e), peak closure 2 P / (k W c), θ = peak / c.
// The contact normal (the rounded normal) turns with the block by about θ/2,
// a geometric effect of relative size ~θ H / e that the small-rotation closed form ignores; at
// this load θ ~ 1e-5 and the tolerance is 2e-3 relative.
class EccentricLoad : public ::testing::TestWithParam<double> {};

TEST_P(EccentricLoad, TiltAndPeakClosureMatchWinklerFooting) {
  const double k = 1e10, L = 0.1, W = 0.1, H = 0.05, P = 200.0;
  const double e = GetParam() * L;
  WorldSettings s;
  s.contact_mode = ContactMode::face_integrated;
  s.damping = 0.7;
  World w = test::linear_world(k, 1e9, 60, s);
  w.add_block(test::box_block({0.4, 0.4, 0.05}, {0, 0, -0.025}, 2600, Motion::fixed, "base"));
  Block b = test::box_block({L, W, H}, {0, 0, H / 2}, 2600);
  b.set_external_force({0, 0, -P});
  b.set_external_torque(
      {0, P * e, 0});  // the load at x = e: r × F = (e,0,0) × (0,0,-P) = (0, P e, 0)
  w.add_block(b);
  Stage st;
  st.unbalanced_tolerance = 1e-10;
  st.kinetic_tolerance = 1e-18;
  st.max_steps = 400000;
  const StageResult res = run_stage(w, st);
  ASSERT_TRUE(res.converged) << res.message;
  const auto contacts = w.contacts();
  ASSERT_EQ(contacts.size(), 1u);
  const Contact& c = *contacts[0];
  ASSERT_TRUE(c.integrated);
  EXPECT_NEAR(c.normal_force, P, 1e-6 * P);
  const double theta_meas = w.blocks()[1].rotation_since_start().y();
  double theta = 0.0, peak = 0.0;
  if (e <= L / 6) {
    theta = 12 * P * e / (k * W * L * L * L);
    peak = P / (k * W * L) + theta * L / 2;
  } else {
    const double cl = 3 * (L / 2 - e);
    peak = 2 * P / (k * W * cl);
    theta = peak / cl;
  }
  EXPECT_NEAR(c.force_point().x() - w.blocks()[1].position.x(), e, 1e-5 * L);
  EXPECT_NEAR(std::abs(theta_meas), theta, 2e-3 * theta);
  EXPECT_NEAR(c.peak_closure(), peak, 2e-3 * peak);
}

INSTANTIATE_TEST_SUITE_P(Offsets, EccentricLoad, ::testing::Values(0.05, 0.1, 0.25, 0.35));

// An undamped block rocking on a fixed base (linear joint, friction high enough to prevent
// slip): kinetic + gravitational + elastic energy (½ k ∫ g² dA over the contact cells, plus
// ½|F_s|²/(k_s A) in the shear spring) is conserved to the integrator's order: the largest
// deviation over 0.2 s falls about fourfold when the step is halved (second order), and stays a
// small fraction of the rocking energy. (Lift-off and re-contact are impacts, which a fixed-step
// scheme resolves only to first order; the amplitudes here stay below the static closure.)
double rocking_energy_error(double dt, double* rocking_energy) {
  const double k = 1e9, ks = 1e9, L = 0.1, H = 0.2, rho = 2600, g = 9.81;
  WorldSettings s;
  s.contact_mode = ContactMode::face_integrated;
  s.gravity = {0, 0, -g};
  s.time_step = dt;
  World w = test::linear_world(k, ks, 80, s);
  w.add_block(test::box_block({0.6, 0.6, 0.05}, {0, 0, -0.025}, rho, Motion::fixed, "base"));
  Block b = test::box_block({L, L, H}, {0, 0, H / 2}, rho);
  const double m = b.mass;
  b.position.z() -= m * g / (k * L * L);  // at the static closure
  // A small kick: the block rocks and bounces on its joint without any part of the face
  // lifting off (amplitudes below the static closure), so no impact enters the balance.
  b.velocity = {0, 0, 0.002};
  b.angular_velocity = {0, 0.02, 0};
  w.add_block(b);
  *rocking_energy = w.blocks()[1].kinetic_energy();
  // Potential energy at the current positions x_n: gravity, the joint's normal springs and its
  // shear spring.
  auto potential = [&]() {
    const Block& bl = w.blocks()[1];
    double e = m * g * bl.position.z();
    for (const Contact* c : w.contacts()) {
      const auto& ba = w.blocks()[c->a];
      const auto& bb = w.blocks()[c->b];
      const FaceContactGeometry fc = face_contact_geometry(
          ba.world_planes, bb.world_planes, c->geometry.point, c->geometry.normal, 2.0);
      for (const auto& cell : fc.cells) {
        for (std::size_t i = 1; i + 1 < cell.vertices.size(); ++i) {
          const double g0 = cell.closures[0], g1 = cell.closures[i], g2 = cell.closures[i + 1];
          const double area = 0.5 * (cell.vertices[i] - cell.vertices[0])
                                        .cross(cell.vertices[i + 1] - cell.vertices[0])
                                        .norm();
          e += 0.5 * k * area / 6 * (g0 * g0 + g1 * g1 + g2 * g2 + g0 * g1 + g1 * g2 + g0 * g2);
        }
      }
      e += 0.5 * c->shear.force.squaredNorm() / (ks * c->compressed_area());
    }
    return e;
  };
  // Leapfrog keeps velocities at half steps: the kinetic energy at step n uses the mean of
  // v_{n-1/2} and v_{n+1/2}, and the step that computes v_{n+1/2} also evaluates the contact at
  // x_n.
  auto step_energy = [&]() {
    const Eigen::Vector3d v0 = w.blocks()[1].velocity, w0 = w.blocks()[1].angular_velocity;
    w.step();
    const double u = potential();  // the contacts now hold the geometry of x_n
    const Block& bl = w.blocks()[1];
    const Eigen::Vector3d v = 0.5 * (v0 + bl.velocity);
    const Eigen::Vector3d om = 0.5 * (w0 + bl.angular_velocity);
    return u - m * g * (bl.position.z() - (bl.position.z() - bl.velocity.z() * dt)) +
           0.5 * m * v.squaredNorm() + 0.5 * om.dot(bl.world_inertia() * om);
  };
  w.step();
  const double e0 = step_energy();
  double worst = 0.0;
  const int steps = static_cast<int>(0.2 / dt);
  for (int i = 0; i < steps; ++i) {
    worst = std::max(worst, std::abs(step_energy() - e0));
    EXPECT_EQ(w.contact_count(), 1u);
  }
  return worst;
}

TEST(FaceIntegrated, UndampedRockingBlockConservesEnergyToSecondOrder) {
  double rocking = 0.0;
  const double coarse = rocking_energy_error(2e-5, &rocking);
  const double fine = rocking_energy_error(1e-5, &rocking);
  EXPECT_GT(coarse / fine, 3.0) << "coarse " << coarse << " J, fine " << fine << " J";
  EXPECT_LT(fine, 1e-3 * rocking) << "rocking energy " << rocking << " J";
}

}  // namespace
}  // namespace blockdem
