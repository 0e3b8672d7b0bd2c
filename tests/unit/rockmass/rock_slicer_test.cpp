// Rock slicing against closed forms (orthogonal sets: every block volume), conservation of volume
// (oblique sets), an independent polyhedron construction as oracle for every block, statistics
// of random spacing, determinism, non-persistent joints and excavation outlines.
#include "blockdem/rockmass/rock_slicer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include "blockdem/geometry/polyhedron.hpp"
#include "support/joint_sets.hpp"

namespace blockdem {
namespace {

using test::persistent_set;

// Width of the slab of [0, L] cut at origin + k*spacing that contains x.
double slab_width(double x, double first_cut, double spacing, double length) {
  double lo = 0.0, hi = length;
  for (double c = first_cut; c < length; c += spacing) {
    if (c <= x) lo = c;
    if (c > x) {
      hi = c;
      break;
    }
  }
  return hi - lo;
}

TEST(RockSlicer, ThreeOrthogonalPersistentSetsGiveExactCountAndVolumes) {
  // Box 10 x 6 x 4; cuts x = 1, 3, .., 9 (6 slabs), y = 0.75 + 1.5k (5), z = 0.5 + k (5):
  // 150 blocks, each the product of its three slab widths (closed form), to 1e-12 relative.
  RockMassSpec spec;
  spec.region = Region::box({0, 0, 0}, {10, 6, 4});
  spec.joint_sets.push_back(persistent_set("J1", 90, 90, 2.0, {1, 0, 0}));
  spec.joint_sets.push_back(persistent_set("J2", 90, 0, 1.5, {0, 0.75, 0}));
  spec.joint_sets.push_back(persistent_set("J3", 0, 0, 1.0, {0, 0, 0.5}));
  const RockMass rm = slice_rock_mass(spec);
  ASSERT_EQ(rm.blocks.size(), 150u);
  for (const auto& b : rm.blocks) {
    const Eigen::Vector3d c = b.centroid();
    const double expected = slab_width(c.x(), 1.0, 2.0, 10.0) * slab_width(c.y(), 0.75, 1.5, 6.0) *
                            slab_width(c.z(), 0.5, 1.0, 4.0);
    EXPECT_NEAR(b.volume(), expected, 1e-12 * expected);
    EXPECT_EQ(b.faces().size(), 6u);
    for (const auto& f : b.faces()) EXPECT_FALSE(f.tag.bonded);
  }
  EXPECT_NEAR(rm.total_volume(), 240.0, 1e-12 * 240.0);
  EXPECT_EQ(rm.merged_cuts, 0);
  EXPECT_EQ(rm.removed_blocks, 0);
}

// Every block checked against Polyhedron::from_planes (vertex enumeration, an independent
// construction): same volume to 1e-9, closed (each edge on exactly two faces, Euler V-E+F = 2),
// convex (every vertex inside every face plane).
void expect_valid_blocks(const RockMass& rm, double min_volume) {
  for (const auto& b : rm.blocks) {
    std::vector<Halfspace> planes;
    for (const auto& f : b.faces()) planes.push_back(f.plane);
    const Polyhedron p = Polyhedron::from_planes(planes);
    EXPECT_NEAR(p.volume(), b.volume(), 1e-9 * b.volume());
    EXPECT_GE(b.volume(), min_volume);
    std::map<std::pair<int, int>, int> edges;
    for (const auto& f : b.faces()) {
      for (std::size_t k = 0; k < f.vertices.size(); ++k) {
        const int a = f.vertices[k], c = f.vertices[(k + 1) % f.vertices.size()];
        ++edges[{std::min(a, c), std::max(a, c)}];
      }
      for (const auto& v : b.vertices()) EXPECT_LE(f.plane.signed_distance(v), 1e-9);
    }
    for (const auto& [e, n] : edges) EXPECT_EQ(n, 2);
    EXPECT_EQ(static_cast<int>(b.vertices().size()) - static_cast<int>(edges.size()) +
                  static_cast<int>(b.faces().size()),
              2);
  }
}

RockMassSpec oblique_spec() {
  RockMassSpec spec;
  spec.region = Region::box({0, 0, 0}, {20, 20, 10});
  spec.joint_sets.push_back(persistent_set("J1", 35, 120, 2.3, {10, 10, 5}));
  spec.joint_sets.push_back(persistent_set("J2", 70, 230, 3.1, {3, 4, 5}));
  spec.joint_sets.push_back(persistent_set("J3", 85, 10, 2.7, {7, 1, 2}));
  spec.settings.min_block_volume = 0.05;
  return spec;
}

TEST(RockSlicer, ObliqueSetsConserveVolumeAndMakeClosedConvexBlocks) {
  // Volume: Σ blocks = region volume (4000 m^3) to 1e-9 relative (merge mode keeps every part).
  const RockMassSpec spec = oblique_spec();
  const RockMass rm = slice_rock_mass(spec);
  EXPECT_GT(rm.blocks.size(), 300u);
  EXPECT_NEAR(rm.region_volume, 4000.0, 1e-9 * 4000.0);
  EXPECT_NEAR(rm.total_volume(), rm.region_volume, 1e-9 * rm.region_volume);
  EXPECT_GT(rm.merged_cuts, 0);
  expect_valid_blocks(rm, spec.settings.min_block_volume);
}

TEST(RockSlicer, RemovedSmallBlocksAreReportedWithTheirVolume) {
  // Σ blocks + removed volume = region volume to 1e-9 relative.
  RockMassSpec spec = oblique_spec();
  spec.settings.small_blocks = SlicingSettings::SmallBlocks::remove;
  const RockMass rm = slice_rock_mass(spec);
  EXPECT_GT(rm.removed_blocks, 0);
  EXPECT_NEAR(rm.total_volume() + rm.removed_volume, rm.region_volume, 1e-9 * rm.region_volume);
  expect_valid_blocks(rm, spec.settings.min_block_volume);
}

TEST(RockSlicer, AspectRatioLimitMergesThinSlabs) {
  // Slabs 0.1 m thick in a 2 m cube have aspect ratio 20; with a limit of 5 no block exceeds 5.
  RockMassSpec spec;
  spec.region = Region::box({0, 0, 0}, {2, 2, 2});
  spec.joint_sets.push_back(persistent_set("J1", 90, 90, 0.1, {0.05, 0, 0}));
  spec.settings.max_aspect_ratio = 5.0;
  const RockMass rm = slice_rock_mass(spec);
  EXPECT_GT(rm.merged_cuts, 0);
  for (const auto& b : rm.blocks) EXPECT_LE(b.aspect_ratio(), 5.0 + 1e-12);
  EXPECT_NEAR(rm.total_volume(), 8.0, 1e-12 * 8.0);
}

// Spacings measured from the blocks: the distinct offsets of faces made by set 0, differenced.
std::vector<double> measured_spacings(const RockMass& rm, const Eigen::Vector3d& n) {
  std::set<double> offsets;
  for (const auto& b : rm.blocks) {
    for (const auto& f : b.faces()) {
      if (f.tag.source == FaceSource::joint && f.tag.index == 0)
        offsets.insert(std::round(std::abs(f.plane.normal.dot(n) * f.plane.offset) * 1e9) / 1e9);
    }
  }
  std::vector<double> d(offsets.begin(), offsets.end());
  std::vector<double> s;
  for (std::size_t i = 1; i < d.size(); ++i) s.push_back(d[i] - d[i - 1]);
  return s;
}

TEST(RockSlicer, RandomSpacingMeanMatchesWithinItsStatisticalError) {
  // Horizontal joints in a 2 x 2 x 600 m column; the sample mean of n spacings must lie within
  // 4 standard errors (sd/sqrt(n)) of the input mean (a 4-sigma band: fails by chance < 1e-4).
  struct Case {
    Spacing::Distribution dist;
    double mean, sd;
  };
  for (const Case c : {Case{Spacing::Distribution::exponential, 2.0, 2.0},
                       Case{Spacing::Distribution::normal, 2.0, 0.5},
                       Case{Spacing::Distribution::lognormal, 2.0, 1.0}}) {
    RockMassSpec spec;
    spec.region = Region::box({0, 0, 0}, {2, 2, 600});
    JointSet s = persistent_set("J", 0, 0, c.mean, {1, 1, 300});
    s.spacing.distribution = c.dist;
    s.spacing.sd = c.sd;
    s.spacing.seed = 12345;
    spec.joint_sets.push_back(s);
    const RockMass rm = slice_rock_mass(spec);
    const auto sp = measured_spacings(rm, Eigen::Vector3d::UnitZ());
    ASSERT_GT(sp.size(), 200u);
    double mean = 0.0;
    for (double x : sp) mean += x;
    mean /= static_cast<double>(sp.size());
    const double se = c.sd / std::sqrt(static_cast<double>(sp.size()));
    EXPECT_NEAR(mean, c.mean, 4.0 * se) << "distribution " << static_cast<int>(c.dist);
  }
}

TEST(RockSlicer, SameSeedSameBlocksOtherSeedOtherBlocks) {
  auto make = [](std::uint64_t seed) {
    RockMassSpec spec = oblique_spec();
    for (auto& s : spec.joint_sets) {
      s.spacing.distribution = Spacing::Distribution::lognormal;
      s.spacing.sd = 1.0;
      s.spacing.seed = seed;
    }
    return slice_rock_mass(spec);
  };
  const RockMass a = make(7), b = make(7), c = make(8);
  ASSERT_EQ(a.blocks.size(), b.blocks.size());
  for (std::size_t i = 0; i < a.blocks.size(); ++i) {
    EXPECT_EQ(a.blocks[i].volume(), b.blocks[i].volume());  // bit for bit
    EXPECT_EQ(a.blocks[i].vertices(), b.blocks[i].vertices());
  }
  bool differs = a.blocks.size() != c.blocks.size();
  for (std::size_t i = 0; !differs && i < a.blocks.size(); ++i)
    differs = a.blocks[i].volume() != c.blocks[i].volume();
  EXPECT_TRUE(differs);
}

JointSet disc_joint(const Eigen::Vector3d& centre, double radius) {
  JointSet s = persistent_set("D", 30, 45, 1.0, centre);
  JointExtent e;
  e.radius = radius;
  s.extent = e;
  s.centres = {centre};
  return s;
}

TEST(RockSlicer, DiscJointInsideABlockMakesABondedCut) {
  // A disc of radius 0.5 m in the middle of a 4 m cube: the cut goes through the block, but the
  // cut face reaches beyond the disc, so both sides of it are bonded (intact rock): the block is
  // held whole. Volume conserved to 1e-12.
  RockMassSpec spec;
  spec.region = Region::box({0, 0, 0}, {4, 4, 4});
  spec.joint_sets.push_back(disc_joint({2, 2, 2}, 0.5));
  const RockMass rm = slice_rock_mass(spec);
  ASSERT_EQ(rm.blocks.size(), 2u);
  int cut_faces = 0;
  for (const auto& b : rm.blocks) {
    for (const auto& f : b.faces()) {
      if (f.tag.source != FaceSource::joint) continue;
      ++cut_faces;
      EXPECT_TRUE(f.tag.bonded);
    }
  }
  EXPECT_EQ(cut_faces, 2);
  EXPECT_NEAR(rm.total_volume(), 64.0, 1e-12 * 64);

  // A disc larger than the block: the cut face lies wholly inside it, an open joint.
  spec.joint_sets[0] = disc_joint({2, 2, 2}, 10.0);
  for (const auto& b : slice_rock_mass(spec).blocks) {
    for (const auto& f : b.faces()) {
      if (f.tag.source == FaceSource::joint) {
        EXPECT_FALSE(f.tag.bonded);
      }
    }
  }
}

TEST(RockSlicer, DiscJointCutsOnlyTheBlocksItPassesThrough) {
  // Two blocks (x < 2, x > 2); a disc of radius 0.4 m centred in the second cuts it alone: 3.
  RockMassSpec spec;
  spec.region = Region::box({0, 0, 0}, {4, 2, 2});
  spec.joint_sets.push_back(persistent_set("J1", 90, 90, 10.0, {2, 0, 0}));
  spec.joint_sets.push_back(disc_joint({3, 1, 1}, 0.4));
  const RockMass rm = slice_rock_mass(spec);
  EXPECT_EQ(rm.blocks.size(), 3u);
  for (const auto& b : rm.blocks) {
    if (b.centroid().x() < 2.0) {
      EXPECT_NEAR(b.volume(), 8.0, 1e-12);
    }
  }
}

TEST(RockSlicer, BoxExcavationOutlineCutsLeaveTheExcavatedBlockWhole) {
  // An intact 10 m cube with a 2 m box excavation [4, 6]^3: the outline cuts make one block of
  // exactly 8 m^3 inside, all six faces open excavation faces; every extension is bonded.
  RockMassSpec spec;
  spec.region = Region::box({0, 0, 0}, {10, 10, 10});
  Excavation ex;
  ex.name = "box";
  ex.planes = Region::box({4, 4, 4}, {6, 6, 6}).planes;
  spec.excavations.push_back(ex);
  const RockMass rm = slice_rock_mass(spec);
  const auto inside = rm.blocks_inside(spec, 0);
  ASSERT_EQ(inside.size(), 1u);
  const ConvexCell& b = rm.blocks[inside[0]];
  EXPECT_NEAR(b.volume(), 8.0, 1e-12);
  for (const auto& f : b.faces()) {
    EXPECT_EQ(f.tag.source, FaceSource::excavation);
    EXPECT_FALSE(f.tag.bonded);
  }
  int bonded = 0;
  for (const auto& c : rm.blocks) {
    for (const auto& f : c.faces()) bonded += f.tag.bonded ? 1 : 0;
  }
  EXPECT_GT(bonded, 0);
  EXPECT_NEAR(rm.total_volume(), 1000.0, 1e-12 * 1000);
}

void expect_error(const RockMassSpec& spec, const std::string& key) {
  try {
    slice_rock_mass(spec);
    ADD_FAILURE() << "no error for " << key;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
  }
}

TEST(RockSlicer, BadInputNamesTheKey) {
  RockMassSpec spec;
  spec.region = Region::box({0, 0, 0}, {4, 4, 4});
  spec.joint_sets.push_back(persistent_set("J1", 95, 0, 1, {0, 0, 0}));
  expect_error(spec, "joint_sets[1].dip_deg");
  spec.joint_sets[0] = persistent_set("J1", 45, 360, 1, {0, 0, 0});
  expect_error(spec, "joint_sets[1].dip_direction_deg");
  spec.joint_sets[0] = persistent_set("J1", 45, 0, 0, {0, 0, 0});
  expect_error(spec, "joint_sets[1].spacing");
  spec.joint_sets[0] = persistent_set("J1", 45, 0, 1, {0, 0, 0});
  spec.joint_sets[0].spacing.distribution = Spacing::Distribution::exponential;
  expect_error(spec, "joint_sets[1].spacing.seed");
  spec.joint_sets.clear();
  Excavation ex{"far", Region::box({10, 10, 10}, {11, 11, 11}).planes};
  spec.excavations.push_back(ex);
  expect_error(spec, "excavations[1]");
  spec.excavations.clear();
  spec.region.planes.pop_back();  // five faces of a box: open at the top
  expect_error(spec, "region");
}

}  // namespace
}  // namespace blockdem
