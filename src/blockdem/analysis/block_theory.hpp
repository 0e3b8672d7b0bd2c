// Block theory for one block held by planar contacts: its mode under gravity (falling, sliding on
// one plane, sliding on two), its limit-equilibrium factor of safety, and the support force that
// brings it to a required factor (Goodman & Shi 1985; Hoek & Bray, Rock Slope Engineering).
#pragma once

#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>

namespace blockdem {

/// One face of a block in contact with the rock that stays.
struct ContactPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< the block's unit outward normal (-)
  double area = 0.0;                                  ///< area in contact (m^2)
  double friction_coefficient = 0.0;                  ///< tan(phi) of the joint (-)
  double cohesion = 0.0;                              ///< c of the joint (Pa)
};

/// How a block moves under gravity. `stable`: no translation both admissible and downward
/// (gravity presses it into the rock, whatever the friction).
enum class BlockMode { stable, falling, sliding_one, sliding_two };
/// "stable", "falling", "sliding_one", "sliding_two".
std::string to_string(BlockMode mode);

/// A block's limit equilibrium under its weight.
struct BlockEquilibrium {
  BlockMode mode = BlockMode::stable;
  std::vector<int> planes;           ///< the planes it slides on (indices of the input)
  std::vector<double> normal_force;  ///< N on each of them, compressive (N)
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  ///< unit direction of motion (-)
  double driving_force = 0.0;    ///< S, the weight's component along `direction` (N)
  double resisting_force = 0.0;  ///< R = sum(N tan(phi) + c A) over `planes` (N)
  /// R / S; 0 for a falling block (nothing resists it).
  double factor_of_safety = 0.0;
};

/// The mode and factor of safety of a block of weight `weight` (N) under gravity along `down`
/// (any length), held by `planes`.
///
/// Method (the vector method of Londe, Vigier & Vormeringer 1969, as Goodman & Shi 1985, ch. 8,
/// set it out): the block can translate along d only if d . n_i <= 0 on every contact (it opens or
/// slides). The direction it moves in is the admissible direction nearest the unit gravity
/// vector g, s = g - sum(mu_i n_i) with mu_i >= 0 and mu_i (s . n_i) = 0: the reactions mu_i W
/// act on the planes it slides on (none: falling; one; two, along their line of intersection),
/// and s = 0 means it stays. The three cases are tried in that order; the nearest point is unique,
/// so at most one passes. Factor of safety (Hoek & Bray, ch. 7 and 8; wedge eq. 8.1):
/// F = sum(N_i tan(phi_i) + c_i A_i) / (W |s|), with N_i = mu_i W.
BlockEquilibrium block_equilibrium(std::span<const ContactPlane> planes,
                                   const Eigen::Vector3d& down, double weight);

/// The bolt force T (N) along the unit direction `bolt` that brings the block of `eq` to the
/// factor of safety `required` (> 0): 0 when it has that already.
///
/// Sliding: the bolt adds T b to the weight's load W g; on the planes of `eq` (its mode kept) the
/// normal forces and the driving force become linear in T, N_i = N_i0 + T N_i1 and S = S0 + T S1
/// (S1 = b . s), so F(T) = (R0 + T R1) / (S0 + T S1) = required gives
///     T = (required S0 - R0) / (R1 - required S1).
/// One plane, bolt at angle theta from the up-slope direction towards the plane (b = -cos(theta)
/// s + sin(theta) n, n the plane's outward normal, into the rock): R1 = sin(theta) tan(phi),
/// S1 = -cos(theta), so
///     T = (W (F sin(psi) - cos(psi) tan(phi)) - c A) / (F cos(theta) + sin(theta) tan(phi)),
/// the planar-failure form of Hoek & Bray (ch. 7, reinforcement) and Hudson & Harrison (1997,
/// Engineering Rock Mechanics, ch. 18). Falling: the factor is the support's component against
/// the fall over the weight, T = required W / (-b . s).
/// Throws std::invalid_argument when the bolt cannot bring the block there (it pulls along the
/// motion, or it would open a plane the block slides on).
double support_force(std::span<const ContactPlane> planes, const BlockEquilibrium& eq,
                     const Eigen::Vector3d& down, double weight, const Eigen::Vector3d& bolt,
                     double required);

}  // namespace blockdem
