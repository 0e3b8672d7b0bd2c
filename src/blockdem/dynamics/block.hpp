// A rigid block: shape in its principal body frame, mass properties, kinematic state, loads.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "blockdem/geometry/polyhedron.hpp"

namespace blockdem {

/// How a block moves.
enum class Motion {
  free,        ///< integrated from forces
  fixed,       ///< never moves
  prescribed,  ///< moves with a given velocity and angular velocity
  servo,       ///< translates along an axis at a speed set by a force controller (see Servo)
};

/// A servo-controlled boundary block: its speed along `axis` is
/// v = gain (F_target - F_reaction), clipped to ±max_speed, where F_reaction is the component
/// along -axis of the contact force the block receives (how hard it pushes forward).
struct Servo {
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  ///< unit direction of travel (-)
  double target_force = 0.0;                        ///< (N)
  double gain = 0.0;        ///< (m/s/N); 0: chosen from the contact stiffness
  double max_speed = 0.0;   ///< (m/s); 0: chosen from the time step
  double tolerance = 0.01;  ///< converged when |F - F_target| <= tol·F_target
  bool hold = false;        ///< when true the block stays where it is
};

/// Whether two servos hold the same bits in every field (-0.0 and 0.0 differ): a servo equal to
/// Servo{} this way is Servo{}.
bool same_bits(const Servo& a, const Servo& b);

/// The fields most blocks leave at their defaults. A block holds them apart, behind one pointer
/// that stays null until one is set, so that a large scene of plain blocks does not pay their
/// 112 bytes per block.
struct BlockExtras {
  Servo servo;
  // Constant applied loads (world frame), added every step to free blocks.
  Eigen::Vector3d external_force = Eigen::Vector3d::Zero();   ///< (N), acts at the centroid
  Eigen::Vector3d external_torque = Eigen::Vector3d::Zero();  ///< (N m)
  // The loads of the ground water and of a pseudo-static earthquake at the block's pose of the
  // step (world frame), set by the world at every step's start.
  Eigen::Vector3d water_force = Eigen::Vector3d::Zero();    ///< (N), acts at the centroid
  Eigen::Vector3d water_torque = Eigen::Vector3d::Zero();   ///< about the centroid (N m)
  Eigen::Vector3d seismic_force = Eigen::Vector3d::Zero();  ///< (N), acts at the centroid
};

// The fields are ordered by use. The step's per-pair passes (narrow phase, contact forces, the
// loads' scatter) read a few fields of two blocks per pair, and in a large scene the blocks of a
// pair lie far apart in memory: those fields sit together in the first 120 bytes of the record (at
// most three cache lines; the loads of the step in the next 72), not spread over all of it.
// The small members fill what the larger ones' alignment would leave as padding: index and motion
// the 8 bytes after bounding_radius, density the 8 before the orientation, the blocked degrees of
// freedom the 6 before the pointer to the extras.
struct Block {
  // Read per pair: the shape, pose, velocities and world planes (narrow phase, shear).
  Polyhedron shape;  ///< body frame: centroid at the origin, principal axes
  Eigen::Vector3d position = Eigen::Vector3d::Zero();          ///< centroid (m)
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();          ///< (m/s), at the half step
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  ///< world frame (rad/s), half step
  // World-frame planes, refreshed every step (the bounding box below too).
  std::vector<Halfspace> world_planes;
  /// shape.bounding_radius(), refreshed with world_planes: read per pair without a visit to the
  /// shape's data (m).
  double bounding_radius = 0.0;

  int index = -1;
  Motion motion = Motion::free;

  // Loads of the current step (written per pair by the scatter).
  Eigen::Vector3d force = Eigen::Vector3d::Zero();          ///< total, including gravity (N)
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();         ///< about the centroid (N m)
  Eigen::Vector3d contact_force = Eigen::Vector3d::Zero();  ///< from contacts only (N)

  double density = 0.0;  ///< (kg/m^3)

  // State. Orientation maps body to world coordinates.
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d angular_momentum =
      Eigen::Vector3d::Zero();  ///< world frame (kg m^2/s), half step

  double mass = 0.0;                                  ///< (kg)
  Eigen::Vector3d inertia = Eigen::Vector3d::Zero();  ///< principal moments (kg m^2)
  /// Density scaling of a quasi-static stage (docs/stability.md): the equations of motion use
  /// mass_scale · mass and inertia_scale · inertia; the weight stays mass · g. 1 when off.
  double mass_scale = 1.0;     ///< (-)
  double inertia_scale = 1.0;  ///< (-)

  /// Degrees of freedom held at zero for a free block, along the world axes x, y, z: translation
  /// (blocked_translation) and rotation (blocked_rotation). E.g. plane motion in x-z: translation
  /// (false, true, false), rotation (true, false, true).
  Eigen::Matrix<bool, 3, 1> blocked_translation = Eigen::Matrix<bool, 3, 1>::Constant(false);
  Eigen::Matrix<bool, 3, 1> blocked_rotation = Eigen::Matrix<bool, 3, 1>::Constant(false);

 private:
  /// Null while every field of BlockExtras has its default; a copy of a block copies them.
  struct ExtrasBox {
    std::unique_ptr<BlockExtras> p;
    ExtrasBox() = default;
    ExtrasBox(const ExtrasBox& o) : p(o.p ? std::make_unique<BlockExtras>(*o.p) : nullptr) {}
    ExtrasBox(ExtrasBox&&) noexcept = default;
    ExtrasBox& operator=(const ExtrasBox& o) {
      if (this != &o) p = o.p ? std::make_unique<BlockExtras>(*o.p) : nullptr;
      return *this;
    }
    ExtrasBox& operator=(ExtrasBox&&) noexcept = default;
    ~ExtrasBox() = default;
  };
  ExtrasBox extras_;
  /// The group's name, one copy per distinct name for the whole process (a scene has a handful
  /// of groups and every block has one, "default" unless named); null for "".
  const std::string* group_ = nullptr;

