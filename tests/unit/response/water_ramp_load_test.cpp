// The water's load on a block while a ramp moves the pressure between two states of the ground
// water, p = (1 - f) p_from + f p_to: Archimedes' rho_w g V_sub under each of two level tables of
// other densities (exact), a drawdown to dry, and the equality of water tables that tells a stage
// whether there is anything to ramp.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <optional>

#include "blockdem/response/water_pressure.hpp"

namespace blockdem::test::response_water_ramp {
namespace {

constexpr double kG = 9.81;

GroundWater level(double z, double density) {
  return GroundWater{WaterTable::plane({0.0, 0.0, z}, {0.0, 0.0, 1.0}), density};
}

// A box 2 × 1 × 0.5 m with its base at z = 0: a third below a table at 1/6 m of fresh water
// (rho_w g V / 3), wholly below one at 3 m of sea water (1025 kg/m^3). At a fraction f of the
// ramp its water force is (1 - f) 1000 g V / 3 + f 1025 g V upward, to round-off; with no water
// to go to (a drawdown) it is (1 - f) times the load before.
TEST(WaterRampLoad, ForceIsTheInterpolationOfArchimedesUnderEachTable) {
  const Polyhedron box = Polyhedron::box({2.0, 1.0, 0.5});
  const Eigen::Vector3d at(1.0, 2.0, 0.25);
  const Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  const double volume = box.volume();
  const std::optional<GroundWater> before = level(1.0 / 6.0, 1000.0);
  const std::optional<GroundWater> after = level(3.0, 1025.0);
  for (const double f : {0.0, 0.125, 0.5, 0.9}) {
    const WaterLoad load = block_water_load(after, WaterRamp{before, f}, kG, box, r, at);
    const double expected = (1.0 - f) * 1000.0 * kG * volume / 3.0 + f * 1025.0 * kG * volume;
    EXPECT_NEAR(load.force.z(), expected, 1e-12 * expected) << f;
    EXPECT_NEAR(load.force.head<2>().norm(), 0.0, 1e-12 * expected) << f;
    // Drawdown to dry: (1 - f) of the load under the table before.
    const WaterLoad dry = block_water_load(std::nullopt, WaterRamp{after, f}, kG, box, r, at);
    EXPECT_NEAR(dry.force.z(), (1.0 - f) * 1025.0 * kG * volume, 1e-12 * 1025.0 * kG * volume);
  }
  // No ramp: the table's own load, bit for bit.
  const WaterLoad plain = block_water_load(*after, kG, box, r, at);
  const WaterLoad none = block_water_load(after, std::nullopt, kG, box, r, at);
  EXPECT_EQ(plain.force, none.force);
  EXPECT_EQ(plain.torque, none.torque);
}

TEST(WaterRampLoad, TablesAreEqualOnlyWhenTheirPiecesAndDensityAre) {
  EXPECT_EQ(level(2.0, 1000.0), level(2.0, 1000.0));
  EXPECT_FALSE(level(2.0, 1000.0) == level(2.5, 1000.0));
  EXPECT_FALSE(level(2.0, 1000.0) == level(2.0, 1025.0));
  const WaterTable surface = WaterTable::surface({{0, 0, 2}, {1, 0, 2}, {0, 1, 2}});
  EXPECT_FALSE(surface == level(2.0, 1000.0).table);
  EXPECT_EQ(surface, WaterTable::surface({{0, 0, 2}, {1, 0, 2}, {0, 1, 2}}));
}

}  // namespace
}  // namespace blockdem::test::response_water_ramp
