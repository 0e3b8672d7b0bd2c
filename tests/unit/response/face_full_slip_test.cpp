// Full slip of a square contact about an instantaneous centre (face_full_slip) against closed
// forms and an independent fine-grid oracle, the closure's polar moments
// (face_closure_polar_moments), and the state's instantaneous centre (slip_centre) and the slip
// test (exceeds_full_slip, certified_inside) of contact/shear_twist.hpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "blockdem/response/face_twist.hpp"
#include "square_cells.hpp"

// A namespace of this file's own: the unity build (cmake/build_speed.cmake) compiles it together
// with other test files that define helpers of the same names.
namespace blockdem::test::response_face_full_slip {
namespace {

constexpr double kSide = 0.046;                    // square side a (m)
constexpr double kClosure = 1e-5;                  // uniform closure (m)
constexpr double kStiffness = 1e10;                // k_n (Pa/m)
constexpr double kStress = kStiffness * kClosure;  // σ_n (Pa)
const Eigen::Vector3d kNormal = Eigen::Vector3d::UnitZ();
const Eigen::Vector3d kCentre(kSide / 2, kSide / 2, 0.0);

// The square [0, a]² at z = 0 as two cells, the closure g(x) = g0 + slope x (linear over the
// square; uniform by default).
FaceContactGeometry square_cells(double g0 = kClosure, double slope = 0.0) {
  return test::square_cells(kSide, g0, slope);
}

SlipCentre centre_at(const Eigen::Vector3d& p, double sense) {
  SlipCentre c;
  c.translation = false;
  c.point = p;
  c.sense = sense;
  return c;
}

// The oracle: the midpoint rule on an N x N grid of the square, written out independently of
// the quadrature (traction -σ ŵ, ŵ the unit of s n × (y - p)), for the stress σ(y) (Pa); about
// 1e-5 relative at N = 800.
template <class Stress>
FullSlip grid_full_slip(const Eigen::Vector3d& p, double sense, Stress&& stress, int n = 800) {
  FullSlip s;
  const double h = kSide / n;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const Eigen::Vector3d y((i + 0.5) * h, (j + 0.5) * h, 0.0);
      const Eigen::Vector3d d = y - p;
      const Eigen::Vector3d w = sense * Eigen::Vector3d(-d.y(), d.x(), 0.0);
      const double sigma = stress(y);
      const Eigen::Vector3d t = sigma * h * h * w / w.norm();
      s.force -= t;
      s.moment -= (y - kCentre).x() * t.y() - (y - kCentre).y() * t.x();
      s.power += sigma * h * h * w.norm();
    }
  }
  return s;
}

FullSlip grid_full_slip(const Eigen::Vector3d& p, double sense) {
  return grid_full_slip(p, sense, [](const Eigen::Vector3d&) { return kStress; });
}

// Full slip about the square's centre is a pure twist: no force (1e-9 of σ A, by symmetry) and
// the moment σ ∫ r dA = σ a³ (√2 + ln(1 + √2))/6 against the turn (2e-4: the rule's error at
// the centre, where r has a kink), equal to the power of the unit turn.
TEST(FaceFullSlip, AboutTheCentreIsThePureTwistLimit) {
  const FaceContactGeometry fc = square_cells();
  const LinearNormal law{kStiffness};
  const double radial =
      kStress * std::pow(kSide, 3) * (std::numbers::sqrt2 + std::log(1 + std::numbers::sqrt2)) / 6;
  for (const double sense : {1.0, -1.0}) {
    const FullSlip s = face_full_slip(fc.cells, law, kNormal, kCentre, centre_at(kCentre, sense));
    EXPECT_LT(s.force.norm(), 1e-9 * kStress * kSide * kSide);
    EXPECT_NEAR(s.moment, -sense * radial, 2e-4 * radial);
    EXPECT_NEAR(s.power, radial, 2e-4 * radial);
  }
}

