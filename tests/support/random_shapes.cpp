// The two shape helpers of random_shapes.hpp whose Eigen decompositions (a 3x3 LU, the quaternion
// between two vectors, which takes an SVD) cost seconds of compilation in every file that
// instantiates them: compiled once here, for the tests and the benchmarks.
#include "support/random_shapes.hpp"

#include "support/dense_solves.hpp"

namespace blockdem::test_shapes {

std::vector<Eigen::Vector3d> vertices(const Planes& planes, double tol) {
  std::vector<Eigen::Vector3d> out;
  const std::size_t m = planes.size();
  for (std::size_t i = 0; i < m; ++i) {
    for (std::size_t j = i + 1; j < m; ++j) {
      for (std::size_t k = j + 1; k < m; ++k) {
        Eigen::Matrix3d a;
        a.row(0) = planes[i].normal.transpose();
        a.row(1) = planes[j].normal.transpose();
        a.row(2) = planes[k].normal.transpose();
        if (std::abs(a.determinant()) < 1e-9) continue;
        const Eigen::Vector3d x = test::solve_partial_lu(
            a, Eigen::Vector3d(planes[i].offset, planes[j].offset, planes[k].offset));
        const bool inside = std::all_of(planes.begin(), planes.end(), [&](const Halfspace& h) {
          return h.signed_distance(x) <= tol;
        });
        const bool seen = std::any_of(out.begin(), out.end(), [&](const Eigen::Vector3d& v) {
          return (v - x).norm() <= 10.0 * tol;
        });
        if (inside && !seen) out.push_back(x);
      }
    }
  }
  return out;
}

Planes place_face_on_face(const Planes& a, std::size_t face_a, const Planes& b, std::size_t face_b,
                          double spin, double gap) {
  const Eigen::Vector3d n = a[face_a].normal;
  const Eigen::Matrix3d align =
      (Eigen::AngleAxisd(spin, n) * test::quaternion_between(b[face_b].normal, -n))
          .toRotationMatrix();
  const Planes b_rot = transformed(b, align, Eigen::Vector3d::Zero());
  const Eigen::Vector3d ca = face_centroid(a, vertices(a), face_a);
  const Eigen::Vector3d cb = face_centroid(b_rot, vertices(b_rot), face_b);
  return transformed(b_rot, Eigen::Matrix3d::Identity(), ca - cb + gap * n);
}

}  // namespace blockdem::test_shapes
