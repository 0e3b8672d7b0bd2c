// A convex cell of the rock slicer: vertices and ordered face polygons that share vertex indices,
// split exactly by a plane (every face remembers its FaceTag).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "blockdem/geometry/halfspace.hpp"
#include "blockdem/geometry/polyhedron.hpp"
#include "blockdem/rockmass/face_tag.hpp"

namespace blockdem {

/// One face of a cell: its plane (unit outward normal), tag, and vertex indices in
/// counter-clockwise order seen from outside.
struct CellFace {
  Halfspace plane;
  FaceTag tag;
  std::vector<int> vertices;
};

struct CellParts;

class ConvexCell {
 public:
  /// From a bounded polyhedron; `tags[i]` is the tag of the polyhedron's plane i.
  static ConvexCell from_polyhedron(const Polyhedron& shape, std::span<const FaceTag> tags);

  const std::vector<Eigen::Vector3d>& vertices() const { return vertices_; }
  const std::vector<CellFace>& faces() const { return faces_; }
  std::vector<CellFace>& faces() { return faces_; }

  double volume() const { return volume_; }                      ///< (m^3)
  const Eigen::Vector3d& centroid() const { return centroid_; }  ///< (m)
  /// Smallest and largest of n · v over the vertices (m).
  std::pair<double, double> extent_along(const Eigen::Vector3d& n) const;
  /// Largest width over smallest width, widths measured along the face normals (-): 1 for a
  /// cube, a/c for an a x b x c box (a >= b >= c).
  double aspect_ratio() const;
  /// The cell's section by a plane, counter-clockwise about the plane's normal; empty when the
  /// plane does not cross the cell by more than `snap` (m).
  std::vector<Eigen::Vector3d> section(const Halfspace& plane, double snap) const;
  /// The ordered polygon of face f.
  std::vector<Eigen::Vector3d> face_polygon(int f) const;

  /// The two parts {n·x <= d} ("below") and {n·x >= d} ("above"), each with a new face on the
  /// plane tagged `tag`, or nothing when the plane does not cross the cell. Vertices closer than
  /// `snap` (m) to the plane count as on it, so no face edge shorter than snap is made there.
  std::optional<CellParts> split(const Halfspace& plane, const FaceTag& tag, double snap) const;

  /// Frees the spare capacity of the vertex and face lists (a cell kept after slicing).
  void shrink_to_fit();

 private:
  void update_mass_properties();

  std::vector<Eigen::Vector3d> vertices_;
  std::vector<CellFace> faces_;
  double volume_ = 0.0;
  Eigen::Vector3d centroid_ = Eigen::Vector3d::Zero();
};

/// The two parts of a split cell.
struct CellParts {
  ConvexCell below;
  ConvexCell above;
};

/// Orders points lying on a plane counter-clockwise about `normal` (in place).
void order_about(std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& normal);

}  // namespace blockdem
