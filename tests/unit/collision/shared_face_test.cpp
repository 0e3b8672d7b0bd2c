// Shared faces of two blocks: the polygon of two unit cubes side by side against its closed form
// (area, centroid, normal), none for cubes that meet along an edge or at a corner when the caller
// asks for a least area, and the pose form (A's world vertices found face by face) the same bits
// as the form given every world vertex, at turned poses; and a least area drops no face that the
// full clip keeps (the clip stops early for a sliver: the full clip without a least area is the
// oracle).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <optional>
#include <vector>

#include "blockdem/collision/shared_face.hpp"
#include "blockdem/geometry/polyhedron.hpp"

namespace blockdem {
namespace {

// A shape at a pose: its world planes as a block computes them (n = R n_b, d = d_b + n · x) and
// its world vertices as Block::to_world does (x + q v).
struct Posed {
  Polyhedron shape;
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::vector<Halfspace> planes;
  std::vector<Eigen::Vector3d> vertices;
};

Posed posed(const Polyhedron& shape, const Eigen::Quaterniond& q, const Eigen::Vector3d& x) {
  Posed p{shape, q, x, {}, {}};
  const Eigen::Matrix3d r = q.toRotationMatrix();
  for (const Halfspace& h : shape.planes()) {
    const Eigen::Vector3d n = r * h.normal;
    p.planes.push_back({n, h.offset + n.dot(x)});
  }
  for (const Eigen::Vector3d& v : shape.vertices()) p.vertices.push_back(x + q * v);
  return p;
}

std::optional<SharedFace> by_vertices(const Posed& a, const Posed& b, double min_area = 0.0) {
  return shared_face(a.shape, a.vertices, a.planes, b.planes, 1e-9, min_area);
}

std::optional<SharedFace> by_pose(const Posed& a, const Posed& b, double min_area = 0.0) {
  return shared_face(a.shape, a.orientation, a.position, a.planes, b.planes, 1e-9, min_area);
}

const Polyhedron kCube = Polyhedron::box(Eigen::Vector3d(1.0, 1.0, 1.0));

TEST(SharedFace, CubesSideBySideShareTheirOverlapOfFaces) {
  const Eigen::Quaterniond id = Eigen::Quaterniond::Identity();
  const Posed a = posed(kCube, id, Eigen::Vector3d::Zero());
  const Posed b = posed(kCube, id, Eigen::Vector3d(1.0, 0.3, 0.0));
  const auto face = by_vertices(a, b);
  ASSERT_TRUE(face.has_value());
  // The face x = 0.5 over y in [-0.2, 0.5], z in [-0.5, 0.5] (the clip keeps what lies within
  // the tolerance, 1e-9 m, of B's other planes: the polygon is that much wider).
  EXPECT_NEAR(face->area, 0.7, 1e-8);
  EXPECT_NEAR((face->centroid - Eigen::Vector3d(0.5, 0.15, 0.0)).norm(), 0.0, 1e-8);
  EXPECT_NEAR((face->normal - Eigen::Vector3d::UnitX()).norm(), 0.0, 1e-12);
  // A least area below the face's keeps it, above drops it.
  const auto kept = by_vertices(a, b, 0.69);
  ASSERT_TRUE(kept.has_value());
  EXPECT_EQ(kept->area, face->area);
  EXPECT_FALSE(by_vertices(a, b, 0.71).has_value());
}

TEST(SharedFace, CubesMeetingAlongAnEdgeOrAtACornerShareNoFace) {
  const Eigen::Quaterniond id = Eigen::Quaterniond::Identity();
  const Posed a = posed(kCube, id, Eigen::Vector3d::Zero());
  for (const Eigen::Vector3d& at : {Eigen::Vector3d(1, 1, 0), Eigen::Vector3d(1, 1, 1),
                                    Eigen::Vector3d(0, -1, 1), Eigen::Vector3d(2, 0, 0)}) {
    const Posed b = posed(kCube, id, at);
    EXPECT_FALSE(by_vertices(a, b, 1e-6).has_value()) << at.transpose();
    EXPECT_FALSE(by_pose(a, b, 1e-6).has_value()) << at.transpose();
  }
}

TEST(SharedFace, PoseFormGivesTheBitsOfTheVerticesForm) {
  // Pairs of boxes face to face, turned together about assorted axes and moved off the origin.
  const Polyhedron brick = Polyhedron::box(Eigen::Vector3d(0.7, 0.4, 0.25));
  int found = 0;
  for (int k = 0; k < 40; ++k) {
    const Eigen::Vector3d axis =
        Eigen::Vector3d(std::sin(1.3 * k), std::cos(0.7 * k), 0.4 + 0.1 * k).normalized();
    const Eigen::Quaterniond q(Eigen::AngleAxisd(0.37 * k, axis));
    const Eigen::Vector3d origin(10.0 + k, -3.0 * k, 0.5 * k);
    const Eigen::Vector3d offset(0.1 * std::sin(k), 0.4, 0.05 * std::cos(k));  // along body y
    const Posed a = posed(brick, q, origin);
    const Posed b = posed(brick, q, origin + q * offset);
    const auto x = by_vertices(a, b);
    const auto y = by_pose(a, b);
    ASSERT_EQ(x.has_value(), y.has_value()) << k;
    if (!x) continue;
    ++found;
    EXPECT_EQ(x->plane_a, y->plane_a);
    EXPECT_EQ(x->plane_b, y->plane_b);
    EXPECT_EQ(x->area, y->area);
    EXPECT_EQ(x->centroid, y->centroid);
    ASSERT_EQ(x->polygon.size(), y->polygon.size());
    for (std::size_t v = 0; v < x->polygon.size(); ++v) EXPECT_EQ(x->polygon[v], y->polygon[v]);
    // The face y = 0.2 of A over x in [-0.35, 0.35] less the shift, z in [-0.125, 0.125] less
    // the shift, to round-off of the turned planes.
    const double expected = (0.7 - std::abs(offset.x())) * (0.25 - std::abs(offset.z()));
    EXPECT_NEAR(x->area, expected, 1e-9) << k;
  }
  EXPECT_GT(found, 30);
}

TEST(SharedFace, LeastAreaDropsOnlyWhatTheFullClipFindsBelowIt) {
  // Two sheared prisms (a parallelepiped on e1, e2, e3), B one e1 along from A: they share the
  // face spanned by e2 and e3, B slid along it by s e2 + u e3. As s or u nears 1 the shared
  // polygon narrows to a sliver along an edge (s = 1: the blocks meet along the edge only; past
  // 1 they share nothing). With a least area m, the face must be the full clip's (min_area 0,
  // which never stops early) with the same bits where that face's area exceeds m, and none where
  // it does not.
  const Eigen::Vector3d e1(1.0, 0.0, 0.0), e2(0.4, 1.0, 0.0), e3(0.2, 0.3, 1.0);
  std::vector<Eigen::Vector3d> corners;
  for (int i = 0; i < 8; ++i)
    corners.push_back((i & 1) * e1 + ((i >> 1) & 1) * e2 + ((i >> 2) & 1) * e3);
  const Polyhedron prism = Polyhedron::from_vertices(corners);
  const double fractions[] = {0.0,        0.3,        0.9, 1.0 - 1e-3,  1.0 - 1e-5,
                              1.0 - 1e-7, 1.0 - 1e-9, 1.0, 1.0 + 1e-12, 1.0 + 1e-6};
  const double least[] = {1e-9, 1e-7, 1e-6, 1e-4, 1e-2, 0.5};
  int kept = 0, dropped = 0;
  for (int turn = 0; turn < 3; ++turn) {
    const Eigen::Quaterniond q(
        Eigen::AngleAxisd(0.9 * turn, Eigen::Vector3d(1.0, 2.0, 0.5 + turn).normalized()));
    const Eigen::Vector3d origin(3.0 * turn, -2.0, 1.0 + turn);
    const Posed a = posed(prism, q, origin);
    for (double s : fractions) {
      for (double u : {0.0, 0.5, 1.0 - 1e-6, 1.0}) {
        const Posed b = posed(prism, q, origin + q * (e1 + s * e2 + u * e3));
        const auto full = by_vertices(a, b);
        for (double m : least) {
          for (const auto& face : {by_vertices(a, b, m), by_pose(a, b, m)}) {
            if (full && full->area > m) {
              ASSERT_TRUE(face.has_value()) << s << " " << u << " " << m;
              EXPECT_EQ(face->plane_a, full->plane_a);
              EXPECT_EQ(face->plane_b, full->plane_b);
              EXPECT_EQ(face->area, full->area);
              EXPECT_EQ(face->centroid, full->centroid);
              ++kept;
            } else {
              EXPECT_FALSE(face.has_value()) << s << " " << u << " " << m;
              ++dropped;
            }
          }
        }
      }
    }
  }
  // Both sides of the least area are met many times.
  EXPECT_GT(kept, 100);
  EXPECT_GT(dropped, 100);
}

}  // namespace
}  // namespace blockdem
