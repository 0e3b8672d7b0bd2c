// Viscous contact damping: a dashpot in parallel with a contact's normal spring, given as a
// fraction of critical damping, and the work it does over a step.
#pragma once

#include <Eigen/Core>

#include "blockdem/dynamics/block.hpp"

namespace blockdem {

/// The mass of a contact's two-body oscillator (kg): m_a m_b / (m_a + m_b) between free blocks,
/// the free block's mass against a fixed, prescribed or servo block; 0 when neither is free.
double contact_oscillator_mass(const Block& a, const Block& b);

/// The dashpot of a linear spring-dashpot contact at a fraction ζ of critical damping: the
/// coefficient c = 2 ζ sqrt(m K_n) (N s/m), m the oscillator's mass (kg) and K_n the normal
/// spring's tangent stiffness k_n A (N/m). The normal force on B along +n (compression positive)
/// is F_d = -c (v_B - v_A)·n at the force point; it is cut so that the springs' and the
/// dashpot's force together stay at or above min(F_n, 0): the dashpot resists closing at full
/// strength, but it does not pull blocks that are parting together (no sticky pull), and a
/// bonded joint in tension is not pulled harder than its law says.
///
/// A linear spring-dashpot that may pull (x'' + 2β x' + ω0² x = 0, β = ζ ω0) leaves a wall when
/// the overlap is back to zero, after π / ω with ω = ω0 sqrt(1 - ζ²): restitution
/// e = exp(-ζ π / sqrt(1 - ζ²)). Without the pull it leaves earlier, when the total force is
/// zero, at ω t = π - 2 arctan(β / ω): e = exp(-(β / ω) (π - 2 arctan(β / ω))) (Schwager &
/// Pöschel 2007, Granular Matter 9, 465-469, "Coefficient of restitution and linear-dashpot
/// model revisited"). The two agree to 0.5% at ζ = 0.05; at ζ = 0.2 they are 0.527 and 0.572.
///
/// The dashpot is not part of the joint's strength (the shear law's Coulomb limit reads the
/// springs' stress alone). The velocities are the leapfrog's at the step's forces, v_{n-1/2}, half
/// a step behind the positions: a change of the damping of order ω Δt, below 1e-3 of e at
/// Δt = τ/400 (τ = 1/ω0), 0.05% of e at ζ = 0.2 (tests/validation/contact_damping_test.cpp).
struct Dashpot {
  double force = 0.0;  ///< F_d (N), compression positive, on B along +n
  /// This step's half of the dashpot's trapezoidal work on the blocks, ½ Δt F_d (v_B - v_A)·n
  /// with the velocities the force used (J), at most zero.
  double half_work = 0.0;
};

/// The dashpot's force over a step of length `dt` (s) at a contact of unit normal `n` (A to B)
/// whose spring force is `spring_force` (N, compression positive) and normal stiffness
/// `stiffness` (N/m), acting at `x` (m), with the damping ratio `zeta` (-).
Dashpot contact_dashpot(double zeta, const Block& a, const Block& b, const Eigen::Vector3d& x,
                        const Eigen::Vector3d& n, double stiffness, double spring_force, double dt);

/// The other half of the trapezoidal work of a dashpot force `force` (N, along `n` on B) that
/// acted at `x` over the step `dt` before this one (s): ½ dt F_d (v_B - v_A)·n with the blocks'
/// velocities now (those that step produced), the lever arms about the centres where that step
/// found them (the centre now less dt times the velocity). With this half, the dashpot's work is
/// the trapezoidal rule of central differences, the one the kinetic energy of the energy budget
/// balances exactly (docs/outputs.md).
double dashpot_carried_work(double force, const Block& a, const Block& b, const Eigen::Vector3d& x,
                            const Eigen::Vector3d& n, double dt);

}  // namespace blockdem