// A centre far away (D = 1e4 a) is a translation: |F| = σ A against the slip (1e-6 of σ A),
// and the moment about the centre of pressure is the slip lines' curvature over the square,
// σ a⁴ / (12 D) to first order in a / D (1%). Reference: Coulomb's law for a uniform slip.
TEST(FaceFullSlip, AFarCentreIsTheTranslationLimit) {
  const FaceContactGeometry fc = square_cells();
  const LinearNormal law{kStiffness};
  const double limit = kStress * kSide * kSide, distance = 1e4 * kSide;
  // Centre on -y far away, turning +z: B slips along -x, the traction on B along +x.
  const Eigen::Vector3d p = kCentre - Eigen::Vector3d(0, distance, 0);
  const FullSlip s = face_full_slip(fc.cells, law, kNormal, kCentre, centre_at(p, 1.0));
  EXPECT_NEAR(s.force.x(), limit, 1e-6 * limit);
  EXPECT_NEAR(s.force.y(), 0.0, 1e-6 * limit);
  const double curvature = kStress * std::pow(kSide, 4) / (12.0 * distance);
  EXPECT_NEAR(std::abs(s.moment), curvature, 0.01 * curvature);
}

// Centres inside, on the edge of and outside the square, both senses: force and moment of the
// instantaneous-centre solution against the fine-grid oracle, within 3e-3 of σ A and σ A a (the
// slip direction jumps at a centre inside the square: the rule is about 2e-3 there);
// and the power is the maximum-power identity -(F · v + M s) at the slip rate (1e-12).
TEST(FaceFullSlip, MatchesTheInstantaneousCentreOracle) {
  const FaceContactGeometry fc = square_cells();
  const LinearNormal law{kStiffness};
  const double limit = kStress * kSide * kSide;
  for (const Eigen::Vector3d& offset :
       {Eigen::Vector3d(0.3, 0.1, 0), Eigen::Vector3d(-0.2, 0.45, 0), Eigen::Vector3d(0.5, 0, 0),
        Eigen::Vector3d(1.5, -0.7, 0)}) {
    for (const double sense : {1.0, -1.0}) {
      const Eigen::Vector3d p = kCentre + kSide * offset;
      const FullSlip s = face_full_slip(fc.cells, law, kNormal, kCentre, centre_at(p, sense));
      const FullSlip o = grid_full_slip(p, sense);
      EXPECT_NEAR(s.force.x(), o.force.x(), 3e-3 * limit) << offset.transpose();
      EXPECT_NEAR(s.force.y(), o.force.y(), 3e-3 * limit) << offset.transpose();
      EXPECT_NEAR(s.moment, o.moment, 3e-3 * limit * kSide) << offset.transpose();
      const Eigen::Vector3d v = sense * kNormal.cross(kCentre - p);
      EXPECT_NEAR(-(s.force.dot(v) + s.moment * sense), s.power, 1e-12 * s.power);
    }
  }
}

