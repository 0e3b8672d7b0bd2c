// Block construction (principal frame) and per-step world geometry.
#include "blockdem/dynamics/block.hpp"

#include <Eigen/Eigenvalues>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <set>

#include "blockdem/geometry/geometry_error.hpp"
#include "blockdem/numerics/number_text.hpp"
#include "blockdem/numerics/units.hpp"

namespace blockdem {

Block make_block(const Polyhedron& world_shape, double density, std::string name,
                 std::string group) {
  if (!(density > 0.0) || !std::isfinite(density)) {
    throw GeometryError("density must be positive and finite, got " + number_text(density));
  }
  Block b;
  b.name = std::move(name);
  b.set_group(std::move(group));
  b.density = density;
  b.mass = density * world_shape.volume();

  // Principal axes: columns of R are the eigenvectors of the unit inertia tensor (right-handed).
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(world_shape.unit_inertia());
  Eigen::Matrix3d axes = eig.eigenvectors();
  if (axes.determinant() < 0) axes.col(2) = -axes.col(2);
  // Snap to the world axes when the tensor is (nearly) isotropic or already diagonal, so that a
  // box keeps its faces along the world axes in its body frame.
  const Eigen::Matrix3d inertia = world_shape.unit_inertia();
  const double off = std::abs(inertia(0, 1)) + std::abs(inertia(0, 2)) + std::abs(inertia(1, 2));
  if (off <= 1e-12 * inertia.trace()) axes.setIdentity();
  const Eigen::Matrix3d body_inertia = axes.transpose() * inertia * axes;
  b.inertia = density * body_inertia.diagonal();

  // Body shape: x_body = axesᵀ (x_world - centroid).
  b.shape = world_shape.transformed(axes.transpose(), -axes.transpose() * world_shape.centroid());
  b.position = world_shape.centroid();
  b.orientation = Eigen::Quaterniond(axes).normalized();
  b.initial_position = b.position;
  b.initial_orientation = b.orientation;
  b.update_world_geometry();
  return b;
}

namespace {

// World planes and bounding radius of block b at rotation r (its orientation's matrix).
void refresh_planes(Block& b, const Eigen::Matrix3d& r) {
  const auto& planes = b.shape.planes();
  b.world_planes.resize(planes.size());
  b.bounding_radius = b.shape.bounding_radius();
  for (std::size_t i = 0; i < planes.size(); ++i) {
    const Eigen::Vector3d n = r * planes[i].normal;
    b.world_planes[i].normal = n;
    b.world_planes[i].offset = planes[i].offset + n.dot(b.position);
  }
}

// The box of a block's vertices at the pose (position, r).
void box_of(const Polyhedron& shape, const Eigen::Vector3d& position, const Eigen::Matrix3d& r,
            Eigen::Vector3d& box_min, Eigen::Vector3d& box_max) {
  box_min.setConstant(std::numeric_limits<double>::infinity());
  box_max.setConstant(-std::numeric_limits<double>::infinity());
  for (const auto& v : shape.vertices()) {
    const Eigen::Vector3d w = position + r * v;
    box_min = box_min.cwiseMin(w);
    box_max = box_max.cwiseMax(w);
  }
}

}  // namespace

void Block::update_world_geometry() {
  refresh_planes(*this, rotation());
}

void Block::update_world_geometry(Eigen::Vector3d& box_min, Eigen::Vector3d& box_max) {
  const Eigen::Matrix3d r = rotation();
  refresh_planes(*this, r);
  box_of(shape, position, r, box_min, box_max);
}

void Block::world_box(Eigen::Vector3d& box_min, Eigen::Vector3d& box_max) const {
  box_of(shape, position, rotation(), box_min, box_max);
}

const BlockExtras Block::kNoExtras{};
const std::string Block::kNoGroup;

BlockExtras& Block::own_extras() {
  if (!extras_.p) extras_.p = std::make_unique<BlockExtras>();
  return *extras_.p;
}

namespace {

bool zero_bits(const Eigen::Vector3d& v) {
  return std::bit_cast<std::uint64_t>(v.x()) == 0 && std::bit_cast<std::uint64_t>(v.y()) == 0 &&
         std::bit_cast<std::uint64_t>(v.z()) == 0;
}

}  // namespace

// The setters keep a block without extras so when the value is the default's bits (-0.0 is not
// 0.0), so that reading the value back always gives the bits that were set.
void Block::set_servo(const Servo& s) {
  if (extras_.p || !same_bits(s, Servo{})) own_extras().servo = s;
}

void Block::set_external_force(const Eigen::Vector3d& f) {
  if (extras_.p || !zero_bits(f)) own_extras().external_force = f;
}

void Block::set_field_loads(const Eigen::Vector3d& water_force, const Eigen::Vector3d& water_torque,
                            const Eigen::Vector3d& seismic_force) {
  if (!extras_.p && zero_bits(water_force) && zero_bits(water_torque) && zero_bits(seismic_force))
    return;
  BlockExtras& e = own_extras();
  e.water_force = water_force;
  e.water_torque = water_torque;
  e.seismic_force = seismic_force;
}

void Block::set_external_torque(const Eigen::Vector3d& t) {
  if (extras_.p || !zero_bits(t)) own_extras().external_torque = t;
}

void Block::set_group(std::string g) {
  if (g.empty()) {
    group_ = nullptr;
    return;
  }
  // Never freed, so that a group's address stays valid for every block, even during static
  // destruction; a set's nodes do not move when it grows.
  static std::mutex mutex;
  static auto* names = new std::set<std::string>;
  // The group this thread named last, looked up without the lock: a rock mass's million blocks
  // made on several threads share one group, and the name in a node never changes.
  thread_local const std::string* last = nullptr;
  if (last != nullptr && *last == g) {
    group_ = last;
    return;
  }
  const std::lock_guard<std::mutex> lock(mutex);
  group_ = &*names->insert(std::move(g)).first;
  last = group_;
}

bool same_bits(const Servo& a, const Servo& b) {
  const auto same = [](double x, double y) {
    return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y);
  };
  return same(a.axis.x(), b.axis.x()) && same(a.axis.y(), b.axis.y()) &&
         same(a.axis.z(), b.axis.z()) && same(a.target_force, b.target_force) &&
         same(a.gain, b.gain) && same(a.max_speed, b.max_speed) && same(a.tolerance, b.tolerance) &&
         a.hold == b.hold;
}

Eigen::Vector3d Block::rotation_since_start() const {
  const Eigen::AngleAxisd aa(orientation * initial_orientation.conjugate());
  return aa.angle() > kPi ? Eigen::Vector3d(-(2 * kPi - aa.angle()) * aa.axis())
                          : Eigen::Vector3d(aa.angle() * aa.axis());
}

double Block::kinetic_energy() const {
  const Eigen::Vector3d w_body = orientation.conjugate() * angular_velocity;
  return 0.5 * inertial_mass() * velocity.squaredNorm() +
         0.5 * w_body.dot(inertial_moments().cwiseProduct(w_body));
}

Eigen::Matrix3d Block::world_inertia() const {
  const Eigen::Matrix3d r = rotation();
  return r * inertial_moments().asDiagonal() * r.transpose();
}

}  // namespace blockdem
