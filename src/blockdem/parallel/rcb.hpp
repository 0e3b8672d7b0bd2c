// Recursive coordinate bisection: points (block centroids) split into K parts of about equal
// weight by cuts normal to the longest side of each part's bounding box.
#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

namespace blockdem {

/// The part, in [0, parts), of each point. A part's points are cut normal to the longest side of
/// their bounding box at the weighted position that gives the two halves weights in the ratio of
/// their part counts (floor(K/2) : ceil(K/2)), recursively. Ties in the coordinate are broken by
/// the point's index, so the result depends only on the input. Weights must be positive.
/// Throws std::invalid_argument when parts < 1, parts > points, or the spans differ in size.
std::vector<int> recursive_coordinate_bisection(std::span<const Eigen::Vector3d> points,
                                                std::span<const double> weights, int parts);

/// The heaviest part's weight over the mean part weight (1: perfect balance) (-).
double partition_imbalance(std::span<const double> weights, const std::vector<int>& part,
                           int parts);

}  // namespace blockdem
