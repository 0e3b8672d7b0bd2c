// Central-difference (leapfrog) time integration of rigid blocks, with Cundall's local damping.
#pragma once

#include "blockdem/dynamics/block.hpp"

namespace blockdem {

/// Cundall's local non-viscous damping (Cundall 1987): each component of the unbalanced force
/// is reduced by α |F_i| sign(v_i), with α in [0, 1). α = 0 leaves the dynamics undamped.
Eigen::Vector3d local_damping(const Eigen::Vector3d& force, const Eigen::Vector3d& velocity,
                              double alpha);

/// Unit quaternion of the rotation by the rotation vector θ (rad): exp(θ/2).
Eigen::Quaterniond rotation_quaternion(const Eigen::Vector3d& theta);

/// Advances one block by dt from its current force and torque (which must include gravity).
/// Free blocks: v_{n+1/2} = v_{n-1/2} + dt F/m, x_{n+1} = x_n + dt v_{n+1/2}; the world
/// angular momentum L advances likewise, and the orientation by a two-stage exponential map
/// (orientation at the half step from L_n ≈ L_{n-1/2} + dt T/2, then the full step with the
/// angular velocity at the half step), which conserves L exactly when T = 0.
/// Blocked degrees of freedom (Block::blocked_translation, blocked_rotation) have their force or
/// torque component and velocity held at zero; with blocked rotations the angular velocity is
/// the projection of I⁻¹L on the free axes (exact when a free axis is a principal axis, as for a
/// box turning about one of its edges' directions).
/// Prescribed and servo blocks move with their velocity and angular velocity; fixed blocks stay.
void integrate_block(Block& block, double dt, double damping);

}  // namespace blockdem
