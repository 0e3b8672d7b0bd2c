// The water's load on polygons and blocks below a water table: Archimedes' buoyancy ρ_w g V for a
// block wholly or partly below a level table (exact to round-off), the exact polygon resultant
// against a fine midpoint quadrature (the slow, obviously right oracle), and the water table
// surfaces through points (a plane through three points, continuity across the pieces).
#include "blockdem/response/water_pressure.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "blockdem/geometry/polygon_moments.hpp"

namespace blockdem::test::response_water_pressure {
namespace {

constexpr double kG = 9.81;

GroundWater level_table(double z, double density = 1000.0) {
  return GroundWater{WaterTable::plane({0.0, 0.0, z}, {0.0, 0.0, 1.0}), density};
}

// Archimedes: a box wholly below a level table feels ρ_w g V upward through its centroid, at any
// orientation (the pressure's resultant over a closed surface, -∮ p n dA = -∫ ∇p dV).
TEST(WaterPressure, BuoyancyOfASubmergedBlockIsRhoGV) {
  const Polyhedron box = Polyhedron::box({2.0, 1.0, 0.5});
  const GroundWater water = level_table(10.0);
  for (const double angle : {0.0, 0.3, 1.1}) {
    const Eigen::Matrix3d r =
        Eigen::AngleAxisd(angle, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
    const Eigen::Vector3d at(3.0, -2.0, 5.0);
    const WaterLoad load = block_water_load(water, kG, box, r, at);
    const double buoyancy = 1000.0 * kG * box.volume();
    EXPECT_NEAR(load.force.z(), buoyancy, 1e-12 * buoyancy) << angle;
    EXPECT_NEAR(load.force.head<2>().norm(), 0.0, 1e-12 * buoyancy) << angle;
    EXPECT_NEAR(load.torque.norm(), 0.0, 1e-12 * buoyancy) << angle;
    EXPECT_NEAR(load.wetted_area, 2 * (2.0 + 1.0 + 0.5), 1e-12);
  }
}

// Partly below: the buoyancy of the submerged part, ρ_w g V_sub, through its centroid: a box
// 2 × 1 × 0.5 m standing in water 0.2 m above its base has V_sub = 0.4 m³ at z = 0.1 m above
// its base, so the moment about the box's centroid is zero (the centroids lie on one vertical).
TEST(WaterPressure, BuoyancyOfAFloatingBlockIsRhoGVSubmerged) {
  const Polyhedron box = Polyhedron::box({2.0, 1.0, 0.5});
  const GroundWater water = level_table(0.2, 1025.0);
  const WaterLoad load =
      block_water_load(water, kG, box, Eigen::Matrix3d::Identity(), {0.0, 0.0, 0.25});
  const double buoyancy = 1025.0 * kG * 2.0 * 1.0 * 0.2;
  EXPECT_NEAR(load.force.z(), buoyancy, 1e-12 * buoyancy);
  EXPECT_NEAR(load.force.head<2>().norm(), 0.0, 1e-12 * buoyancy);
  EXPECT_NEAR(load.torque.norm(), 0.0, 1e-12 * buoyancy);
  // Above the table: nothing.
  const WaterLoad dry =
      block_water_load(water, kG, box, Eigen::Matrix3d::Identity(), {0.0, 0.0, 0.5});
  EXPECT_EQ(dry.force, Eigen::Vector3d::Zero());
  EXPECT_EQ(dry.wetted_area, 0.0);
}

// The exact resultant of a polygon cut by an inclined table against a midpoint quadrature over
// a fine grid of its plane: cells kept by their centres, whose error is of the order of the cell
// size along the edges (relative agreement 1e-3 at 800 × 800 cells of 3 mm).
TEST(WaterPressure, PolygonResultantMatchesQuadrature) {
  const GroundWater water{WaterTable::plane({0.0, 0.0, 1.0}, {0.2, -0.1, 1.0}), 1000.0};
  // A quadrilateral in a tilted plane, crossing the table.
  const Eigen::Vector3d n = Eigen::Vector3d(0.3, 0.4, 0.8).normalized();
  const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
  const Eigen::Vector3d o(0.5, 0.2, 0.8);
  const std::vector<Eigen::Vector2d> plan = {{-1.0, -0.8}, {1.2, -0.6}, {0.9, 1.1}, {-0.7, 0.9}};
  std::vector<Eigen::Vector3d> polygon;
  for (const auto& q : plan) polygon.push_back(o + q.x() * u + q.y() * v);
  const Eigen::Vector3d about(0.1, 0.0, 0.3);
  const WaterLoad exact = polygon_water_load(water, kG, polygon, n, about);
  // The oracle: cells of the bounding square, kept where their centre is inside the polygon.
  const int cells = 800;
  const double lo = -1.2, hi = 1.2, h = (hi - lo) / cells;
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
  for (int i = 0; i < cells; ++i) {
    for (int j = 0; j < cells; ++j) {
      const Eigen::Vector2d q(lo + (i + 0.5) * h, lo + (j + 0.5) * h);
      bool inside = true;
      for (std::size_t k = 0; k < plan.size(); ++k) {
        const Eigen::Vector2d a = plan[k], b = plan[(k + 1) % plan.size()];
        const Eigen::Vector2d e = b - a, w = q - a;
        inside = inside && e.x() * w.y() - e.y() * w.x() >= 0.0;
      }
      if (!inside) continue;
      const Eigen::Vector3d x = o + q.x() * u + q.y() * v;
      const double zw = water.table.height(x.x(), x.y());
      const double p = std::max(0.0, 1000.0 * kG * (zw - x.z()));
      const Eigen::Vector3d f = -p * h * h * n;
      force += f;
      torque += (x - about).cross(f);
    }
  }
  ASSERT_GT(force.norm(), 0.0);
  EXPECT_NEAR((exact.force - force).norm(), 0.0, 1e-3 * force.norm());
  EXPECT_NEAR((exact.torque - torque).norm(), 0.0, 1e-3 * torque.norm());
}

// A surface through three points is their plane; through four, its height is each triangle's
// plane inside the hull, and it is continuous across the pieces beyond the hull.
TEST(WaterPressure, SurfaceThroughPoints) {
  const WaterTable three = WaterTable::surface({{0, 0, 1}, {10, 0, 2}, {0, 10, 3}});
  EXPECT_NEAR(three.height(2.0, 3.0), 1.0 + 0.1 * 2.0 + 0.2 * 3.0, 1e-12);
  const WaterTable four = WaterTable::surface({{0, 0, 0}, {10, 0, 1}, {10, 10, 5}, {0, 10, 2}});
  EXPECT_NEAR(four.height(0.0, 0.0), 0.0, 1e-12);
  EXPECT_NEAR(four.height(10.0, 10.0), 5.0, 1e-12);
  EXPECT_NEAR(four.top(), 5.0, 0.0);
  // Beyond the edge y = 0: linear along it, level across it; beyond the corner (10, 10): 5.
  EXPECT_NEAR(four.height(4.0, -7.0), 0.4, 1e-12);
  EXPECT_NEAR(four.height(14.0, 13.0), 5.0, 1e-12);
  // Continuous: the height just inside and just outside each hull edge agree.
  for (const auto& [x, y, dx, dy] : std::vector<std::array<double, 4>>{
           {5, 0, 0, 1}, {10, 5, 1, 0}, {5, 10, 0, 1}, {0, 5, 1, 0}}) {
    EXPECT_NEAR(four.height(x - 1e-9 * dx, y - 1e-9 * dy),
                four.height(x + 1e-9 * dx, y + 1e-9 * dy), 1e-6);
  }
  // A block wholly below the surface still feels exactly ρ_w g V when the surface is level.
  const WaterTable flat =
      WaterTable::surface({{0, 0, 9}, {4, 0, 9}, {4, 4, 9}, {0, 4, 9}, {2, 1, 9}});
  const Polyhedron box = Polyhedron::box({1.0, 1.0, 1.0});
  const WaterLoad load = block_water_load(GroundWater{flat, 1000.0}, kG, box,
                                          Eigen::Matrix3d::Identity(), {1.0, 6.0, 2.0});
  EXPECT_NEAR(load.force.z(), 1000.0 * kG, 1e-9 * 1000.0 * kG);
  EXPECT_NEAR(load.force.head<2>().norm(), 0.0, 1e-9 * 1000.0 * kG);
}

TEST(WaterPressure, BadTablesAreRefused) {
  EXPECT_THROW(WaterTable::surface({{0, 0, 1}, {1, 0, 1}}), std::invalid_argument);
  EXPECT_THROW(WaterTable::surface({{0, 0, 1}, {1, 0, 1}, {2, 0, 1}}), std::invalid_argument);
  EXPECT_THROW(WaterTable::surface({{0, 0, 1}, {0, 0, 2}, {2, 1, 1}}), std::invalid_argument);
  EXPECT_THROW(WaterTable::plane({0, 0, 0}, {1, 0, 0}), std::invalid_argument);
  EXPECT_THROW(WaterTable::plane({0, 0, 0}, {0, 0, 0}), std::invalid_argument);
  EXPECT_THROW(WaterTable::plane({0, 0, NAN}, {0, 0, 1}), std::invalid_argument);
}

}  // namespace
}  // namespace blockdem::test::response_water_pressure
