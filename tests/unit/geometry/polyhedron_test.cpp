// Polyhedron construction and exact mass properties against closed forms.
#include "blockdem/geometry/polyhedron.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "blockdem/geometry/geometry_error.hpp"

namespace blockdem {
namespace {

TEST(Polyhedron, BoxMassPropertiesMatchClosedForm) {
  // Box a x b x c: V = abc, I_xx = V (b² + c²)/12 for unit density.
  const Eigen::Vector3d s(0.3, 0.5, 0.7);
  const Polyhedron p = Polyhedron::box(s);
  const double v = s.prod();
  EXPECT_NEAR(p.volume(), v, 1e-15);
  EXPECT_LT(p.centroid().norm(), 1e-15);
  EXPECT_NEAR(p.unit_inertia()(0, 0), v * (s.y() * s.y() + s.z() * s.z()) / 12, 1e-15);
  EXPECT_NEAR(p.unit_inertia()(1, 1), v * (s.x() * s.x() + s.z() * s.z()) / 12, 1e-15);
  EXPECT_NEAR(p.unit_inertia()(2, 2), v * (s.x() * s.x() + s.y() * s.y()) / 12, 1e-15);
  EXPECT_NEAR(p.unit_inertia()(0, 1), 0.0, 1e-16);
  EXPECT_EQ(p.vertices().size(), 8u);
  EXPECT_EQ(p.faces().size(), 6u);
  for (int f = 0; f < 6; ++f) EXPECT_EQ(p.faces()[f].vertices.size(), 4u);
  EXPECT_NEAR(p.bounding_radius(), 0.5 * s.norm(), 1e-15);
}

TEST(Polyhedron, FacesAreCounterClockwiseAboutOutwardNormal) {
  const Polyhedron p = Polyhedron::box({1, 2, 3});
  for (const auto& f : p.faces()) {
    const auto& v = p.vertices();
    const Eigen::Vector3d n =
        (v[f.vertices[1]] - v[f.vertices[0]]).cross(v[f.vertices[2]] - v[f.vertices[1]]);
    EXPECT_GT(n.dot(p.planes()[f.plane].normal), 0.0);
  }
  double area = 0;
  for (int f = 0; f < 6; ++f) area += p.face_area(f);
  EXPECT_NEAR(area, 2 * (1 * 2 + 2 * 3 + 1 * 3), 1e-12);
}

TEST(Polyhedron, TetrahedronFromVerticesMatchesClosedForm) {
  // Right tetrahedron with legs a, b, c: V = abc/6, centroid (a, b, c)/4,
  // ∫x² dV = V a²/10 about the origin, products ∫xy dV = V ab/20.
  const double a = 1.0, b = 2.0, c = 3.0;
  std::vector<Eigen::Vector3d> pts = {{0, 0, 0}, {a, 0, 0}, {0, b, 0}, {0, 0, c}};
  const Polyhedron p = Polyhedron::from_vertices(pts);
  const double v = a * b * c / 6;
  EXPECT_NEAR(p.volume(), v, 1e-14);
  EXPECT_LT((p.centroid() - Eigen::Vector3d(a, b, c) / 4).norm(), 1e-14);
  // Second moments about the origin, then shifted to the centroid.
  Eigen::Matrix3d m0;
  m0 << a * a, a * b / 2, a * c / 2, a * b / 2, b * b, b * c / 2, a * c / 2, b * c / 2, c * c;
  m0 *= v / 10;
  const Eigen::Vector3d g = p.centroid();
  const Eigen::Matrix3d cov = m0 - v * g * g.transpose();
  const Eigen::Matrix3d inertia = cov.trace() * Eigen::Matrix3d::Identity() - cov;
  EXPECT_LT((p.unit_inertia() - inertia).norm(), 1e-13);
  EXPECT_EQ(p.faces().size(), 4u);
}

TEST(Polyhedron, RotatedTranslatedBoxKeepsMassProperties) {
  const Polyhedron p = Polyhedron::box({0.2, 0.4, 0.6});
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(1.5, -2.0, 0.25);
  const Polyhedron q = p.transformed(r, t);
  EXPECT_NEAR(q.volume(), p.volume(), 1e-14);
  EXPECT_LT((q.centroid() - t).norm(), 1e-13);
  EXPECT_LT((q.unit_inertia() - r * p.unit_inertia() * r.transpose()).norm(), 1e-14);
}

// Every stored value of two shapes, compared bit for bit.
void expect_same_bits(const Polyhedron& a, const Polyhedron& b) {
  ASSERT_EQ(a.planes().size(), b.planes().size());
  for (std::size_t i = 0; i < a.planes().size(); ++i) {
    EXPECT_EQ(a.planes()[i].normal, b.planes()[i].normal);
    EXPECT_EQ(a.planes()[i].offset, b.planes()[i].offset);
  }
  EXPECT_TRUE(std::ranges::equal(a.vertices(), b.vertices()));
  ASSERT_EQ(a.faces().size(), b.faces().size());
  for (std::size_t f = 0; f < a.faces().size(); ++f) {
    EXPECT_EQ(a.faces()[f].plane, b.faces()[f].plane);
    EXPECT_TRUE(std::ranges::equal(a.faces()[f].vertices, b.faces()[f].vertices));
  }
  EXPECT_EQ(a.volume(), b.volume());
  EXPECT_EQ(a.centroid(), b.centroid());
  EXPECT_EQ(a.unit_inertia(), b.unit_inertia());
  EXPECT_EQ(a.bounding_radius(), b.bounding_radius());
}

TEST(Polyhedron, ClosedPlanesGiveTheSameShapeAsTheCheckedPath) {
  // Oracle: from_planes, which also tests for an empty or unbounded set. Random hulls of 5 to 20
  // planes (redundant and near-coplanar planes included), placed off the origin.
  std::mt19937_64 rng(20261126);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const int m = 5 + trial % 16;
    const Eigen::Vector3d centre(3.0 * u(rng), 3.0 * u(rng), 3.0 * u(rng));
    std::vector<Halfspace> planes;
    // A box first, so that every set is closed; then random cuts through points near the box.
    for (int axis = 0; axis < 3; ++axis) {
      for (double sign : {1.0, -1.0}) {
        const Eigen::Vector3d n = sign * Eigen::Vector3d::Unit(axis);
        planes.push_back(Halfspace{n, n.dot(centre) + 0.5 + 0.2 * u(rng)});
      }
    }
    for (int k = 6; k < m; ++k) {
      const Eigen::Vector3d n = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
      planes.push_back(Halfspace{n, n.dot(centre) + 0.3 + 0.3 * u(rng)});
    }
    const Polyhedron checked = Polyhedron::from_planes(planes);
    expect_same_bits(Polyhedron::from_closed_planes(planes), checked);
    // A rigid motion (which takes the unchecked path) against the checked path on its planes.
    const Eigen::Matrix3d r =
        Eigen::AngleAxisd(3.0 * u(rng), Eigen::Vector3d(u(rng), u(rng), 1.0).normalized())
            .toRotationMatrix();
    const Eigen::Vector3d t(u(rng), u(rng), u(rng));
    const Polyhedron moved = checked.transformed(r, t);
    std::vector<Halfspace> moved_planes;
    for (const auto& h : checked.planes()) {
      const Eigen::Vector3d n = (r * h.normal).normalized();
      moved_planes.push_back(Halfspace{n, h.offset + n.dot(t)});
    }
    expect_same_bits(moved, Polyhedron::from_planes(moved_planes));
  }
}

TEST(Polyhedron, RedundantPlanesAreDropped) {
  std::vector<Halfspace> planes = copy_planes(Polyhedron::box({1, 1, 1}));
  planes.push_back(Halfspace{Eigen::Vector3d(1, 1, 0).normalized(), 5.0});  // far away
  planes.push_back(planes[0]);                                              // duplicate
  const Polyhedron p = Polyhedron::from_planes(planes);
  EXPECT_EQ(p.planes().size(), 6u);
  EXPECT_NEAR(p.volume(), 1.0, 1e-14);
}

TEST(Polyhedron, CutCornerPrismHasExactVolume) {
  // Unit cube with the corner x + y > 1.5 cut off: removes a prism of volume 0.5·0.5·0.5/2·... =
  // 0.125.
  std::vector<Halfspace> planes = copy_planes(Polyhedron::box({1, 1, 1}));
  for (auto& h : planes) h.offset += h.normal.dot(Eigen::Vector3d(0.5, 0.5, 0.5));  // cube [0,1]^3
  planes.push_back(Halfspace{Eigen::Vector3d(1, 1, 0).normalized(), 1.5 / std::sqrt(2.0)});
  const Polyhedron p = Polyhedron::from_planes(planes);
  EXPECT_NEAR(p.volume(), 1.0 - 0.5 * 0.5 * 0.5, 1e-14);
  EXPECT_EQ(p.faces().size(), 7u);
}

TEST(Polyhedron, BadShapesAreRejectedWithAClearMessage) {
  auto expect_error = [](auto make, const std::string& words) {
    try {
      make();
      FAIL() << "expected a GeometryError mentioning '" << words << "'";
    } catch (const GeometryError& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  // Unbounded: a box without its top.
  expect_error(
      [] {
        auto planes = copy_planes(Polyhedron::box({1, 1, 1}));
        planes.erase(planes.begin() + 4);
        return Polyhedron::from_planes(planes);
      },
      "unbounded");
  // Empty: x <= -1 and x >= 1.
  expect_error(
      [] {
        auto planes = copy_planes(Polyhedron::box({1, 1, 1}));
        planes.push_back(Halfspace{Eigen::Vector3d::UnitX(), -1.0});
        return Polyhedron::from_planes(planes);
      },
      "empty");
  // Zero volume: a box of zero height.
  expect_error([] { return Polyhedron::box({1, 1, 0}); }, "positive");
  expect_error(
      [] {
        auto planes = copy_planes(Polyhedron::box({1, 1, 1}));
        planes[4].offset = -0.5;  // top plane at z = -0.5 meets the bottom
        return Polyhedron::from_planes(planes);
      },
      "volume");
  // Non-unit and NaN normals.
  expect_error(
      [] {
        auto planes = copy_planes(Polyhedron::box({1, 1, 1}));
        planes[0].normal *= 2.0;
        return Polyhedron::from_planes(planes);
      },
      "unit");
  expect_error(
      [] {
        auto planes = copy_planes(Polyhedron::box({1, 1, 1}));
        planes[0].offset = std::nan("");
        return Polyhedron::from_planes(planes);
      },
      "NaN");
  // Non-convex vertex list: a cube's corners plus its centre.
  expect_error(
      [] {
        std::vector<Eigen::Vector3d> pts;
        for (int i = 0; i < 8; ++i) pts.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
        pts.emplace_back(0.5, 0.5, 0.5);
        return Polyhedron::from_vertices(pts);
      },
      "not convex");
  expect_error(
      [] {
        std::vector<Eigen::Vector3d> pts = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
        return Polyhedron::from_vertices(pts);
      },
      "flat");
}

TEST(Polyhedron, CopiesShareTheShapeAndAMovedFromPolyhedronKeepsIt) {
  // A polyhedron is immutable: a copy (or a move) refers to the same planes, vertices and faces.
  const Eigen::Vector3d s(0.3, 0.5, 0.7);
  Polyhedron p = Polyhedron::box(s);
  const Polyhedron copy = p;
  EXPECT_TRUE(copy.shares_data_with(p));
  EXPECT_EQ(copy.vertices().data(), p.vertices().data());
  const Polyhedron moved = std::move(p);
  EXPECT_TRUE(moved.shares_data_with(copy));
  EXPECT_NEAR(p.volume(), s.prod(), 1e-15);  // NOLINT(bugprone-use-after-move): still usable
  // Built separately from the same planes: equal, not shared.
  const Polyhedron other = Polyhedron::box(s);
  EXPECT_FALSE(other.shares_data_with(copy));
  EXPECT_TRUE(std::ranges::equal(other.vertices(), copy.vertices()));
  // The default polyhedron is empty.
  const Polyhedron empty;
  EXPECT_TRUE(empty.planes().empty());
  EXPECT_EQ(empty.volume(), 0.0);
  // A copy outlives the shape it came from (its record is freed with the last copy, which the
  // sanitizer builds check), and an assignment lets go of what it held.
  auto first = std::make_unique<Polyhedron>(Polyhedron::box(s));
  Polyhedron kept = *first;
  const std::vector<Eigen::Vector3d> corners(first->vertices().begin(), first->vertices().end());
  first.reset();
  EXPECT_TRUE(std::ranges::equal(kept.vertices(), corners));
  EXPECT_EQ(kept.faces().size(), 6u);
  EXPECT_EQ(kept.faces()[0].vertices.size(), 4u);
  EXPECT_NEAR(kept.volume(), s.prod(), 1e-15);
  const Polyhedron& self = kept;
  kept = self;  // assigning a shape to itself keeps it
  EXPECT_NEAR(kept.volume(), s.prod(), 1e-15);
  kept = empty;
  EXPECT_TRUE(kept.vertices().empty());
  EXPECT_TRUE(kept.shares_data_with(empty));
}

}  // namespace
}  // namespace blockdem
