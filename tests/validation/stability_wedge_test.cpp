// Strength reduction against Hoek & Bray's wedge on two planes (Rock Slope Engineering, 3rd ed.,
// ch. 8, friction only, both planes in contact): F = (N_A tan phi_A + N_B tan phi_B) /
// (W sin psi_i), with N_A, N_B from equilibrium normal to the line of intersection. The line of
// intersection is the x axis and plunges psi_i (gravity tilted by psi_i about y); plane A
// (y < 0) and plane B (y > 0) rise from it at alpha_A and alpha_B from the horizontal in the
// cross-section. A symmetric and an asymmetric wedge; tolerance 3%.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>

#include "blockdem/numerics/units.hpp"
#include "blockdem/world/stability.hpp"
#include "scenes.hpp"
#include "support/dense_solves.hpp"

namespace blockdem {
namespace {

struct WedgeCase {
  double alpha_a_deg;  // rise of plane A from the horizontal in the cross-section
  double alpha_b_deg;
  double plunge_deg;  // psi_i
  double phi_deg;
};

Block fixed_block(std::vector<Halfspace> planes, const std::string& name) {
  Block b = make_block(Polyhedron::from_planes(planes), 2500.0, name);
  b.motion = Motion::fixed;
  return b;
}

class WedgeSliding : public ::testing::TestWithParam<WedgeCase> {};

TEST_P(WedgeSliding, FactorOfSafetyMatchesHoekBray) {
  const WedgeCase c = GetParam();
  const double aa = deg_to_rad(c.alpha_a_deg), ab = deg_to_rad(c.alpha_b_deg);
  const double psi = deg_to_rad(c.plunge_deg);
  // Upward unit normals of the two planes, both through the x axis.
  const Eigen::Vector3d na(0, std::sin(aa), std::cos(aa));
  const Eigen::Vector3d nb(0, -std::sin(ab), std::cos(ab));
  const Eigen::Vector3d ex = Eigen::Vector3d::UnitX(), ey = Eigen::Vector3d::UnitY();

  WorldSettings s;
  s.gravity = kOneG * Eigen::Vector3d(std::sin(psi), 0, -std::cos(psi));
  s.damping = 0.7;
  World w = test::linear_world(1e10, 1e9, c.phi_deg, s);
  // The trough: slabs 0.05 m thick below each plane, 1 m long in x.
  w.add_block(fixed_block({{na, 0.0}, {-na, 0.05}, {ey, 0.0}, {-ey, 0.3}, {ex, 0.5}, {-ex, 0.5}},
                          "plane_A"));
  w.add_block(fixed_block({{nb, 0.0}, {-nb, 0.05}, {-ey, 0.0}, {ey, 0.3}, {ex, 0.5}, {-ex, 0.5}},
                          "plane_B"));
  // The wedge: above both planes, below z = 0.1, 0.2 m long.
  const Eigen::Vector3d ez = Eigen::Vector3d::UnitZ();
  Block wedge = make_block(Polyhedron::from_planes(std::vector<Halfspace>{
                               {-na, 0.0}, {-nb, 0.0}, {ez, 0.1}, {ex, 0.1}, {-ex, 0.1}}),
                           2500.0, "wedge");
  w.add_block(wedge);

  Stage settle;
  settle.name = "settle";
  settle.max_steps = 200000;
  const StageResult r = run_stage(w, settle);
  ASSERT_TRUE(r.converged) << r.message;

  // Closed form: N_A na + N_B nb balances the weight's component normal to the line,
  // W cos(psi_i) along +z; then F = (N_A + N_B) tan(phi) / (W sin(psi_i)).
  Eigen::Matrix2d a;
  a << na.y(), nb.y(), na.z(), nb.z();
  const Eigen::Vector2d n = test::solve_partial_lu(a, Eigen::Vector2d(0.0, std::cos(psi)));
  const double expected = (n(0) + n(1)) * std::tan(deg_to_rad(c.phi_deg)) / std::sin(psi);

  Stage trial = settle;
  trial.name = "srm";
  trial.max_steps = 60000;
  const StabilitySearch sr =
      strength_reduction(w, trial, {0}, 0.5 * expected, 2.0 * expected, 0.01, {});
  const double F = 0.5 * (sr.last_stable + sr.first_failed);
  std::printf("wedge %g/%g, plunge %g, phi %g: F = %.4f (Hoek & Bray %.4f), %zu trials\n",
              c.alpha_a_deg, c.alpha_b_deg, c.plunge_deg, c.phi_deg, F, expected, sr.trials.size());
  EXPECT_NEAR(F, expected, 0.03 * expected);
}

INSTANTIATE_TEST_SUITE_P(HoekBray, WedgeSliding,
                         ::testing::Values(WedgeCase{50, 50, 30, 30}, WedgeCase{40, 60, 30, 30}),
                         [](const ::testing::TestParamInfo<WedgeCase>& p) {
                           return p.param.alpha_a_deg == p.param.alpha_b_deg ? "symmetric"
                                                                             : "asymmetric";
                         });

}  // namespace
}  // namespace blockdem
