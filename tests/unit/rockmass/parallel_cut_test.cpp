// A rock mass cut, made into blocks and written on several threads is the one thread's, bit for
// bit: the parts, their order, the merged and removed volumes' sums, the world blocks and every
// byte of the files. The numbers in blocks.vtk are checked against the C++ stream's text at
// precision 12 (what the file held before it was written on threads).
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "blockdem/numerics/shares.hpp"
#include "blockdem/rockmass/rock_mass_model.hpp"
#include "blockdem/rockmass/rock_mass_output.hpp"
#include "blockdem/rockmass/rock_slicer.hpp"
#include "support/joint_sets.hpp"
#include "support/temp_path.hpp"

namespace blockdem {
namespace {

using test::persistent_set;

// Three oblique persistent sets, one of random discs (bonded and open cut faces) and a box
// excavation (outline facets), with small parts merged back or removed: every path of the cut.
RockMassSpec spec(SlicingSettings::SmallBlocks small) {
  RockMassSpec s;
  s.region = Region::box({0, 0, 0}, {16, 12, 10});
  s.joint_sets.push_back(persistent_set("J1", 80, 10, 1.1, {0.3, 0.2, 0.1}));
  s.joint_sets.push_back(persistent_set("J2", 70, 230, 1.7, {3, 4, 5}));
  s.joint_sets.push_back(persistent_set("J3", 25, 120, 1.3, {7, 1, 2}));
  JointSet discs = persistent_set("D", 55, 300, 2.0, {6, 5, 4});
  JointExtent disc;
  disc.radius = 2.5;
  discs.extent = disc;
  discs.placement_seed = 11;
  discs.persistence = 0.7;
  s.joint_sets.push_back(discs);
  Excavation box;
  box.name = "box";
  box.planes = {Halfspace{{1, 0, 0}, 7.5}, Halfspace{{-1, 0, 0}, -4.5},
                Halfspace{{0, 1, 0}, 6.5}, Halfspace{{0, -1, 0}, -3.5},
                Halfspace{{0, 0, 1}, 5.5}, Halfspace{{0, 0, -1}, -2.5}};
  s.excavations.push_back(box);
  s.settings.min_block_volume = 0.02;
  s.settings.small_blocks = small;
  return s;
}

std::uint64_t bits(double x) {
  return std::bit_cast<std::uint64_t>(x);
}

void expect_same_cells(const RockMass& a, const RockMass& b) {
  EXPECT_EQ(a.merged_cuts, b.merged_cuts);
  EXPECT_EQ(bits(a.merged_volume), bits(b.merged_volume));
  EXPECT_EQ(a.removed_blocks, b.removed_blocks);
  EXPECT_EQ(bits(a.removed_volume), bits(b.removed_volume));
  ASSERT_EQ(a.blocks.size(), b.blocks.size());
  for (std::size_t i = 0; i < a.blocks.size(); ++i) {
    const ConvexCell &x = a.blocks[i], &y = b.blocks[i];
    ASSERT_EQ(x.vertices().size(), y.vertices().size()) << "block " << i;
    for (std::size_t v = 0; v < x.vertices().size(); ++v) {
      for (int k = 0; k < 3; ++k)
        ASSERT_EQ(bits(x.vertices()[v][k]), bits(y.vertices()[v][k])) << "block " << i;
    }
    ASSERT_EQ(x.faces().size(), y.faces().size()) << "block " << i;
    for (std::size_t f = 0; f < x.faces().size(); ++f) {
      const CellFace &p = x.faces()[f], &q = y.faces()[f];
      EXPECT_EQ(p.vertices, q.vertices) << "block " << i;
      EXPECT_EQ(p.tag.source, q.tag.source);
      EXPECT_EQ(p.tag.index, q.tag.index);
      EXPECT_EQ(p.tag.joint, q.tag.joint);
      EXPECT_EQ(p.tag.bonded, q.tag.bonded);
    }
  }
}

TEST(ParallelCut, PartsAndTalliesOnThreeThreadsAreThoseOfOne) {
  for (auto small : {SlicingSettings::SmallBlocks::merge, SlicingSettings::SmallBlocks::remove}) {
    RockMassSpec one = spec(small), three = spec(small);
    one.settings.threads = 1;
    three.settings.threads = 3;
    const RockMass a = slice_rock_mass(one);
    const RockMass b = slice_rock_mass(three);
    // A cut with work for three threads that merges (or removes) parts and bonds faces.
    ASSERT_GT(a.blocks.size(), 500u);
    EXPECT_GT(small == SlicingSettings::SmallBlocks::merge ? a.merged_cuts : a.removed_blocks, 0);
    bool bonded = false;
    for (const auto& c : a.blocks) {
      for (const auto& f : c.faces()) bonded |= f.tag.bonded;
    }
    EXPECT_TRUE(bonded);
    expect_same_cells(a, b);
  }
}

RockMassModel model() {
  RockMassModel m;
  m.spec = spec(SlicingSettings::SmallBlocks::merge);
  m.spec.settings.threads = 1;
  m.rock_mass = slice_rock_mass(m.spec);
  m.density = 2600.0;
  m.set_laws = {0, 1, -1, 0};
  m.default_law = 2;
  BoundaryCondition fixed;
  fixed.faces = {4};  // z_min
  m.boundaries.push_back(fixed);
  return m;
}

TEST(ParallelCut, BlocksMadeOnThreeThreadsAreThoseOfOne) {
  const RockMassModel m = model();
  const RockMassBlocks a = make_rock_mass_blocks(m, 1);
  const RockMassBlocks b = make_rock_mass_blocks(m, 3);
  ASSERT_EQ(a.blocks.size(), m.rock_mass.blocks.size());
  ASSERT_EQ(b.blocks.size(), a.blocks.size());
  EXPECT_EQ(a.face_laws, b.face_laws);
  EXPECT_EQ(a.face_sets, b.face_sets);
  EXPECT_EQ(a.excavated, b.excavated);
  for (std::size_t i = 0; i < a.blocks.size(); ++i) {
    const Block &x = a.blocks[i], &y = b.blocks[i];
    ASSERT_EQ(x.name, y.name);
    EXPECT_EQ(x.name, RockMassModel::block_name(i));
    EXPECT_EQ(x.motion, y.motion);
    EXPECT_EQ(bits(x.mass), bits(y.mass));
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(bits(x.position[k]), bits(y.position[k])) << x.name;
      EXPECT_EQ(bits(x.inertia[k]), bits(y.inertia[k])) << x.name;
    }
    EXPECT_EQ(bits(x.orientation.w()), bits(y.orientation.w())) << x.name;
    EXPECT_EQ(bits(x.orientation.x()), bits(y.orientation.x())) << x.name;
    ASSERT_EQ(x.world_planes.size(), y.world_planes.size());
    for (std::size_t j = 0; j < x.world_planes.size(); ++j)
      EXPECT_EQ(bits(x.world_planes[j].offset), bits(y.world_planes[j].offset)) << x.name;
  }
}

std::string file_text(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

// Where two texts first differ (npos: nowhere), for a message that does not print megabytes.
std::size_t first_difference(const std::string& a, const std::string& b) {
  const std::size_t n = std::min(a.size(), b.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (a[i] != b[i]) return i;
  }
  return a.size() == b.size() ? std::string::npos : n;
}

TEST(ParallelCut, FilesWrittenOnThreeThreadsAreThoseOfOneAndTheStreamsNumbers) {
  const RockMassModel m = model();
  // Pieces of 256 blocks, formatted 4 a thread at a time: several rounds of several pieces.
  ASSERT_GT(m.rock_mass.blocks.size(), 5u * 256u);
  const auto one = test::temp_path("cut_one"), three = test::temp_path("cut_three");
  write_rock_mass(m, one, 1);
  write_rock_mass(m, three, 3);
  for (const char* name : {"blocks.vtk", "blocks.csv", "faces.csv", "rock_mass.json"}) {
    const std::string a = file_text(one / name);
    EXPECT_FALSE(a.empty()) << name;
    EXPECT_EQ(first_difference(a, file_text(three / name)), std::string::npos) << name;
  }
  // The points as a C++ stream at precision 12 writes them, in the blocks' order.
  std::ostringstream expected;
  expected.precision(12);
  std::size_t points = 0;
  for (const auto& b : m.rock_mass.blocks) {
    for (const auto& v : b.vertices()) expected << v.x() << " " << v.y() << " " << v.z() << "\n";
    points += b.vertices().size();
  }
  const std::string vtk = file_text(one / "blocks.vtk");
  const std::string header = "POINTS " + std::to_string(points) + " double\n";
  const auto at = vtk.find(header);
  ASSERT_NE(at, std::string::npos);
  EXPECT_EQ(first_difference(vtk.substr(at + header.size(), expected.str().size()), expected.str()),
            std::string::npos);
  EXPECT_EQ(vtk.compare(at + header.size() + expected.str().size(), 9, "POLYGONS "), 0);
}

TEST(ParallelCut, AShareThatThrowsPassesTheFirstSharesErrorOnAfterEveryShareRan) {
  // Shares 2 and 5 of 8 throw: every share runs, and the error is share 2's, as on one thread.
  for (int threads : {1, 3}) {
    std::vector<int> ran(8, 0);
    std::string what;
    try {
      for_each_share(8, 800, threads, [&](std::int64_t k, std::int64_t begin, std::int64_t end) {
        ran[static_cast<std::size_t>(k)] = static_cast<int>(end - begin);
        if (k == 2 || k == 5) throw std::runtime_error("share " + std::to_string(k));
      });
    } catch (const std::runtime_error& e) {
      what = e.what();
    }
    EXPECT_EQ(what, "share 2") << threads << " threads";
    EXPECT_EQ(ran, std::vector<int>(8, 100)) << threads << " threads";
  }
}

}  // namespace
}  // namespace blockdem