// The centres of the test above for a stress that is not uniform, against the oracle with the
// same stress, each case of the integration: the linear law with the closure rising from 0 to
// 2 kClosure across the square (a partly open joint; the closed forms, exact), the exponential
// law at a uniform closure (its chord is exact), and the exponential law by its radial closed
// forms and Gauss-Legendre in angle: the closure rising from 0 to 2 kClosure and to
// 5 kClosure across the square (b Δg = 1.5 and 3.7, partly open) and a closed joint at
// 10 kClosure whose closure varies by 1e-7 m (b g = 7.4: too curved for the chord): all within
// 2e-5 of σ A and σ A a (the oracle's error, about 1e-5). σ A is the oracle's normal force. The
// power is the maximum-power identity (1e-12).
TEST(FaceFullSlip, MatchesTheOracleUnderAVaryingStress) {
  struct Case {
    NormalLaw law;
    double g0, slope, tolerance;
  };
  const ExponentialNormal exponential = ExponentialNormal::eq3();
  const std::vector<Case> cases{{LinearNormal{kStiffness}, 0.0, 2 * kClosure / kSide, 2e-5},
                                {exponential, kClosure, 0.0, 2e-5},
                                {exponential, 0.0, 2 * kClosure / kSide, 2e-5},
                                {exponential, 0.0, 5 * kClosure / kSide, 2e-5},
                                {exponential, 10 * kClosure, 1e-7 / kSide, 2e-5}};
  for (const Case& c : cases) {
    const FaceContactGeometry fc = square_cells(c.g0, c.slope);
    const auto stress = [&](const Eigen::Vector3d& y) {
      return normal_stress(c.law, c.g0 + c.slope * y.x());
    };
    const double limit = grid_full_slip(kCentre + Eigen::Vector3d(0, 1e4 * kSide, 0), 1.0, stress)
                             .force.norm();  // F_n = ∫ σ dA: a translation's |F|
    for (const Eigen::Vector3d& offset :
         {Eigen::Vector3d(0.3, 0.1, 0), Eigen::Vector3d(-0.2, 0.45, 0), Eigen::Vector3d(0.5, 0, 0),
          Eigen::Vector3d(1.5, -0.7, 0), Eigen::Vector3d(0, 0, 0)}) {
      for (const double sense : {1.0, -1.0}) {
        const Eigen::Vector3d p = kCentre + kSide * offset;
        const FullSlip s = face_full_slip(fc.cells, c.law, kNormal, kCentre, centre_at(p, sense));
        const FullSlip o = grid_full_slip(p, sense, stress);
        const double tol = c.tolerance * limit;
        EXPECT_NEAR(s.force.x(), o.force.x(), tol) << c.slope << " " << offset.transpose();
        EXPECT_NEAR(s.force.y(), o.force.y(), tol) << c.slope << " " << offset.transpose();
        EXPECT_NEAR(s.moment, o.moment, tol * kSide) << c.slope << " " << offset.transpose();
        EXPECT_NEAR(s.power, o.power, tol * kSide) << c.slope << " " << offset.transpose();
        const Eigen::Vector3d v = sense * kNormal.cross(kCentre - p);
        EXPECT_NEAR(-(s.force.dot(v) + s.moment * sense), s.power, 1e-12 * s.power);
      }
    }
  }
}

// The force within `tol` and the moment within `tol` times `diameter` (centre p, for the trace).
void expect_slip_near(const FullSlip& got, const FullSlip& want, double tol, double diameter,
                      const Eigen::Vector3d& p) {
  EXPECT_NEAR(got.force.x(), want.force.x(), tol) << p.transpose();
  EXPECT_NEAR(got.force.y(), want.force.y(), tol) << p.transpose();
  EXPECT_NEAR(got.moment, want.moment, tol * diameter) << p.transpose();
}

// A pentagon 5.5 cm across whose closure rises with the gradient (1.2e-3, 0.5e-3) from `offset`
// at its last vertex; `doubled`: a second vertex 1e-17 m from the second one along its next edge
// (as the clipping can leave).
ClosureCell pentagon(double offset, bool doubled = false) {
  const Eigen::Vector2d gradient(1.2e-3, 0.5e-3);  // closure gradient (-)
  const std::array<Eigen::Vector2d, 5> corners{
      {{0.0, 0.0}, {0.04, -0.005}, {0.05, 0.03}, {0.02, 0.045}, {-0.01, 0.025}}};
  ClosureCell cell;
  const auto add = [&](const Eigen::Vector2d& c) {
    cell.vertices.push_back(Eigen::Vector3d(c.x(), c.y(), 0.0));
    cell.closures.push_back(gradient.dot(c - corners[4]) + offset);
  };
  for (std::size_t i = 0; i < corners.size(); ++i) {
    add(corners[i]);
    if (doubled && i == 1) add(corners[1] + 1e-17 * (corners[2] - corners[1]).normalized());
  }
  return cell;
}

