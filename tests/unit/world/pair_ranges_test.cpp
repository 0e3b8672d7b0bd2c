// A one-process step's broad phase by ranges of blocks (world_pairs.cpp) against the list it
// replaced, the threads' lists joined and sorted: the same world stepped both ways ends each step
// in the same state, bit for bit.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

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
World sliding_layers(bool far_plate, int threads) {
  WorldSettings s;
  s.gravity = Eigen::Vector3d(0, 0, -9.81);
  s.damping = 0.1;
  s.threads = threads;
  World w = linear_world(5e8, 5e7, 20.0, s);
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

// Oracle: the same world with the far plate, whose broad phase joins the threads' lists (the
// step before the ranges). Tolerance: none. Both ways of closing up the ranges' list are taken
// (in place, and a list of its own when a layer lands), and so is the step without a list.
TEST(PairRanges, StepsBitIdenticalToTheJoinedList) {
  for (int threads : {1, 3}) {
    World ranges = sliding_layers(false, threads);
    World joined = sliding_layers(true, threads);
    const std::size_t blocks = ranges.blocks().size();
    std::size_t touching = 0;
    for (int step = 1; step <= 400; ++step) {
      ranges.step();
      joined.step();
      ASSERT_TRUE(record(ranges, blocks) == record(joined, blocks))
          << threads << " threads: first difference at step " << step;
      touching = ranges.contact_count();
    }
    EXPECT_GT(touching, 144u);  // more than a layer landed
    const World::PairListCounts& r = ranges.pair_list_counts();
    const World::PairListCounts& j = joined.pair_list_counts();
    EXPECT_EQ(j.joined, 400) << threads << " threads";
    EXPECT_EQ(r.joined, 1);  // the first step: no slots yet
    EXPECT_GT(r.in_place, 0) << threads << " threads";
    EXPECT_GT(r.own_list, 0) << threads << " threads";
    EXPECT_GT(r.slots_own, 0) << threads << " threads";
    EXPECT_EQ(r.slots_own + r.in_place + r.own_list + r.joined, 400);
  }
}

}  // namespace
}  // namespace blockdem::test::pair_ranges_test
