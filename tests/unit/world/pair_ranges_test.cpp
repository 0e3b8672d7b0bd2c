// A one-process step's broad phase by ranges of blocks (world_pairs.cpp) against the list it
// replaced, the threads' lists joined and sorted: the same world stepped both ways ends each step
// in the same state, bit for bit.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "blockdem/response/in_situ.hpp"
#include "validation/scenes.hpp"

// A namespace of this file's own: the unity build compiles it with other test files.
namespace blockdem::test::pair_ranges_test {
namespace {

// 4 layers of 12 x 12 cubes (576 blocks, three ranges of 256 and a short one) over a fixed layer
// of cubes, side by side in a layer (their boxes touch: pairs from the first step), every layer
// 2 mm above the one below and sliding east: the layers fall together, so a
// whole layer's pairs with the layer below appear in one step (more than a range's room), and
// then a few pairs come and go each step as the layers slide. No box is large, so the grid takes
// the ranges. With `far_plate`, a fixed plate far away, large beside the cubes, added last: the
// grid then joins the threads' lists, and no other block's pairs change.
// With `bonded`, the joints have cohesion and tensile strength: the cubes of a layer start bonded
// side by side, and as the odd rows slide against the even ones the bonds open (their pairs kept
// after the boxes part: World::keep_open_bonds) and break.
World sliding_layers(bool far_plate, int threads, bool bonded = false) {
  WorldSettings s;
  s.gravity = Eigen::Vector3d(0, 0, -9.81);
  s.damping = 0.1;
  s.threads = threads;
  World w(s);
  JointLaw law;
  law.name = "joint";
  law.normal = LinearNormal{5e8};
  JointStrength strength = JointStrength::from_friction_deg(20.0);
  if (bonded) {
    strength.cohesion = 2e3;
    strength.tensile_strength = 1e3;
  }
  law.shear = LinearShear{5e7, strength};
  w.add_joint_law(law);
  w.add_joint_rule(JointRule{"", "", 0});
  const double edge = 0.1, gap = 0.002;
  for (int layer = 0; layer < 5; ++layer) {
    for (int y = 0; y < 12; ++y) {
      for (int x = 0; x < 12; ++x) {
        // Odd rows start 3 um east of even rows and run west of them: as their rows pass, each
        // cube trades its pair with the cube south-west (north-west) of it for the one
        // south-east (north-east) in one step, so a range's pairs change with their count kept.
        const double shift = y % 2 == 1 ? 3e-6 : 0.0;
        const Eigen::Vector3d centre((x + 0.5) * edge + 0.01 * layer + shift, (y + 0.5) * edge,
                                     (layer + 0.5) * (edge + gap));
        Block b = box_block(
            Eigen::Vector3d::Constant(edge), centre, 2500.0,
            layer == 0 ? Motion::fixed : Motion::free,
            "c" + std::to_string(layer) + "_" + std::to_string(y) + "_" + std::to_string(x));
        if (layer > 0)
          b.velocity = Eigen::Vector3d(0.05 * layer + (y % 2 == 1 ? -0.05 : 0.05), 0.0, 0.0);
        w.add_block(b);
      }
    }
  }
  if (far_plate)
    w.add_block(box_block({5.0, 5.0, 0.1}, {50.0, 50.0, -10.0}, 2500.0, Motion::fixed, "plate"));
  return w;
}

// The first `blocks` blocks' state and loads and every contact's force, as raw bytes.
std::vector<char> record(const World& w, std::size_t blocks) {
  std::vector<char> out;
  const auto append = [&](const double* p, std::size_t n) {
    const char* c = reinterpret_cast<const char*>(p);
    out.insert(out.end(), c, c + n * sizeof(double));
  };
  for (std::size_t i = 0; i < blocks; ++i) {
    const Block& b = w.blocks()[i];
    append(b.position.data(), 3);
    append(b.velocity.data(), 3);
    append(b.angular_velocity.data(), 3);
    append(b.orientation.coeffs().data(), 4);
    append(b.force.data(), 3);
    append(b.torque.data(), 3);
  }
  for (const Contact* c : w.contacts()) {
    const double ends[2] = {static_cast<double>(c->a), static_cast<double>(c->b)};
    append(ends, 2);
    append(&c->normal_force, 1);
    append(c->shear.force.data(), 3);
  }
  const double counts[2] = {static_cast<double>(w.contact_count()),
                            static_cast<double>(w.candidate_pair_count())};
  append(counts, 2);
  return out;
}

// Steps both worlds `steps` times: every step's record (and broken bonds) the same bytes.
::testing::AssertionResult step_alike(World& ranges, World& joined, int steps) {
  const std::size_t blocks = ranges.blocks().size();
  for (int step = 1; step <= steps; ++step) {
    ranges.step();
    joined.step();
    if (record(ranges, blocks) != record(joined, blocks) ||
        ranges.broken_bond_count() != joined.broken_bond_count())
      return ::testing::AssertionFailure() << "first difference at step " << step;
  }
  return ::testing::AssertionSuccess();
}

// Oracle: the same world with the far plate, whose broad phase joins the threads' lists (the
// step before the ranges). Tolerance: none. The store merged from the ranges' changes, the list
// made after all (a large shift: more than an eighth of the slots would come from outside the
// share of new places of the thread that moves them) and the step where no range changed are
// each taken.
TEST(PairRanges, StepsBitIdenticalToTheJoinedList) {
  for (int threads : {1, 3}) {
    World ranges = sliding_layers(false, threads);
    World joined = sliding_layers(true, threads);
    ASSERT_TRUE(step_alike(ranges, joined, 400)) << threads << " threads";
    EXPECT_GT(ranges.contact_count(), 144u);  // more than a layer landed
    const World::PairListCounts& r = ranges.pair_list_counts();
    const World::PairListCounts& j = joined.pair_list_counts();
    EXPECT_EQ(j.joined, 400) << threads << " threads";
    EXPECT_EQ(r.joined, 1);  // the first step: no slots yet
    EXPECT_GT(r.changed, 0) << threads << " threads";
    EXPECT_GT(r.listed, 0) << threads << " threads";
    EXPECT_GT(r.unchanged, 0) << threads << " threads";
    EXPECT_EQ(r.unchanged + r.changed + r.listed + r.joined, 400);
  }
}

// The same with bonded joints: the ranges' changes keep the open bonds' pairs as the joined
// list's union with them does (bit for bit), while bonds open and break.
TEST(PairRanges, OpenBondsKeepTheirPairsAsWithTheJoinedList) {
  for (int threads : {1, 3}) {
    World ranges = sliding_layers(false, threads, true);
    World joined = sliding_layers(true, threads, true);
    ASSERT_TRUE(step_alike(ranges, joined, 400)) << threads << " threads";
    EXPECT_GT(ranges.broken_bond_count(), 0) << threads << " threads";
    EXPECT_GT(ranges.pair_list_counts().changed, 0) << threads << " threads";
  }
}

// 300 columns of two cubes sharing a face, the lower fixed, the joint between them prestressed
// by a uniform compressive field; every third upper cube leaves upwards at 3 m/s. Its joint keeps
// its pair after the boxes part (the prestressed joints' pairs are kept whatever the broad
// phase finds): the joined list merges the joints in, the ranges keep the joints' slots.
// With `far_plate` the grid joins the threads' lists instead.
World parting_columns(bool far_plate, int threads) {
  WorldSettings s;
  s.damping = 0.0;
  s.threads = threads;
  World w = linear_world(5e9, 5e8, 30.0, s);
  const double edge = 0.1;
  std::vector<std::pair<int, int>> joints;
  for (int c = 0; c < 300; ++c) {
    const Eigen::Vector3d foot((c % 20) * 0.2, (c / 20) * 0.2, 0.5 * edge);
    w.add_block(box_block(Eigen::Vector3d::Constant(edge), foot, 2500.0, Motion::fixed,
                          "f" + std::to_string(c)));
    Block top = box_block(Eigen::Vector3d::Constant(edge), foot + Eigen::Vector3d(0, 0, edge),
                          2500.0, Motion::free, "t" + std::to_string(c));
    if (c % 3 == 0) top.velocity = Eigen::Vector3d(0, 0, 3.0);
    w.add_block(top);
    joints.emplace_back(2 * c, 2 * c + 1);
  }
  if (far_plate)
    w.add_block(box_block({5.0, 5.0, 0.1}, {50.0, 50.0, -10.0}, 2500.0, Motion::fixed, "plate"));
  StressField field;
  field.stress = Eigen::Matrix3d::Identity() * 1e5;
  EXPECT_EQ(w.prestress_joints(field, joints), joints.size());
  return w;
}

// Oracle: the same world with the far plate (the threads' lists joined). Tolerance: none.
// Every joint has had its slot since the first step, so no step makes a list of every pair: the
// parting joints' slots stay in place (a scene whose in-situ joints' boxes miss each other by
// round-off made the list at every step).
TEST(PairRanges, PartingPrestressedJointsKeepTheirSlotsAsTheJoinedStepKeepsTheirPairs) {
  for (int threads : {1, 3}) {
    World ranges = parting_columns(false, threads);
    World joined = parting_columns(true, threads);
    ASSERT_TRUE(step_alike(ranges, joined, 300)) << threads << " threads";
    const World::PairListCounts& r = ranges.pair_list_counts();
    EXPECT_EQ(r.listed, 0) << threads << " threads";
    EXPECT_EQ(r.joined, 1) << threads << " threads";  // the first step: no slots yet
    EXPECT_EQ(ranges.candidate_pair_count(), joined.candidate_pair_count());
    // The joints that parted are still candidate pairs: 300 joints and no other pair.
    EXPECT_EQ(ranges.candidate_pair_count(), 300u) << threads << " threads";
  }
}

}  // namespace
}  // namespace blockdem::test::pair_ranges_test