// The exponential law over a partly open pentagon (closure 0 at one vertex, b Δg = 5.6 across)
// by its closed forms against the rule alone (face_full_slip_by_rule) with the centre outside
// the cell, where the slip direction is smooth over it: near a vertex, beside another (the chord
// between the tangent vertices splits the cell unevenly), beyond the largest closure (where the
// stress extrapolated to the centre would be 8 times the cell's largest) and 30 diameters away;
// both senses. Within 5e-6 of F_n and F_n D (D the diameter), the power within 5e-6 of itself:
// the rule's error here (up to 3.1e-6 measured; the closed forms move by less than 1e-9 of F_n
// when their Gauss-Legendre pieces are made five times narrower).
TEST(FaceFullSlip, ExponentialClosedFormsMatchTheRuleOutsideTheCell) {
  const ExponentialNormal law = ExponentialNormal::eq3();
  ClosureCell cell = pentagon(0.0125e-3);
  double low = cell.closures[0];
  for (const double g : cell.closures) low = std::min(low, g);
  for (double& g : cell.closures) g -= low;  // 0 at the lowest vertex
  const std::vector<ClosureCell> cells{cell};
  const Eigen::Vector3d xp(0.02, 0.02, 0.0);
  const double diameter = 0.055;
  const double normal_force =
      std::abs(face_full_slip_by_rule(cells, law, kNormal, xp,
                                      centre_at(xp + Eigen::Vector3d(0, 1e4, 0), 1.0))
                   .force.x());
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(0.045, -0.01, 0), Eigen::Vector3d(-0.02, -0.004, 0),
        Eigen::Vector3d(0.07, 0.04, 0), Eigen::Vector3d(0.03, 0.06, 0),
        Eigen::Vector3d(-1.0, 1.3, 0)}) {
    for (const double sense : {1.0, -1.0}) {
      const FullSlip s = face_full_slip(cells, law, kNormal, xp, centre_at(p, sense));
      const FullSlip r = face_full_slip_by_rule(cells, law, kNormal, xp, centre_at(p, sense));
      expect_slip_near(s, r, 5e-6 * normal_force, diameter, p);
      EXPECT_NEAR(s.power, r.power, 5e-6 * r.power) << p.transpose();
    }
  }
}

// A vertex doubled by the clipping (a second one 1e-17 m along the next edge) leaves an edge
// whose span in the angle about the centre is below the angle's round-off: full slip is that of
// the cell without it (5e-6 of the normal force, as against the rule above), for centres inside,
// outside, on a vertex and near the doubled one.
TEST(FaceFullSlip, ADoubledVertexLeavesFullSlipAsItWas) {
  const ExponentialNormal law = ExponentialNormal::eq3();
  const double offset = 0.0125e-3 - 0.06e-3;  // partly open
  const std::vector<ClosureCell> one{pentagon(offset)}, two{pentagon(offset, true)};
  const Eigen::Vector3d xp(0.02, 0.02, 0.0);
  const double diameter = 0.055;
  const double normal_force = std::abs(
      face_full_slip_by_rule(one, law, kNormal, xp, centre_at(xp + Eigen::Vector3d(0, 1e4, 0), 1.0))
          .force.x());
  ASSERT_GT(normal_force, 0.0);
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(0.045, -0.01, 0), Eigen::Vector3d(-0.02, -0.004, 0),
        Eigen::Vector3d(0.07, 0.04, 0), Eigen::Vector3d(0.03, 0.06, 0),
        Eigen::Vector3d(0.02, 0.01, 0), Eigen::Vector3d(0.04, -0.005, 0),
        Eigen::Vector3d(0.04 + 1e-3, -0.005 + 1e-3, 0), Eigen::Vector3d(-1.0, 1.3, 0)}) {
    for (const double sense : {1.0, -1.0}) {
      const FullSlip a = face_full_slip(one, law, kNormal, xp, centre_at(p, sense));
      const FullSlip b = face_full_slip(two, law, kNormal, xp, centre_at(p, sense));
      expect_slip_near(b, a, 5e-6 * normal_force, diameter, p);
    }
  }
}

