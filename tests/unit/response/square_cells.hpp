// A square face contact for the response tests: the square [0, a]² in the plane z = 0 as two
// cells of linear closure (split at x = a/2), as face_contact_geometry reports a face contact.
#pragma once

#include <utility>

#include "blockdem/collision/face_contact.hpp"

namespace blockdem::test {

/// The square of side `side` (m) with the closure g = g0 + slope x (m; >= 0 over the square for a
/// contact face_contact_geometry could report): one linear field over both cells.
inline FaceContactGeometry square_cells(double side, double g0, double slope) {
  FaceContactGeometry fc;
  fc.face_type = true;
  for (int half = 0; half < 2; ++half) {
    const double x0 = half * side / 2, x1 = x0 + side / 2;
    ClosureCell cell;
    for (const auto& [x, y] : {std::pair{x0, 0.0}, {x1, 0.0}, {x1, side}, {x0, side}}) {
      cell.vertices.push_back(Eigen::Vector3d(x, y, 0.0));
      cell.closures.push_back(g0 + slope * x);
    }
    fc.cells.push_back(cell);
  }
  return fc;
}

}  // namespace blockdem::test
