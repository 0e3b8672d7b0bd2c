// Eigen's decompositions for the tests and benchmarks, instantiated in this file alone
// (dense_solves.hpp says why).
#include "support/dense_solves.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/QR>

namespace blockdem::test {

Eigen::Quaterniond quaternion_between(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  return Eigen::Quaterniond::FromTwoVectors(from, to);
}

Eigen::Vector2d solve_partial_lu(const Eigen::Matrix2d& a, const Eigen::Vector2d& b) {
  return a.partialPivLu().solve(b);
}

Eigen::Vector3d solve_partial_lu(const Eigen::Matrix3d& a, const Eigen::Vector3d& b) {
  return a.partialPivLu().solve(b);
}

Eigen::Vector3d solve_full_lu(const Eigen::Matrix3d& a, const Eigen::Vector3d& b) {
  return a.fullPivLu().solve(b);
}

Eigen::Vector3d solve_ldlt(const Eigen::Matrix3d& a, const Eigen::Vector3d& b) {
  return a.ldlt().solve(b);
}

Eigen::Vector2d solve_qr(const Eigen::Matrix<double, 3, 2>& a, const Eigen::Vector3d& b) {
  return a.colPivHouseholderQr().solve(b);
}

}  // namespace blockdem::test