// Centres far away on both sides of the distance beyond which the cells are integrated by the
// rule rather than the closed forms (1e3 cell diameters; the cells here are 1.12 a across):
// D = 300 a and 3000 a, both the translation limit |F| = σ A (1e-6) and the slip lines'
// curvature moment σ a⁴ / (12 D) (1%; the first-order term's error is (a / D)²).
TEST(FaceFullSlip, FarCentresOnBothSidesOfTheRuleSwitch) {
  const FaceContactGeometry fc = square_cells();
  const LinearNormal law{kStiffness};
  const double limit = kStress * kSide * kSide;
  for (const double distance : {300 * kSide, 3000 * kSide}) {
    const Eigen::Vector3d p = kCentre - Eigen::Vector3d(0, distance, 0);
    const FullSlip s = face_full_slip(fc.cells, law, kNormal, kCentre, centre_at(p, 1.0));
    EXPECT_NEAR(s.force.x(), limit, 1e-6 * limit) << distance;
    EXPECT_NEAR(s.force.y(), 0.0, 1e-6 * limit) << distance;
    const double curvature = kStress * std::pow(kSide, 4) / (12.0 * distance);
    EXPECT_NEAR(std::abs(s.moment), curvature, 0.01 * curvature) << distance;
  }
}

// A sliver cell (a contact edge-on: its vertices on one line up to 3e-16 m, three of them at one
// point with different closures, as the clipping can leave) has no area: full slip about a
// centre 300 cell diameters away adds nothing, within 1e-9 of σ a² (a gradient taken from such a
// cell and carried to the centre once gave 1e3 N here).
TEST(FaceFullSlip, ASliverCellAddsNothing) {
  const LinearNormal law{1e10};
  ClosureCell cell;
  const double x0 = 0.04600055086750332, x1 = 0.092000550867503278;
  const std::array<std::array<double, 3>, 5> points{
      {{x0, 0.045999902561941329, 1.1641532182693481e-10},
       {x0, 0.045999902561941003, 1.6763806343078613e-08},
       {x0, 0.045999902561940975, 1.8393620848655701e-08},
       {x1, 0.045999902825164619, 1.8393620848655701e-08},
       {x1, 0.045999902825164973, 1.1641532182693481e-10}}};
  for (const auto& [x, y, g] : points) {
    cell.vertices.push_back(Eigen::Vector3d(x, y, 0.0));
    cell.closures.push_back(g);
  }
  const std::vector<ClosureCell> cells{cell};
  const double scale = law.stiffness * 1.8393620848655701e-08 * kSide * kSide;
  const Eigen::Vector3d p(2.5786661204971182, 14.095128565041286, 0.0);
  const FullSlip s =
      face_full_slip(cells, law, kNormal, Eigen::Vector3d(x0, 0.046, 0), centre_at(p, 1.0));
  EXPECT_LT(s.force.norm(), 1e-9 * scale);
  EXPECT_LT(std::abs(s.power), 1e-9 * scale * 15.0);
  EXPECT_LT(
      std::abs(face_twist_moments(cells, law, Eigen::Vector3d(x0, 0.046, 0)).radial_normal_moment),
      1e-9 * scale * kSide);
}

