// Leapfrog for translation and rotation.
#include "blockdem/dynamics/integrator.hpp"

#include <cmath>

namespace blockdem {

Eigen::Vector3d local_damping(const Eigen::Vector3d& force, const Eigen::Vector3d& velocity,
                              double alpha) {
  if (alpha == 0.0) return force;
  Eigen::Vector3d out = force;
  for (int i = 0; i < 3; ++i) {
    const double s = velocity[i] > 0.0 ? 1.0 : (velocity[i] < 0.0 ? -1.0 : 0.0);
    out[i] -= alpha * std::abs(force[i]) * s;
  }
  return out;
}

Eigen::Quaterniond rotation_quaternion(const Eigen::Vector3d& theta) {
  const double angle = theta.norm();
  if (angle < 1e-300) return Eigen::Quaterniond::Identity();
  const double half = 0.5 * angle;
  const Eigen::Vector3d axis = theta / angle;
  const double s = std::sin(half);
  return Eigen::Quaterniond(std::cos(half), s * axis.x(), s * axis.y(), s * axis.z());
}

namespace {

// Body-frame angular velocity for world angular momentum L at orientation q.
Eigen::Vector3d body_omega(const Block& b, const Eigen::Quaterniond& q, const Eigen::Vector3d& L) {
  return (q.conjugate() * L).cwiseQuotient(b.inertial_moments());
}

}  // namespace

void integrate_block(Block& b, double dt, double damping) {
  switch (b.motion) {
    case Motion::fixed:
      b.velocity.setZero();
      b.angular_velocity.setZero();
      b.angular_momentum.setZero();
      return;
    case Motion::prescribed:
    case Motion::servo:
      b.position += dt * b.velocity;
      b.orientation = (rotation_quaternion(dt * b.angular_velocity) * b.orientation).normalized();
      b.angular_momentum = b.world_inertia() * b.angular_velocity;
      return;
    case Motion::free:
      break;
  }
  // Translation.
  Eigen::Vector3d f = local_damping(b.force, b.velocity, damping);
  for (int i = 0; i < 3; ++i) {
    if (b.blocked_translation[i]) {
      f[i] = 0.0;
      b.velocity[i] = 0.0;
    }
  }
  b.velocity += dt * f / b.inertial_mass();
  b.position += dt * b.velocity;

  if (b.blocked_rotation.any()) {
    // Rotation restricted to the free world axes: ω = P I⁻¹ L, L = I ω.
    Eigen::Vector3d t = local_damping(b.torque, b.angular_velocity, damping);
    Eigen::Vector3d w = b.world_inertia().inverse() * (b.angular_momentum + dt * t);
    for (int i = 0; i < 3; ++i) {
      if (b.blocked_rotation[i]) w[i] = 0.0;
    }
    b.orientation = (rotation_quaternion(dt * w) * b.orientation).normalized();
    b.angular_velocity = w;
    b.angular_momentum = b.world_inertia() * w;
    return;
  }

  // Rotation: damping acts on the world components of the torque against ω.
  const Eigen::Vector3d t = local_damping(b.torque, b.angular_velocity, damping);
  const Eigen::Vector3d l_now = b.angular_momentum + 0.5 * dt * t;
  b.angular_momentum += dt * t;
  const Eigen::Quaterniond q0 = b.orientation;
  const Eigen::Quaterniond q_half =
      (q0 * rotation_quaternion(0.5 * dt * body_omega(b, q0, l_now))).normalized();
  const Eigen::Vector3d w_half = body_omega(b, q_half, b.angular_momentum);
  b.orientation = (q0 * rotation_quaternion(dt * w_half)).normalized();
  b.angular_velocity = q_half * w_half;
}

}  // namespace blockdem
