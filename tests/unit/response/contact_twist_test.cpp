// The area terms of a face contact's torsional spring: J of the cells about their centroid
// (closed form a⁴/6 for a square), and the cheap lower bounds of ∫ σ_n r dA that let an elastic
// step skip the full quadrature: they never exceed the quadrature's value.
#include "blockdem/response/contact_twist.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "blockdem/contact/normal_integral.hpp"
#include "square_cells.hpp"

// A namespace of this file's own: the unity build (cmake/build_speed.cmake) compiles it together
// with other test files that define helpers of the same names.
namespace blockdem::test::response_contact_twist {
namespace {

constexpr double kSide = 0.046;  // square side a (m)

// The square [0, a]² at z = 0 as two cells (split at x = a/2) with the closure linear in x,
// g = g0 + slope x (m): one linear field over both cells.
FaceContactGeometry square_cells(double g0, double slope) {
  return test::square_cells(kSide, g0, slope);
}

/// F_n and the centre of pressure x_p of the cells, as the world's step forms them.
struct NormalResultant {
  double force = 0.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
};
NormalResultant normal_resultant(const FaceContactGeometry& fc, const NormalLaw& law) {
  double force = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (const auto& cell : fc.cells) {
    const PolygonStressResultant r =
        integrate_normal_stress_over_polygon(law, cell.vertices, cell.closures);
    force += r.force;
    if (r.centre_of_pressure) moment += r.force * *r.centre_of_pressure;
  }
  return {force, moment / force};
}

// r_max is the largest distance of a vertex from the centroid, to the bit (taken as the square
// root of the largest squared distance).
TEST(ContactTwist, MaxRadiusIsTheLargestVertexDistance) {
  FaceContactGeometry fc;
  fc.face_type = true;
  for (int c = 0; c < 3; ++c) {
    ClosureCell& cell = fc.cells.emplace_back();
    for (int k = 0; k < 4 + c; ++k) {
      const double angle = 2.0 * std::numbers::pi * k / (4 + c) + 0.3 * c;
      cell.vertices.push_back(Eigen::Vector3d(0.02 * c + 0.013 * std::cos(angle),
                                              0.011 * c + 0.017 * std::sin(angle), 0.0));
      cell.closures.push_back(1e-5);
    }
  }
  const TwistGeometry g = face_twist_geometry(fc.cells, Eigen::Vector3d::UnitZ(), 1.0,
                                              Eigen::Vector3d(0.02, 0.01, 0.0));
  double largest = 0.0;
  for (const ClosureCell& cell : fc.cells)
    for (const Eigen::Vector3d& x : cell.vertices)
      largest = std::max(largest, (x - g.centre).norm());
  ASSERT_GT(largest, 0.0);
  EXPECT_EQ(g.max_radius, largest);
}

// J about the centroid: a⁴/6, to round-off (1e-12).
TEST(ContactTwist, PolarMomentOfTwoCellsIsTheSquares) {
  const FaceContactGeometry fc = square_cells(1e-5, 0.0);
  const TwistGeometry g = face_twist_geometry(fc.cells, Eigen::Vector3d::UnitZ(), 1.0,
                                              Eigen::Vector3d(0.01, 0.02, 0.0));
  EXPECT_NEAR(g.polar_moment / (std::pow(kSide, 4) / 6.0), 1.0, 1e-12);
  EXPECT_NEAR((g.centre - Eigen::Vector3d(kSide / 2, kSide / 2, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(g.max_radius, kSide / std::numbers::sqrt2, 1e-15);
  EXPECT_FALSE(g.exact);
}

// Uniform closure: Jensen's bound is an equality for ∫ σ r² dA, so the bound is σ J / r_max =
// σ a³ √2 / 6 (1e-12), below the exact σ a³ (√2 + asinh 1) / 6.
TEST(ContactTwist, BoundUnderUniformClosureIsStressTimesPolarMomentOverRadius) {
  const LinearNormal law{10e9};
  const FaceContactGeometry fc = square_cells(1e-5, 0.0);
  const double sigma = 10e9 * 1e-5;
  const TwistGeometry g =
      face_twist_geometry(fc.cells, Eigen::Vector3d::UnitZ(), sigma * kSide * kSide,
                          Eigen::Vector3d(kSide / 2, kSide / 2, 0));
  const double bound = face_radial_normal_bound(fc.cells, law, g);
  EXPECT_NEAR(bound / (sigma * std::pow(kSide, 3) * std::numbers::sqrt2 / 6.0), 1.0, 1e-12);
  const double exact = face_radial_normal_moment(fc.cells, law, g.centre);
  EXPECT_NEAR(exact / (sigma * std::pow(kSide, 3) * (std::numbers::sqrt2 + std::asinh(1.0)) / 6.0),
              1.0, 1e-3);
}

// A closure rising across the square (from zero at one edge, a hinging joint) with both laws:
// the free bound F_n |x_p - c| and the Jensen bound stay below the quadrature's ∫ σ_n r dA
// (which is within 1e-3 of the truth), and the Jensen bound is not trivially small (> 0.4 of it).
TEST(ContactTwist, BoundsStayBelowTheExactRadialMoment) {
  const NormalLaw laws[] = {LinearNormal{10e9}, ExponentialNormal::eq3()};
  for (const NormalLaw& law : laws) {
    for (const double slope : {0.0, 2e-4, 1e-3}) {
      const FaceContactGeometry fc = square_cells(slope == 0.0 ? 1e-5 : 0.0, slope);
      const NormalResultant n = normal_resultant(fc, law);
      const TwistGeometry g =
          face_twist_geometry(fc.cells, Eigen::Vector3d::UnitZ(), n.force, n.centre);
      const double exact = face_radial_normal_moment(fc.cells, law, g.centre);
      const double bound = face_radial_normal_bound(fc.cells, law, g);
      EXPECT_LE(g.radial_normal_moment, exact * (1 + 1e-3)) << slope;
      EXPECT_LE(bound, exact * (1 + 1e-3)) << slope;
      EXPECT_GT(bound, 0.4 * exact) << slope;
    }
  }
}

// The capacity about the centre of pressure x_p on the same hinging square: the bound
// face_pressure_radial_bound stays below the quadrature's ∫ σ_n |y - x_p| dA (within 1e-3 of
// the truth) and above 0.05 of it. The uniform closure (x_p = c) gives the bound about c exactly;
// on the hinging joint (x_p off c) it is more than twice the bound about c less F_n |x_p - c|
// (2.3-3.9 times here; that one reaches zero on the steep exponential hinge).
TEST(ContactTwist, BoundAboutThePressureCentreStaysBelowTheExact) {
  const NormalLaw laws[] = {LinearNormal{10e9}, ExponentialNormal::eq3()};
  for (const NormalLaw& law : laws) {
    for (const double slope : {0.0, 2e-4, 1e-3}) {
      const FaceContactGeometry fc = square_cells(slope == 0.0 ? 1e-5 : 0.0, slope);
      const NormalResultant n = normal_resultant(fc, law);
      const double force = n.force;
      const Eigen::Vector3d xp = n.centre;
      const TwistGeometry g = face_twist_geometry(fc.cells, Eigen::Vector3d::UnitZ(), force, xp);
      const double d = (g.centre - xp).norm();
      const double exact = face_radial_normal_moment(fc.cells, law, xp);
      const double about_c = face_radial_normal_bound(fc.cells, law, g) - force * d;
      const double bound = face_pressure_radial_bound(fc.cells, law, g, force, xp);
      EXPECT_LE(bound, exact * (1 + 1e-3)) << slope;
      EXPECT_GT(bound, 0.05 * exact) << slope;
      if (slope == 0.0)
        EXPECT_NEAR(bound / about_c, 1.0, 1e-9);
      else
        EXPECT_GT(bound, 2.0 * about_c) << slope;
    }
  }
}

// A contact barely closed, 4 m from the origin: a pentagon whose closures are zero or ~1e-16 m
// at its vertices (found by a random search over such cells; the closed forms of the cells
// cancel terms and summed to -2.2e-21 N m). ∫ σ_n r dA is not negative (σ_n >= 0, r >= 0) and at
// most σ_max r_max A; the torsional spring takes it (a negative value stopped a 1e5-block pile's
// settling in mode face_integrated). Tolerance: the bounds themselves.
TEST(ContactTwist, ExactRadialMomentOfABarelyClosedCellIsNotNegative) {
  ClosureCell cell;
  const double v[5][4] = {
      {0x1.8cad3bb2ab212p+1, 0x1.b6498b50fafa7p+1, 0x1.bea38246b1192p-3, 0.0},
      {0x1.8cad8038ef527p+1, 0x1.b649a09ea870ap+1, 0x1.be9e1f89f3d84p-3, 0x1.b61aeb40add9cp-53},
      {0x1.8cad44327cabdp+1, 0x1.b64a5b6887bdp+1, 0x1.bea38269db0ccp-3, 0.0},
      {0x1.8cad042ef981cp+1, 0x1.b64a16776af36p+1, 0x1.bea8618a47c08p-3, 0x1.82fdd733174cbp-51},
      {0x1.8cacf1bbf0f4p+1, 0x1.b649755ba6e9ep+1, 0x1.bea95351351d6p-3, 0.0}};
  for (const auto& x : v) {
    cell.vertices.push_back(Eigen::Vector3d(x[0], x[1], x[2]));
    cell.closures.push_back(x[3]);
  }
  const Eigen::Vector3d centre(0x1.8cad41d93f70ep+1, 0x1.b649a5cbb87c2p+1, 0x1.bea31afcb5f62p-3);
  const NormalLaw law = LinearNormal{10e9};
  const double m = face_radial_normal_moment(std::span<const ClosureCell>(&cell, 1), law, centre);
  double r_max = 0.0, g_max = 0.0;
  for (std::size_t k = 0; k < 5; ++k) {
    r_max = std::max(r_max, (cell.vertices[k] - centre).norm());
    g_max = std::max(g_max, cell.closures[k]);
  }
  Eigen::Vector3d twice_area = Eigen::Vector3d::Zero();
  for (std::size_t k = 1; k + 1 < 5; ++k)
    twice_area +=
        (cell.vertices[k] - cell.vertices[0]).cross(cell.vertices[k + 1] - cell.vertices[0]);
  EXPECT_GE(m, 0.0);
  EXPECT_LE(m, 10e9 * g_max * r_max * 0.5 * twice_area.norm());
  TwistState state;
  TwistIncrement inc;
  inc.radial_normal_moment = m;
  inc.friction_coefficient = 0.8;
  EXPECT_NO_THROW(update_twist(state, inc));
}

}  // namespace
}  // namespace blockdem::test::response_contact_twist