// A cell barely closed (0.05 m by 0.01 m at x = 0.45 m, its closure rising from 1e-9 m to
// 2e-9 m along it) whose closures carry the round-off of a difference of plane offsets there,
// (X + g) - X, one of them one ulp of X = 5.6e-17 m off: the vertices then disagree with one
// plane by 3e-8 of the largest closure, beyond the former 1e-9, though only by round-off. The
// closed forms apply (linear_slip_sums' tolerance counts the round-off of the coordinates): full
// slip about a centre inside the cell equals that of the same cell at the origin with exact
// closures to 1e-6 of F_n and F_n L (the rule, with the centre inside, errs by some 1e-3; the
// round-off itself moves the sums by about 1e-7).
TEST(FaceFullSlip, ClosuresPlanarToRoundOffTakeTheClosedForms) {
  const LinearNormal law{kStiffness};
  const double x0 = 0.45, length = 0.05, width = 0.01;
  const auto cell_at = [&](double origin, bool rounded) {
    ClosureCell cell;
    for (const auto& [x, y] : {std::pair{0.0, 0.0}, {length, 0.0}, {length, width}, {0.0, width}}) {
      const double g = 1e-9 + 2e-8 * x + 3e-9 * y;
      cell.vertices.push_back(Eigen::Vector3d(origin + x, y, 0.0));
      cell.closures.push_back(rounded ? (origin + g) - origin : g);
    }
    if (rounded) cell.closures[2] = std::nextafter(origin + cell.closures[2], 1.0) - origin;
    return std::vector<ClosureCell>{cell};
  };
  const std::vector<ClosureCell> far = cell_at(x0, true), exact = cell_at(0.0, false);
  const auto& g = far[0].closures;
  ASSERT_GT(std::abs(g[0] - g[1] + g[2] - g[3]), 1e-9 * g[2]);  // zero for a plane
  const Eigen::Vector3d p(0.3 * length, 0.4 * width, 0.0), shift(x0, 0.0, 0.0);
  const double normal_force = kStiffness * 1.5e-9 * length * width;
  for (const double sense : {1.0, -1.0}) {
    const FullSlip a = face_full_slip(far, law, kNormal, shift, centre_at(p + shift, sense));
    const FullSlip b =
        face_full_slip(exact, law, kNormal, Eigen::Vector3d::Zero(), centre_at(p, sense));
    EXPECT_NEAR(a.force.x(), b.force.x(), 1e-6 * normal_force);
    EXPECT_NEAR(a.force.y(), b.force.y(), 1e-6 * normal_force);
    EXPECT_NEAR(a.moment, b.moment, 1e-6 * normal_force * length);
    EXPECT_NEAR(a.power, b.power, 1e-6 * normal_force * length);
  }
}

// A regular 12-gon 6 cm across (more vertices than the kernels keep inline) whose closure is
// g0 + gradient · (y - y0), y0 its lowest vertex: `repeat` >= 0 writes vertex `repeat` twice (an
// edge of zero length, as the clipping can leave).
ClosureCell dodecagon(double g0, const Eigen::Vector2d& gradient, int repeat = -1) {
  constexpr int kSides = 12;
  const Eigen::Vector2d centre(0.02, 0.02);
  std::array<Eigen::Vector2d, kSides> corners;
  for (int k = 0; k < kSides; ++k) {
    const double angle = 2.0 * std::numbers::pi * (k + 0.25) / kSides;
    corners[static_cast<std::size_t>(k)] =
        centre + 0.03 * Eigen::Vector2d(std::cos(angle), std::sin(angle));
  }
  double lowest = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& c : corners) lowest = std::min(lowest, gradient.dot(c));
  ClosureCell cell;
  for (int k = 0; k < kSides; ++k) {
    const Eigen::Vector2d& c = corners[static_cast<std::size_t>(k)];
    for (int copy = 0; copy < (k == repeat ? 2 : 1); ++copy) {
      cell.vertices.push_back(Eigen::Vector3d(c.x(), c.y(), 0.0));
      cell.closures.push_back(g0 + gradient.dot(c) - lowest);
    }
  }
  return cell;
}

