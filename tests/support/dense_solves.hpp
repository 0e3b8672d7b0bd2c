// The small dense solves and the rotation between two directions that tests and benchmarks take
// from Eigen, compiled once (tests/support/dense_solves.cpp). Each of Eigen's decompositions costs
// every file that instantiates it seconds of compilation (GCC -O3 with the tests' precompiled
// header, over an empty file: 15 s for Quaterniond::FromTwoVectors, which takes an SVD; 10 s for
// a column-pivoting QR; 3 to 5 s for an LU or an LDLT); here it is paid once per build. Each
// helper is the one Eigen call it names, so a test's numbers are the same bits as with the call.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace blockdem::test {

/// Eigen::Quaterniond::FromTwoVectors(from, to): the rotation taking `from`'s direction to `to`'s.
Eigen::Quaterniond quaternion_between(const Eigen::Vector3d& from, const Eigen::Vector3d& to);

/// a.partialPivLu().solve(b).
Eigen::Vector2d solve_partial_lu(const Eigen::Matrix2d& a, const Eigen::Vector2d& b);
Eigen::Vector3d solve_partial_lu(const Eigen::Matrix3d& a, const Eigen::Vector3d& b);

/// a.fullPivLu().solve(b).
Eigen::Vector3d solve_full_lu(const Eigen::Matrix3d& a, const Eigen::Vector3d& b);

/// a.ldlt().solve(b) (a symmetric).
Eigen::Vector3d solve_ldlt(const Eigen::Matrix3d& a, const Eigen::Vector3d& b);

/// a.colPivHouseholderQr().solve(b): the least-squares solution of the 3 x 2 system.
Eigen::Vector2d solve_qr(const Eigen::Matrix<double, 3, 2>& a, const Eigen::Vector3d& b);

}  // namespace blockdem::test
