// Strength reduction of a wedge with water pressure on both sliding planes against the limit
// equilibrium of Hoek & Bray's wedge with water forces (Hoek & Bray, Rock Slope Engineering,
// 3rd ed., 1981, ch. 8; Wyllie & Mah, 4th ed., 2004, ch. 7), derived here in vector form.
//
// The wedge of the dry test (stability_wedge_test.cpp): planes A and B through the line of
// intersection, rising at alpha_A and alpha_B from the horizontal of the cross-section, upward
// unit normals n_A and n_B; the wedge above both, below the upper face z' = 0.1 m and between
// x' = -0.1 and 0.1 m (line frame x' along the line, z' normal to it). The line plunges psi_i:
// here the geometry is turned by psi_i about y and gravity is vertical, so that the water
// pressure below a table, p = rho_w g (z_w - z), is hydrostatic in the true vertical.
//
// The water table is the plane z' = h of the line frame (dipping psi_i along the line): below it
// p = rho_w g (h - z') / cos(psi_i), the vertical depth below the table. On a sliding plane at
// distance s from the line, z' = s sin(alpha), so over the submerged strip s < h / sin(alpha) of
// the face (length L = 0.2 m along the line) the water force is
//   U_i = L ∫_0^{h / sin a_i} rho_w g (h - s sin a_i) / cos(psi_i) ds
//       = L rho_w g h^2 / (2 sin(a_i) cos(psi_i)),                                      (1)
// along +n_i (pushing the wedge off plane i). The two end faces x' = ±0.1 carry equal and
// opposite forces (p does not depend on x'), and the upper face z' = 0.1 >= h none.
//
// Equilibrium normal to the line of intersection, with the normal reactions N_A, N_B (total) and
// the weight W (line frame: W (sin psi_i, 0, -cos psi_i)):
//   N_A n_A + N_B n_B = W cos(psi_i) e_z',                                              (2)
// the effective normal forces N'_i = N_i - U_i (the joint law carries N'), and along the line
// the driving force S = W sin(psi_i) (the water forces are normal to it), so that
//   F = (N'_A tan(phi_A) + N'_B tan(phi_B) + c_A A_A + c_B A_B) / S                     (3)
// (here c = 0 and phi = 45 degrees on both planes: with the sliding planes wholly under water the
// wedge must still stand at full strength, F > 1, to settle before the search). Cases: dry, h =
// 0.05 m (the lower half of the wedge) and h = 0.1 m (the whole of both sliding planes, p = 0 at
// the upper edges as in Hoek & Bray's wedge), a symmetric and an asymmetric wedge, both contact
// modes. Tolerance 3% on F (bisection bracket 0.01).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "blockdem/numerics/units.hpp"
#include "blockdem/world/stability.hpp"
#include "scenes.hpp"
#include "support/dense_solves.hpp"
#include "support/sanitized_run.hpp"