// The exponential law over many-sided cells, against the rule alone with the centre outside the
// cell (where the slip direction is smooth over it, as above):
// - partly open (closure 0 at the lowest vertex, b Δg = 6.5 across): the closed forms, with more
//   edges than their inline storage; the same cell with a vertex written twice gives the same
//   full slip;
// - nearly uniform (b Δg = 2e-6): the stress's chord, within 1e-6 of the largest stress, and the
//   closed forms of a linear stress.
// Within 5e-6 of F_n and F_n D (D the diameter), the power within 5e-6 of itself. And a triangle
// whose stress is strongly curved (b Δg = 12) seen from 2 mm beside an edge: its closed forms
// would take more Gauss-Legendre pieces than the rule has points, so it is left to the rule (the
// same result, to round-off).
TEST(FaceFullSlip, ManySidedCellsMatchTheRule) {
  const ExponentialNormal law = ExponentialNormal::eq3();
  const Eigen::Vector3d xp(0.02, 0.02, 0.0);
  const double diameter = 0.06;
  struct Case {
    const char* name;
    ClosureCell cell;
    Eigen::Vector3d centre;
  };
  const Eigen::Vector2d open(1.2e-3, 0.5e-3), even(0.4e-9, 0.2e-9);
  const std::vector<Case> cases{
      {"partly open", dodecagon(0.0, open), Eigen::Vector3d(0.06, -0.01, 0)},
      {"partly open, a vertex twice", dodecagon(0.0, open, 4), Eigen::Vector3d(0.06, -0.01, 0)},
      {"partly open", dodecagon(0.0, open), Eigen::Vector3d(-1.0, 1.3, 0)},
      {"partly open, a vertex twice", dodecagon(0.0, open, 4), Eigen::Vector3d(-1.0, 1.3, 0)},
      {"nearly uniform", dodecagon(2e-5, even), Eigen::Vector3d(0.07, 0.04, 0)},
      {"nearly uniform", dodecagon(2e-5, even), Eigen::Vector3d(0.03, -0.03, 0)}};
  for (const Case& c : cases) {
    const std::vector<ClosureCell> cells{c.cell};
    const double normal_force =
        std::abs(face_full_slip_by_rule(cells, law, kNormal, xp,
                                        centre_at(xp + Eigen::Vector3d(0, 1e4, 0), 1.0))
                     .force.x());
    ASSERT_GT(normal_force, 0.0) << c.name;
    for (const double sense : {1.0, -1.0}) {
      SCOPED_TRACE(std::string(c.name) + ", sense " + std::to_string(sense));
      const FullSlip s = face_full_slip(cells, law, kNormal, xp, centre_at(c.centre, sense));
      const FullSlip r =
          face_full_slip_by_rule(cells, law, kNormal, xp, centre_at(c.centre, sense));
      expect_slip_near(s, r, 5e-6 * normal_force, diameter, c.centre);
      EXPECT_NEAR(s.power, r.power, 5e-6 * r.power) << c.centre.transpose();
    }
  }
  ClosureCell triangle;
  for (const auto& [x, y] : {std::pair{0.0, 0.0}, {0.05, 0.0}, {0.025, 0.04}}) {
    triangle.vertices.push_back(Eigen::Vector3d(x, y, 0.0));
    triangle.closures.push_back(3.2e-3 * x);
  }
  const std::vector<ClosureCell> cells{triangle};
  const Eigen::Vector3d beside(0.025, -0.002, 0.0);
  for (const double sense : {1.0, -1.0}) {
    const FullSlip s = face_full_slip(cells, law, kNormal, xp, centre_at(beside, sense));
    const FullSlip r = face_full_slip_by_rule(cells, law, kNormal, xp, centre_at(beside, sense));
    expect_slip_near(s, r, 1e-12 * r.force.norm(), diameter, beside);
    EXPECT_NEAR(s.power, r.power, 1e-12 * r.power);
  }
}

// The closed forms of ∫ r² dA and ∫ g r² dA (face_closure_polar_moments) on the square about
// its corner, with the closure g = g0 + slope x: ∫ r² dA = 2 a⁴ / 3 and
// ∫ g r² dA = g0 2 a⁴ / 3 + slope (a⁵ / 4 + a⁵ / 6) (∫ x³ + ∫ x y² over the square); round-off,
// 1e-12 relative.
TEST(ClosurePolarMoments, SquareAboutACorner) {
  const double slope = 2 * kClosure / kSide;
  const FaceContactGeometry fc = square_cells(kClosure, slope);
  const ClosurePolarMoments m = face_closure_polar_moments(fc.cells, Eigen::Vector3d::Zero());
  const double polar = 2 * std::pow(kSide, 4) / 3;
  const double closure_polar = kClosure * polar + slope * 5 * std::pow(kSide, 5) / 12;
  EXPECT_NEAR(m.polar_moment, polar, 1e-12 * polar);
  EXPECT_NEAR(m.closure_polar_moment, closure_polar, 1e-12 * closure_polar);
}

