// Block theory for one block: the vector method's three modes, limit equilibrium, support force.
#include "blockdem/analysis/block_theory.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>

namespace blockdem {
namespace {

/// Tolerance on unit-vector products: a plane within it of parallel to the motion counts as
/// opening, a reaction within it of zero as none.
constexpr double kTolerance = 1e-9;

/// The reactions mu (per unit weight) on `active` that balance the component of `load` normal to
/// the motion: load_perp = sum(mu_k n_k), from the Gram system of the active normals.
std::vector<double> reactions(std::span<const ContactPlane> planes, const std::vector<int>& active,
                              const Eigen::Vector3d& load) {
  if (active.size() == 1) return {load.dot(planes[static_cast<std::size_t>(active[0])].normal)};
  const Eigen::Vector3d& a = planes[static_cast<std::size_t>(active[0])].normal;
  const Eigen::Vector3d& b = planes[static_cast<std::size_t>(active[1])].normal;
  Eigen::Matrix2d gram;
  gram << 1.0, a.dot(b), a.dot(b), 1.0;
  const Eigen::Vector2d mu = gram.inverse() * Eigen::Vector2d(load.dot(a), load.dot(b));
  return {mu(0), mu(1)};
}

/// Whether direction s opens (or slides along) every plane but those in `active`.
bool opens_others(std::span<const ContactPlane> planes, const std::vector<int>& active,
                  const Eigen::Vector3d& s) {
  for (std::size_t k = 0; k < planes.size(); ++k) {
    bool is_active = false;
    for (int a : active) is_active = is_active || static_cast<std::size_t>(a) == k;
    if (!is_active && s.dot(planes[k].normal) > kTolerance) return false;
  }
  return true;
}

/// The equilibrium of a block that moves along s (not normalised) on `active`, reactions mu.
BlockEquilibrium sliding(std::span<const ContactPlane> planes, std::vector<int> active,
                         const std::vector<double>& mu, const Eigen::Vector3d& s, double weight) {
  BlockEquilibrium eq;
  eq.mode = active.empty()       ? BlockMode::falling
            : active.size() == 1 ? BlockMode::sliding_one
                                 : BlockMode::sliding_two;
  eq.direction = s.normalized();
  eq.driving_force = weight * s.norm();
  for (std::size_t k = 0; k < active.size(); ++k) {
    const ContactPlane& p = planes[static_cast<std::size_t>(active[k])];
    const double n = mu[k] * weight;
    eq.normal_force.push_back(n);
    eq.resisting_force += n * p.friction_coefficient + p.cohesion * p.area;
  }
  eq.planes = std::move(active);
  eq.factor_of_safety = eq.resisting_force / eq.driving_force;
  return eq;
}

}  // namespace

std::string to_string(BlockMode mode) {
  switch (mode) {
    case BlockMode::falling:
      return "falling";
    case BlockMode::sliding_one:
      return "sliding_one";
    case BlockMode::sliding_two:
      return "sliding_two";
    case BlockMode::stable:
      break;
  }
  return "stable";
}

BlockEquilibrium block_equilibrium(std::span<const ContactPlane> planes,
                                   const Eigen::Vector3d& down, double weight) {
  const Eigen::Vector3d g = down.normalized();
  // Falling: gravity opens every plane.
  if (opens_others(planes, {}, g)) return sliding(planes, {}, {}, g, weight);
  // Sliding on one plane i: pressed onto it, moving along gravity's projection on it.
  for (std::size_t i = 0; i < planes.size(); ++i) {
    const std::vector<int> active{static_cast<int>(i)};
    const std::vector<double> mu = reactions(planes, active, g);
    if (!(mu[0] > kTolerance)) continue;
    const Eigen::Vector3d s = g - mu[0] * planes[i].normal;
    if (s.norm() > kTolerance && opens_others(planes, active, s))
      return sliding(planes, active, mu, s, weight);
  }
  // Sliding on two planes i, j: pressed onto both, moving along their line of intersection.
  for (std::size_t i = 0; i < planes.size(); ++i) {
    for (std::size_t j = i + 1; j < planes.size(); ++j) {
      if (planes[i].normal.cross(planes[j].normal).norm() < kTolerance) continue;
      const std::vector<int> active{static_cast<int>(i), static_cast<int>(j)};
      const std::vector<double> mu = reactions(planes, active, g);
      if (!(mu[0] > kTolerance && mu[1] > kTolerance)) continue;
      const Eigen::Vector3d s = g - mu[0] * planes[i].normal - mu[1] * planes[j].normal;
      if (s.norm() > kTolerance && opens_others(planes, active, s))
        return sliding(planes, active, mu, s, weight);
    }
  }
  return {};
}

double support_force(std::span<const ContactPlane> planes, const BlockEquilibrium& eq,
                     const Eigen::Vector3d& down, double weight, const Eigen::Vector3d& bolt,
                     double required) {
  if (!(required > 0.0) || !std::isfinite(required))
    throw std::invalid_argument("the required factor of safety must be a finite number > 0");
  if (eq.mode == BlockMode::stable) return 0.0;
  const Eigen::Vector3d b = bolt.normalized();
  const double against = -b.dot(eq.direction);
  if (eq.mode == BlockMode::falling) {
    if (!(against > kTolerance))
      throw std::invalid_argument("a bolt along or across the fall cannot hold the block");
    return required * weight / against;
  }
  // R and S of the load W g (index 0) and of a unit bolt force (index 1).
  const Eigen::Vector3d g = down.normalized();
  const std::vector<double> mu0 = reactions(planes, eq.planes, weight * g);
  const std::vector<double> mu1 = reactions(planes, eq.planes, b);
  double r0 = 0.0, r1 = 0.0;
  for (std::size_t k = 0; k < eq.planes.size(); ++k) {
    const ContactPlane& p = planes[static_cast<std::size_t>(eq.planes[k])];
    r0 += mu0[k] * p.friction_coefficient + p.cohesion * p.area;
    r1 += mu1[k] * p.friction_coefficient;
  }
  const double s0 = weight * g.dot(eq.direction);
  const double s1 = b.dot(eq.direction);
  if (r0 >= required * s0) return 0.0;
  const double gain = r1 - required * s1;
  if (!(gain > kTolerance))
    throw std::invalid_argument("a bolt in this direction does not raise the factor of safety");
  const double t = (required * s0 - r0) / gain;
  for (std::size_t k = 0; k < eq.planes.size(); ++k) {
    if (mu0[k] + t * mu1[k] < -kTolerance * weight)
      throw std::invalid_argument("a bolt in this direction opens a plane the block slides on");
  }
  return t;
}

}  // namespace blockdem
