// One joint law per face (response/face_laws.hpp): a contact takes the law of the faces in
// contact. Two unit cubes, B resting on A's top face: the law of A's top or of B's bottom,
// whichever names one (the better-aligned face when both do, A on a tie); the group rules' law
// when neither face names one; and, for a contact point out of reach of every face, the face
// best aligned with the contact normal.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <numbers>
#include <vector>

#include "../../validation/scenes.hpp"
#include "blockdem/response/face_laws.hpp"

namespace blockdem::test::face_laws {
namespace {

constexpr double kOverlap = 1e-4;  // m
constexpr int kGroupLaw = 7;

// A: the unit cube about the origin (fixed); B: the unit cube above it, turned by `turn_deg`
// about x, sunk kOverlap into A's top face.
struct Pair {
  Block a, b;
  ContactGeometry g;
};

Pair cubes(double turn_deg = 0.0) {
  Pair p{box_block({1, 1, 1}, {0, 0, 0}, 2500.0, Motion::fixed, "a"),
         box_block({1, 1, 1}, {0, 0, 1.0 - kOverlap}, 2500.0, Motion::free, "b"),
         {}};
  p.b.orientation = Eigen::Quaterniond(
      Eigen::AngleAxisd(turn_deg * std::numbers::pi / 180.0, Eigen::Vector3d::UnitX()));
  p.a.update_world_geometry();
  p.b.update_world_geometry();
  p.g.touching = true;
  p.g.normal = Eigen::Vector3d::UnitZ();  // from A to B
  p.g.point = Eigen::Vector3d(0.1, -0.2, 0.5 - kOverlap / 2);
  p.g.overlap = kOverlap;
  return p;
}

// A law per plane of `block`: `law` on the plane whose world normal is nearest `normal`, `other`
// on the rest.
std::vector<int> laws_facing(const Block& block, const Eigen::Vector3d& normal, int law,
                             int other = -1) {
  std::vector<int> laws(block.world_planes.size(), other);
  std::size_t best = 0;
  for (std::size_t i = 0; i < laws.size(); ++i)
    if (block.world_planes[i].normal.dot(normal) > block.world_planes[best].normal.dot(normal))
      best = i;
  laws[best] = law;
  return laws;
}

TEST(FaceLaws, TheContactTakesTheLawOfTheFaceThatNamesOne) {
  const Pair p = cubes();
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const std::vector<int> none;
  EXPECT_EQ(face_law_for_contact(p.a, none, p.b, none, p.g, kGroupLaw), kGroupLaw);
  // Only A's faces carry laws (B was not cut by a joint set), and only B's.
  EXPECT_EQ(face_law_for_contact(p.a, laws_facing(p.a, up, 2), p.b, none, p.g, kGroupLaw), 2);
  EXPECT_EQ(face_law_for_contact(p.a, none, p.b, laws_facing(p.b, -up, 5), p.g, kGroupLaw), 5);
  // Both lists, but the face in contact names no law on one side: the other side's. A law on
  // A's other faces does not count.
  EXPECT_EQ(face_law_for_contact(p.a, laws_facing(p.a, up, -1, 3), p.b, laws_facing(p.b, -up, 5),
                                 p.g, kGroupLaw),
            5);
  EXPECT_EQ(face_law_for_contact(p.a, laws_facing(p.a, up, 2), p.b, laws_facing(p.b, -up, -1, 4),
                                 p.g, kGroupLaw),
            2);
  // Neither face in contact names one: the group rules' law.
  EXPECT_EQ(face_law_for_contact(p.a, laws_facing(p.a, up, -1, 3), p.b,
                                 laws_facing(p.b, -up, -1, 4), p.g, kGroupLaw),
            kGroupLaw);
}

TEST(FaceLaws, BothFacesNameALawTheBetterAlignedWins) {
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  // Face to face: a tie, A's law.
  const Pair flat = cubes();
  EXPECT_EQ(face_law_for_contact(flat.a, laws_facing(flat.a, up, 2), flat.b,
                                 laws_facing(flat.b, -up, 5), flat.g, kGroupLaw),
            2);
  // B turned by 10 degrees about x (resting on an edge): with the normal along A's top face, A's
  // face is the better aligned (1 against cos 10°), so A's law.
  Pair turned = cubes(10.0);
  const std::vector<int> laws_a = laws_facing(turned.a, up, 2);
  const std::vector<int> laws_b = laws_facing(turned.b, -up, 5);
  EXPECT_EQ(face_law_for_contact(turned.a, laws_a, turned.b, laws_b, turned.g, kGroupLaw), 2);
  // The normal along B's bottom face and the point just inside it, 7.5 mm above A's top: B's
  // face is in reach and aligned; A's top, out of reach, is still A's best-aligned plane
  // (cos 10°), so B's law.
  const Eigen::Vector3d along_b =
      Eigen::AngleAxisd(10.0 * std::numbers::pi / 180.0, Eigen::Vector3d::UnitX()) * up;
  turned.g.normal = along_b;
  turned.g.point = turned.b.position - (0.5 - kOverlap / 4) * along_b;
  EXPECT_EQ(face_law_for_contact(turned.a, laws_a, turned.b, laws_b, turned.g, kGroupLaw), 5);
}

// A contact point deep inside A (farther than the reach from every face): the plane best aligned
// with the outward normal, for each direction of the normal.
TEST(FaceLaws, APointOutOfReachOfEveryFaceTakesTheBestAlignedPlane) {
  const Pair p = cubes();
  for (const Eigen::Vector3d& outward :
       {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0.2, -1, 0.1).normalized(),
        Eigen::Vector3d(-1, 0.3, 0).normalized()}) {
    const auto [face, dot] = contact_face(p.a, outward, Eigen::Vector3d::Zero(), 1e-3);
    ASSERT_GE(face, 0);
    double best = -2.0;
    for (const Halfspace& h : p.a.world_planes) best = std::max(best, h.normal.dot(outward));
    EXPECT_EQ(dot, best) << outward.transpose();
    EXPECT_EQ(p.a.world_planes[static_cast<std::size_t>(face)].normal.dot(outward), best);
  }
}

}  // namespace
}  // namespace blockdem::test::face_laws