// The state's instantaneous centre: the affine field u0 + θ n × (y - x_p) with F = -k_s A u0,
// M = -k_s J θ vanishes at p (1e-12 of a), whatever k_s; M = 0 is a translation.
TEST(ShearTwistKernel, SlipCentreIsWhereTheAffineFieldVanishes) {
  const double ks = 1e9, area = kSide * kSide, polar = std::pow(kSide, 4) / 6;
  const Eigen::Vector3d u0(2e-6, -1e-6, 0);
  const double theta = 3e-4;
  const Eigen::Vector3d force = -ks * area * u0;
  const double moment = -ks * polar * theta;
  const SlipCentre c = slip_centre(force, moment, kNormal, kCentre, polar, area, kSide);
  ASSERT_FALSE(c.translation);
  const Eigen::Vector3d u = u0 + theta * kNormal.cross(c.point - kCentre);
  EXPECT_LT(u.norm() / theta, 1e-12 * kSide);
  EXPECT_EQ(c.sense, 1.0);  // θ > 0
  EXPECT_TRUE(slip_centre(force, 0.0, kNormal, kCentre, polar, area, kSide).translation);
}

// The slip test on the square: a pure force up to μ σ A, or a pure moment up to μ σ ∫ r dA, is
// carried (and a little more is not); a state certified inside is carried by the exact test too.
TEST(ShearTwistKernel, SlipTestReducesToTheSeparateLimits) {
  const FaceContactGeometry fc = square_cells();
  const LinearNormal law{kStiffness};
  const double mu = 0.8, area = kSide * kSide, polar = std::pow(kSide, 4) / 6;
  const double force_limit = mu * kStress * area;
  const double radial =
      kStress * std::pow(kSide, 3) * (std::numbers::sqrt2 + std::log(1 + std::numbers::sqrt2)) / 6;
  const auto exceeds = [&](const Eigen::Vector3d& f, double m) {
    const SlipCentre c = slip_centre(f, m, kNormal, kCentre, polar, area, kSide);
    const FullSlip s = face_full_slip(fc.cells, law, kNormal, kCentre, c);
    return exceeds_full_slip(f, m, c, kCentre, kNormal, s, mu);
  };
  // Nearly a pure force (the moment 1e-4 of the limit: the centre some 4000 a away) and nearly a
  // pure moment.
  const double tiny = 1e-4 * mu * radial;
  EXPECT_FALSE(exceeds(Eigen::Vector3d(0.99 * force_limit, 0, 0), tiny));
  EXPECT_TRUE(exceeds(Eigen::Vector3d(1.01 * force_limit, 0, 0), tiny));
  EXPECT_FALSE(exceeds(Eigen::Vector3d(1e-9 * force_limit, 0, 0), 0.99 * mu * radial));
  EXPECT_TRUE(exceeds(Eigen::Vector3d(1e-9 * force_limit, 0, 0), -1.01 * mu * radial));
  // Half of each: outside the pointwise limit (the joint cannot carry both), though inside the
  // box of the separate caps.
  EXPECT_TRUE(exceeds(Eigen::Vector3d(0, 0.8 * force_limit, 0), 0.8 * mu * radial));
  // The certificate |F|/(μ F_n) + 2|M|/M_c <= 1 with M_c = μ σ ∫ r dA (x_p = c).
  EXPECT_TRUE(certified_inside(0.5 * force_limit, 0.24 * mu * radial, force_limit, mu * radial));
  EXPECT_FALSE(exceeds(Eigen::Vector3d(0.5 * force_limit, 0, 0), 0.24 * mu * radial));
  EXPECT_FALSE(certified_inside(0.5 * force_limit, 0.26 * mu * radial, force_limit, mu * radial));
}

}  // namespace
}  // namespace blockdem::test::response_face_full_slip