namespace blockdem::test::water_wedge {
namespace {

constexpr double kRock = 2500.0, kWater = 1000.0, kLength = 0.2, kTop = 0.1;

struct WedgeCase {
  double alpha_a_deg;
  double alpha_b_deg;
  double table_h;  ///< h: the water table's height above the line of intersection, 0: dry (m)
  ContactMode mode;
};

void PrintTo(const WedgeCase& c, std::ostream* os) {
  *os << c.alpha_a_deg << "/" << c.alpha_b_deg << " h " << c.table_h << " "
      << (c.mode == ContactMode::boon2012 ? "boon2012" : "face_integrated");
}

std::string case_name(const ::testing::TestParamInfo<WedgeCase>& p) {
  const WedgeCase& c = p.param;
  return std::string(c.mode == ContactMode::boon2012 ? "boon2012_" : "face_integrated_") +
         (c.alpha_a_deg == c.alpha_b_deg ? "symmetric_" : "asymmetric_") +
         (c.table_h == 0.0   ? "dry"
          : c.table_h < kTop ? "half"
                             : "full");
}

class WedgeWithWater : public ::testing::TestWithParam<WedgeCase> {};

TEST_P(WedgeWithWater, FactorOfSafetyMatchesHoekBrayWithWaterForces) {
  const WedgeCase c = GetParam();
  // Under the sanitizers (10-100 times slower) the asymmetric wedge half under water stands for
  // the twelve: the same code, each strength reduction a minute there.
  if (test::sanitized_run() &&
      !(c.alpha_a_deg != c.alpha_b_deg && c.table_h > 0.0 && c.table_h < 0.1))
    GTEST_SKIP() << "one case of the twelve runs under the sanitizers";
  const double plunge = deg_to_rad(30.0), phi_deg = 45.0;
  const double aa = deg_to_rad(c.alpha_a_deg), ab = deg_to_rad(c.alpha_b_deg);
  // Line frame: upward unit normals of the two planes, both through the x' axis.
  const Eigen::Vector3d na(0, std::sin(aa), std::cos(aa));
  const Eigen::Vector3d nb(0, -std::sin(ab), std::cos(ab));
  const Eigen::Vector3d ex = Eigen::Vector3d::UnitX(), ey = Eigen::Vector3d::UnitY();
  const Eigen::Vector3d ez = Eigen::Vector3d::UnitZ();
  // The world: the line frame turned by psi_i about y, so that its gravity
  // g (sin psi_i, 0, -cos psi_i) is vertical.
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(plunge, Eigen::Vector3d::UnitY()).matrix();
  const auto world_planes = [&turn](std::vector<Halfspace> planes) {
    for (Halfspace& h : planes) h.normal = turn * h.normal;
    return Polyhedron::from_planes(planes);
  };

  WorldSettings s;
  s.gravity = Eigen::Vector3d(0.0, 0.0, -kOneG);
  s.damping = 0.7;
  s.contact_mode = c.mode;
  if (c.table_h > 0.0)
    s.water = GroundWater{WaterTable::plane(turn * (c.table_h * ez), turn * ez), kWater};
  World w = test::linear_world(1e10, 1e9, phi_deg, s);
  // The trough: slabs 0.05 m thick below each plane, 1 m long along the line.
  struct Slab {
    Eigen::Vector3d normal, side;
    const char* name;
  };
  for (const Slab& p : {Slab{na, ey, "plane_A"}, Slab{nb, -ey, "plane_B"}}) {
    Block b = make_block(world_planes({{p.normal, 0.0},
                                       {-p.normal, 0.05},
                                       {p.side, 0.0},
                                       {-p.side, 0.3},
                                       {ex, 0.5},
                                       {-ex, 0.5}}),
                         kRock, p.name);
    b.motion = Motion::fixed;
    w.add_block(b);
  }
  w.add_block(make_block(
      world_planes({{-na, 0.0}, {-nb, 0.0}, {ez, kTop}, {ex, 0.5 * kLength}, {-ex, 0.5 * kLength}}),
      kRock, "wedge"));

  Stage settle;
  settle.name = "settle";
  settle.max_steps = 200000;
  const StageResult r = run_stage(w, settle);
  ASSERT_TRUE(r.converged) << r.message;

  // The closed form. W from the wedge's cross-section (a triangle of height kTop between the
  // planes) times its length.
  const double width = kTop / std::tan(aa) + kTop / std::tan(ab);
  const double weight = kRock * kOneG * 0.5 * kTop * width * kLength;
  // (2): the total normal reactions.
  Eigen::Matrix2d a;
  a << na.y(), nb.y(), na.z(), nb.z();
  const Eigen::Vector2d n =
      test::solve_partial_lu(a, Eigen::Vector2d(0.0, weight * std::cos(plunge)));
  // (1): the water forces on the sliding planes.
  const double h = c.table_h;
  const double ua = kLength * kWater * kOneG * h * h / (2.0 * std::sin(aa) * std::cos(plunge));
  const double ub = kLength * kWater * kOneG * h * h / (2.0 * std::sin(ab) * std::cos(plunge));
  // (3): effective normal forces and the factor of safety.
  const double tan_phi = std::tan(deg_to_rad(phi_deg));
  const double expected = ((n(0) - ua) + (n(1) - ub)) * tan_phi / (weight * std::sin(plunge));

  // The engine's water force on the settled wedge: U_A n_A + U_B n_B (the wedge has moved into
  // its joints by about 1e-7 m, which changes U by a few 1e-6 of itself).
  const Block& wedge = w.blocks()[2];
  const Eigen::Vector3d water_expected = turn * (ua * na + ub * nb);
  EXPECT_NEAR((wedge.water_force() - water_expected).norm(), 0.0,
              1e-4 * std::max(water_expected.norm(), 1.0));

  Stage trial = settle;
  trial.name = "srm";
  trial.max_steps = 60000;
  const StabilitySearch sr =
      strength_reduction(w, trial, {0}, 0.5 * expected, 2.0 * expected, 0.01, {});
  const double F = 0.5 * (sr.last_stable + sr.first_failed);
  std::printf(
      "%s wedge %g/%g, table h = %.2f m: U_A = %.4f N, U_B = %.4f N, W = %.4f N, "
      "water force (%.4f, %.4f, %.4f) N; F = %.4f (Hoek & Bray %.4f, %+.2f%%), %zu trials\n",
      c.mode == ContactMode::boon2012 ? "boon2012" : "face_integrated", c.alpha_a_deg,
      c.alpha_b_deg, h, ua, ub, weight, wedge.water_force().x(), wedge.water_force().y(),
      wedge.water_force().z(), F, expected, 100.0 * (F / expected - 1.0), sr.trials.size());
  EXPECT_NEAR(F, expected, 0.03 * expected);
}

INSTANTIATE_TEST_SUITE_P(HoekBray, WedgeWithWater,
                         ::testing::Values(WedgeCase{50, 50, 0.0, ContactMode::face_integrated},
                                           WedgeCase{50, 50, 0.05, ContactMode::face_integrated},
                                           WedgeCase{50, 50, 0.1, ContactMode::face_integrated},
                                           WedgeCase{40, 60, 0.0, ContactMode::face_integrated},
                                           WedgeCase{40, 60, 0.05, ContactMode::face_integrated},
                                           WedgeCase{40, 60, 0.1, ContactMode::face_integrated},
                                           WedgeCase{50, 50, 0.0, ContactMode::boon2012},
                                           WedgeCase{50, 50, 0.05, ContactMode::boon2012},
                                           WedgeCase{50, 50, 0.1, ContactMode::boon2012},
                                           WedgeCase{40, 60, 0.0, ContactMode::boon2012},
                                           WedgeCase{40, 60, 0.05, ContactMode::boon2012},
                                           WedgeCase{40, 60, 0.1, ContactMode::boon2012}),
                         case_name);

}  // namespace
}  // namespace blockdem::test::water_wedge