 public:
  // Reference state for displacement outputs.
  Eigen::Vector3d initial_position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond initial_orientation = Eigen::Quaterniond::Identity();

  std::string name;

  /// The rarely set fields: the defaults (BlockExtras{}) for a block that has none.
  const BlockExtras& extras() const { return extras_.p ? *extras_.p : kNoExtras; }
  /// Whether the block holds its own extras (otherwise they are all at their defaults).
  bool has_extras() const { return extras_.p != nullptr; }
  /// The servo (Servo{} for a block that has none).
  const Servo& servo() const { return extras().servo; }
  /// The servo, to be changed (the block's extras are created if it has none).
  Servo& edit_servo() { return own_extras().servo; }
  /// Sets the servo; a block without extras stays so when `s` has Servo{}'s bits.
  void set_servo(const Servo& s);
  /// Constant applied force (world frame), added every step to a free block (N).
  const Eigen::Vector3d& external_force() const { return extras().external_force; }
  /// Constant applied torque (world frame), added every step to a free block (N m).
  const Eigen::Vector3d& external_torque() const { return extras().external_torque; }
  /// Set the applied loads; a block without extras stays so when the value's bits are all zero.
  void set_external_force(const Eigen::Vector3d& f);
  void set_external_torque(const Eigen::Vector3d& t);
  /// The ground water's force and torque on the block (world frame; N, N m about the centroid).
  const Eigen::Vector3d& water_force() const { return extras().water_force; }
  const Eigen::Vector3d& water_torque() const { return extras().water_torque; }
  /// The pseudo-static seismic body force on the block (world frame, N).
  const Eigen::Vector3d& seismic_force() const { return extras().seismic_force; }
  /// Sets the water's and the earthquake's loads; a block without extras stays so when every
  /// value's bits are zero.
  void set_field_loads(const Eigen::Vector3d& water_force, const Eigen::Vector3d& water_torque,
                       const Eigen::Vector3d& seismic_force);
  /// Every applied load besides gravity and the contacts: the constant force, the water's and
  /// the earthquake's (world frame, N; N m about the centroid).
  /// Without water or earthquake, the constant loads' own bits.
  Eigen::Vector3d applied_force() const {
    const BlockExtras& e = extras();
    if (e.water_force.isZero(0.0) && e.seismic_force.isZero(0.0)) return e.external_force;
    return e.external_force + e.water_force + e.seismic_force;
  }
  Eigen::Vector3d applied_torque() const {
    const BlockExtras& e = extras();
    if (e.water_torque.isZero(0.0)) return e.external_torque;
    return e.external_torque + e.water_torque;
  }
  /// The contact rules' group ("" for none).
  const std::string& group() const { return group_ ? *group_ : kNoGroup; }
  void set_group(std::string g);

  bool is_dynamic() const { return motion == Motion::free; }
  /// The mass the equations of motion use: mass_scale · mass (kg).
  double inertial_mass() const { return mass_scale * mass; }
  /// The principal moments the equations of motion use: inertia_scale · inertia (kg m^2).
  Eigen::Vector3d inertial_moments() const { return inertia_scale * inertia; }
  /// Rotation matrix body -> world.
  Eigen::Matrix3d rotation() const { return orientation.toRotationMatrix(); }
  /// Refreshes world_planes and bounding_radius from the pose.
  void update_world_geometry();
  /// The same, and the world-frame bounding box of the pose into box_min, box_max (m). The box
  /// is not a member: the world keeps every block's box in its own compact arrays (the broad
  /// phase reads them), and a copy here would cost 48 bytes per block.
  void update_world_geometry(Eigen::Vector3d& box_min, Eigen::Vector3d& box_max);
  /// The world-frame bounding box of the pose (m), the same bits as update_world_geometry's.
  void world_box(Eigen::Vector3d& box_min, Eigen::Vector3d& box_max) const;
  /// World position of a body-frame point.
  Eigen::Vector3d to_world(const Eigen::Vector3d& body_point) const {
    return position + orientation * body_point;
  }
  /// Velocity of the material point at world position x (m/s).
  Eigen::Vector3d point_velocity(const Eigen::Vector3d& x) const {
    return velocity + angular_velocity.cross(x - position);
  }
  /// Rotation since the initial pose as a rotation vector, world frame (rad): axis × angle,
  /// angle in [0, π].
  Eigen::Vector3d rotation_since_start() const;
  /// Kinetic energy, translational plus rotational, of the inertial (density-scaled) mass and
  /// moments (J).
  double kinetic_energy() const;
  /// World inertia tensor R diag(I) Rᵀ of the inertial moments (kg m^2).
  Eigen::Matrix3d world_inertia() const;

 private:
  static const BlockExtras kNoExtras;
  static const std::string kNoGroup;
  BlockExtras& own_extras();
};

/// Builds a block from a shape given in world coordinates (the shape's own frame is the world's):
/// the body frame is moved to the centroid and turned to the principal axes, and the initial pose
/// puts the block exactly where the shape was. Throws GeometryError for a non-positive density.
Block make_block(const Polyhedron& world_shape, double density, std::string name = {},
                 std::string group = {});

}  // namespace blockdem
