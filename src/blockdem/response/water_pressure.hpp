// Ground water in the joints: a water table (phreatic surface) below which every joint and
// exposed face carries the hydrostatic pressure p = ρ_w g (z_w - z), and the load that pressure
// puts on a polygon or on a whole block, integrated exactly.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "blockdem/geometry/halfspace.hpp"
#include "blockdem/geometry/polyhedron.hpp"

namespace blockdem {

/// A water table: the surface z = z_w(x, y) below which the rock's joints are full of water at
/// rest. It is made of linear pieces, each a plane over a convex region of the plan (a plane
/// table is one piece over the whole plan).
class WaterTable {
 public:
  /// One linear piece: where it holds in plan (half-spaces with vertical planes; none: the whole
  /// plan), and the water below it, {x : below.normal · x <= below.offset}, whose unit normal
  /// points up (below.normal.z() > 0).
  struct Piece {
    std::vector<Halfspace> region;
    Halfspace below;
  };

  /// The plane through `point` (m) with normal `normal` (any length, turned to point up). Throws
  /// std::invalid_argument when a value is not finite, the normal is zero or the plane is
  /// vertical (no height above a point).
  static WaterTable plane(const Eigen::Vector3d& point, const Eigen::Vector3d& normal);
  /// The surface through `points` (m), linear over the triangles of their Delaunay triangulation
  /// in plan, and beyond the points' convex hull in plan continued without a kink across the
  /// hull: over the strip beyond a hull edge linear along the edge and level across it, and
  /// level at a hull vertex's height in the wedge beyond the vertex. Throws
  /// std::invalid_argument for fewer than 3 or more than kMaxSurfacePoints points, a value that
  /// is not finite, two points at one place in plan, or every point on one line in plan.
  static WaterTable surface(const std::vector<Eigen::Vector3d>& points);
  static constexpr std::size_t kMaxSurfacePoints = 64;

  /// The height z_w of the table above the point (x, y) of the plan (m).
  double height(double x, double y) const;
  /// The table moved with the scene: a point x of the file is x - origin in the simulation.
  WaterTable shifted_by(const Eigen::Vector3d& origin) const;
  const std::vector<Piece>& pieces() const { return pieces_; }
  /// The highest point of the table (m): infinite for an inclined plane.
  double top() const { return top_; }
  /// The same pieces, bit for bit.
  bool operator==(const WaterTable& other) const;

 private:
  std::vector<Piece> pieces_;
  double top_ = std::numeric_limits<double>::infinity();
};

/// Ground water at rest: a water table and the water's density.
struct GroundWater {
  WaterTable table;
  double density = 1000.0;  ///< ρ_w (kg/m^3)

  bool operator==(const GroundWater& other) const = default;
};

/// Ground water on its way from one state to another (a stage's ramp, world/stage.hpp): the
/// pressure is p = (1 - f) p_from + f p_to, p_from that of `from` (empty: dry) and p_to that of
/// the water it goes to. The pressures are interpolated, not the tables: each is linear in
/// position below its own table, so the load stays exact and linear in f.
struct WaterRamp {
  std::optional<GroundWater> from;  ///< the water before the ramp (empty: dry)
  double fraction = 0.0;            ///< f in [0, 1) (-)
};

/// The load of the water's pressure on a body through some of its surface.
struct WaterLoad {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   ///< -∫ p n dA, n the outward normal (N)
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  ///< about the given point (N m)
  double wetted_area = 0.0;                          ///< the area below the table (m^2)

  WaterLoad& operator+=(const WaterLoad& other) {
    force += other.force;
    torque += other.torque;
    wetted_area += other.wetted_area;
    return *this;
  }
};

/// The water's load on a planar convex polygon (vertices in order, m) of a body's surface whose
/// outward unit normal is n, at gravity `gravity` (m/s^2, its magnitude g): over the part below
/// each piece of the table the pressure p = ρ_w g (z_w - z) is linear, so its resultant is
/// exact from the part's area A, centroid x̄ and second moment S (polygon_second_moment):
/// ∫ p dA = A p(x̄) and ∫ (x - x̄) p dA = S ∇p. The moment is about `about`.
WaterLoad polygon_water_load(const GroundWater& water, double gravity,
                             std::span<const Eigen::Vector3d> vertices, const Eigen::Vector3d& n,
                             const Eigen::Vector3d& about);

/// The water's load on a convex block (its shape in its body frame, turned by `rotation` and
/// moved to `position`: x = R x_body + position), over every face, about its position (its
/// centroid): the faces that touch other blocks (the joints) and the exposed ones alike. Wholly
/// below a plane table it is the buoyancy ρ_w g V upward through the centroid (Archimedes).
WaterLoad block_water_load(const GroundWater& water, double gravity, const Polyhedron& shape,
                           const Eigen::Matrix3d& rotation, const Eigen::Vector3d& position);

/// The water's load on a block under `water` (empty: dry) or, with `ramp`, on its way to it:
/// (1 - f) L_from + f L_to, each load that of block_water_load (zero where dry).
WaterLoad block_water_load(const std::optional<GroundWater>& water,
                           const std::optional<WaterRamp>& ramp, double gravity,
                           const Polyhedron& shape, const Eigen::Matrix3d& rotation,
                           const Eigen::Vector3d& position);

}  // namespace blockdem
