// The pseudo-static seismic body force: its direction from the azimuth (clockwise from north, x
// east, y north), its size k g, and the force it puts on every free block of a world (m g k, and
// none on a fixed block).
#include <gtest/gtest.h>

#include <cmath>

#include "blockdem/world/world.hpp"

namespace blockdem::test::world_seismic_load {
namespace {

TEST(SeismicLoad, AccelerationPointsAlongTheAzimuth) {
  const double g = 9.81;
  SeismicLoad east{0.1, 90.0, 0.0};
  EXPECT_NEAR((east.acceleration(g) - Eigen::Vector3d(0.981, 0.0, 0.0)).norm(), 0.0, 1e-15);
  SeismicLoad north_up{0.2, 0.0, 0.05};
  EXPECT_NEAR((north_up.acceleration(g) - Eigen::Vector3d(0.0, 1.962, 0.4905)).norm(), 0.0, 1e-15);
  SeismicLoad west{0.1, 270.0, 0.0};
  EXPECT_NEAR((west.acceleration(g) - Eigen::Vector3d(-0.981, 0.0, 0.0)).norm(), 0.0, 1e-15);
  // None: exactly zero bits (a block keeps no extras for it).
  const Eigen::Vector3d none = SeismicLoad{0.0, 135.0, 0.0}.acceleration(g);
  EXPECT_TRUE(std::signbit(none.x()) == false && none.isZero(0.0));
  EXPECT_THROW((SeismicLoad{NAN, 0.0, 0.0}.validate()), std::invalid_argument);
  EXPECT_THROW((SeismicLoad{0.1, INFINITY, 0.0}.validate()), std::invalid_argument);
}

TEST(SeismicLoad, EveryFreeBlockCarriesMassTimesKG) {
  WorldSettings s;
  s.gravity = {0.0, 0.0, -9.81};
  s.seismic = SeismicLoad{0.15, 90.0, -0.05};
  s.time_step = 1e-3;
  World w(s);
  Block fixed = make_block(Polyhedron::box({1.0, 1.0, 1.0}), 2000.0, "fixed");
  fixed.motion = Motion::fixed;
  w.add_block(std::move(fixed));
  w.add_block(make_block(Polyhedron::box({0.5, 0.5, 0.5}), 2000.0, "free"));
  w.blocks()[1].position = {0.0, 0.0, 5.0};  // far from the other: no contact
  w.step();
  const Eigen::Vector3d v1 = w.blocks()[1].velocity;
  w.step();
  const Block& b = w.blocks()[1];
  const Eigen::Vector3d expected = b.mass * 9.81 * Eigen::Vector3d(0.15, 0.0, -0.05);
  EXPECT_NEAR((b.seismic_force() - expected).norm(), 0.0, 1e-12 * expected.norm());
  EXPECT_EQ(w.blocks()[0].seismic_force(), Eigen::Vector3d::Zero());
  // Free flight: a = g + k g.
  const Eigen::Vector3d a = (b.velocity - v1) / 1e-3;
  EXPECT_NEAR((a - Eigen::Vector3d(1.4715, 0.0, -9.81 - 0.4905)).norm(), 0.0, 1e-9);
  // Its work: all of load_work (the only applied load), and F · Δx of the flight (the budget
  // counts from the first step's level, the start, to the last one's).
  const Eigen::Vector3d start = w.level_state(1).position;
  for (int k = 0; k < 200; ++k) w.step();
  const EnergyBudget& e = w.energy_budget();
  const double moved = b.seismic_force().dot(w.level_state(1).position - start);
  EXPECT_NEAR(e.seismic_work, e.load_work, 1e-12 * std::abs(e.load_work));
  EXPECT_NEAR(e.seismic_work, moved, 1e-2 * std::abs(moved));
  EXPECT_EQ(e.water_work, 0.0);
}

}  // namespace
}  // namespace blockdem::test::world_seismic_load
