// Recursive coordinate bisection: exact cuts on small layouts (the part of each point follows
// from the weights by hand), balance on a large layout, and the input errors.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "blockdem/parallel/rcb.hpp"

namespace blockdem {
namespace {

// A 10 x 4 x 2 grid of unit weights, 2 parts: the cut is normal to x (the longest side) between
// x = 4 and x = 5, 40 points each side.
TEST(RecursiveCoordinateBisection, GridCutNormalToLongestSide) {
  std::vector<Eigen::Vector3d> p;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 2; ++k) p.emplace_back(i, j, k);
  const std::vector<double> w(p.size(), 1.0);
  const std::vector<int> part = recursive_coordinate_bisection(p, w, 2);
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_EQ(part[i], p[i].x() < 4.5 ? 0 : 1) << i;
  EXPECT_DOUBLE_EQ(partition_imbalance(w, part, 2), 1.0);
}

// Nine equal points on a line, 3 parts: first cut at weight 3 of 9 (ratio 1 : 2), then 3 : 3.
TEST(RecursiveCoordinateBisection, OddPartCountSplitsInRatio) {
  std::vector<Eigen::Vector3d> p;
  for (int i = 0; i < 9; ++i) p.emplace_back(8 - i, 0.0, 0.0);  // reversed order on purpose
  const std::vector<double> w(p.size(), 1.0);
  const std::vector<int> part = recursive_coordinate_bisection(p, w, 3);
  for (std::size_t i = 0; i < p.size(); ++i)
    EXPECT_EQ(part[i], static_cast<int>(p[i].x()) / 3) << i;
}

// Weights [3, 1, 1, 1] on a line, 2 parts: the heavy point alone balances the other three.
TEST(RecursiveCoordinateBisection, WeightsMoveTheCut) {
  const std::vector<Eigen::Vector3d> p = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  const std::vector<double> w = {3.0, 1.0, 1.0, 1.0};
  EXPECT_EQ(recursive_coordinate_bisection(p, w, 2), (std::vector<int>{0, 1, 1, 1}));
}

// 1000 scattered points of unit weight: every part of K = 1..7 holds N/K points to within one
// point per level of bisection (each cut is within half a point of its target).
TEST(RecursiveCoordinateBisection, BalancedOnScatteredPoints) {
  std::vector<Eigen::Vector3d> p;
  for (int i = 0; i < 1000; ++i)
    p.emplace_back(std::sin(1.7 * i) * 20.0, std::sin(2.3 * i + 1.0) * 7.0, std::sin(0.9 * i));
  const std::vector<double> w(p.size(), 1.0);
  for (int parts = 1; parts <= 7; ++parts) {
    const std::vector<int> part = recursive_coordinate_bisection(p, w, parts);
    std::vector<int> count(parts, 0);
    for (int q : part) ++count[q];
    const double levels = std::ceil(std::log2(parts));
    for (int q = 0; q < parts; ++q)
      EXPECT_LE(std::abs(count[q] - 1000.0 / parts), levels + 1.0) << parts << " parts";
  }
}

TEST(RecursiveCoordinateBisection, RejectsMorePartsThanPoints) {
  const std::vector<Eigen::Vector3d> p = {{0, 0, 0}, {1, 0, 0}};
  const std::vector<double> w = {1.0, 1.0};
  EXPECT_THROW(recursive_coordinate_bisection(p, w, 3), std::invalid_argument);
  EXPECT_THROW(recursive_coordinate_bisection(p, w, 0), std::invalid_argument);
  EXPECT_THROW(recursive_coordinate_bisection(p, std::vector<double>{1.0}, 1),
               std::invalid_argument);
  EXPECT_THROW(recursive_coordinate_bisection(p, std::vector<double>{1.0, 0.0}, 1),
               std::invalid_argument);
}

}  // namespace
}  // namespace blockdem
