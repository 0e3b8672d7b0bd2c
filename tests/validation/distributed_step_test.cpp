// The distributed step without MPI: K worlds in K threads exchange pair slots, ghost blocks and
// their parts of the global sums through an in-process all-gather (the role MPI plays between
// processes). Every world, made whole, is in the same state, bit for bit, as one world alone
// (the oracle), also while the blocks are partitioned again every 25 steps so that blocks and
// contacts change owner (migration).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include "blockdem/world/state_stream.hpp"
#include "brick_pile.hpp"
#include "support/thread_distribution.hpp"

// A namespace of this file's own: the unity build (cmake/build_speed.cmake) compiles it together
// with other test files that define helpers of the same names.
namespace blockdem::test::distributed_step_test {
namespace {

/// Every block's state and loads after each step, as raw bytes.
using Record = std::vector<std::vector<char>>;

void append(std::vector<char>& out, const double* p, std::size_t n) {
  const char* c = reinterpret_cast<const char*>(p);
  out.insert(out.end(), c, c + n * sizeof(double));
}

/// Runs `steps` steps and records the state after every `every`-th one. every > 1: the world is
/// made whole only then (a deferred replica), as the scenario runner does between its checks.
Record run(World w, int steps, std::vector<int>* owners_early, std::vector<int>* owners_late,
           int every = 1, DistributionStats* stats = nullptr) {
  Record rec;
  if (every > 1) w.set_deferred_replica(true);
  std::vector<char> between;
  for (int k = 0; k < steps; ++k) {
    w.step();
    if ((k + 1) % every != 0) {
      // Between refreshes only this process's part is exact: the equilibrium measures come from
      // reductions of the parts (collective), and must still be one world's bits.
      const EquilibriumMeasures m = w.equilibrium();
      append(between, &m.unbalanced_force_ratio, 1);
      append(between, &m.kinetic_energy_ratio, 1);
      append(between, &m.mean_contact_force, 1);
      continue;
    }
    const EquilibriumMeasures reduced = w.equilibrium();
    w.synchronize();
    std::vector<char> r = std::move(between);
    between.clear();
    append(r, &reduced.kinetic_energy, 1);
    const double t = w.time();
    append(r, &t, 1);
    const EnergyBudget& e = w.energy_budget();
    for (double v : {e.kinetic, e.elastic, e.gravity_work, e.load_work, e.boundary_work,
                     e.friction_dissipation, e.damping_dissipation, e.initial})
      append(r, &v, 1);
    const EquilibriumMeasures m = w.equilibrium();
    append(r, &m.unbalanced_force_ratio, 1);
    append(r, &m.kinetic_energy_ratio, 1);
    const double counts[2] = {static_cast<double>(w.contact_count()),
                              static_cast<double>(w.candidate_pair_count())};
    append(r, counts, 2);
    const double dt = w.next_time_step();
    append(r, &dt, 1);
    for (const Block& b : w.blocks()) {
      append(r, b.position.data(), 3);
      append(r, b.velocity.data(), 3);
      append(r, b.angular_velocity.data(), 3);
      append(r, b.orientation.coeffs().data(), 4);
      append(r, b.force.data(), 3);
      append(r, b.torque.data(), 3);
    }
    for (const Contact* c : w.contacts()) {
      append(r, c->geometry.point.data(), 3);
      append(r, &c->normal_force, 1);
      append(r, c->shear.force.data(), 3);
    }
    rec.push_back(std::move(r));
    if (k + 1 >= 10 && owners_early && owners_early->empty()) *owners_early = w.block_owners();
  }
  if (owners_late) *owners_late = w.block_owners();
  if (stats) *stats = w.distribution_stats();
  return rec;
}

/// What run() gives on each of `parts` worlds stepped together in threads (deferred replica:
/// `every`; a partition at least every `repartition` steps when > 0).
struct PartRuns {
  std::vector<Record> records;
  std::vector<DistributionStats> stats;
  std::vector<std::vector<int>> owners;  ///< the block owners at the end
};

PartRuns run_parts(const BrickPile& pile, const WorldSettings& s, double friction_deg, int parts,
                   int steps, int every, std::int64_t repartition) {
  auto meeting = std::make_shared<Meeting>(parts);
  const auto n = static_cast<std::size_t>(parts);
  PartRuns out{std::vector<Record>(n), std::vector<DistributionStats>(n),
               std::vector<std::vector<int>>(n)};
  std::vector<std::thread> threads;
  for (int r = 0; r < parts; ++r) {
    WorldSettings sr = s;
    sr.distribution = std::make_shared<ThreadDistribution>(meeting, r, repartition);
    threads.emplace_back([&, r, sr] {
      const auto k = static_cast<std::size_t>(r);
      out.records[k] =
          run(pile.world(sr, friction_deg), steps, nullptr, &out.owners[k], every, &out.stats[k]);
    });
  }
  for (auto& t : threads) t.join();
  return out;
}

TEST(DistributedStep, BitIdenticalToOneWorldForTwoAndThreeParts) {
  WorldSettings s = BrickPile::sliding_settings();
  const BrickPile pile = distributed_test_pile();
  const int steps = 150;
  const Record oracle = run(pile.world(s, 20.0), steps, nullptr, nullptr);
  for (int parts : {2, 3}) {
    auto meeting = std::make_shared<Meeting>(parts);
    std::vector<Record> records(static_cast<std::size_t>(parts));
    std::vector<std::vector<int>> early(static_cast<std::size_t>(parts)),
        late(static_cast<std::size_t>(parts));
    std::vector<std::thread> threads;
    for (int r = 0; r < parts; ++r) {
      WorldSettings sr = s;
      sr.distribution = std::make_shared<ThreadDistribution>(meeting, r, 25);
      threads.emplace_back([&, r, sr] {
        const auto k = static_cast<std::size_t>(r);
        records[k] = run(pile.world(sr, 20.0), steps, &early[k], &late[k]);
      });
    }
    for (auto& t : threads) t.join();
    for (int r = 0; r < parts; ++r) {
      const auto k = static_cast<std::size_t>(r);
      ASSERT_EQ(records[k].size(), oracle.size());
      for (int step = 0; step < steps; ++step) {
        ASSERT_TRUE(records[k][static_cast<std::size_t>(step)] ==
                    oracle[static_cast<std::size_t>(step)])
            << parts << " parts, part " << r << ": first difference at step " << step + 1;
      }
      // Every part agrees on the owners, every part owns blocks, and owners changed.
      EXPECT_EQ(late[k], late[0]);
      for (int q = 0; q < parts; ++q)
        EXPECT_NE(std::count(late[k].begin(), late[k].end(), q), 0) << parts << " parts";
    }
    EXPECT_NE(early[0], late[0]) << "no block changed owner with " << parts << " parts";
  }
}

// The replica made whole only every 10 steps (as the runner does at its checks): the steps in
// between exchange only pair slots across subdomain boundaries, ghost blocks and the parts of
// the global sums, and the world at every refresh is still bit for bit the one-world state
// (blocks, loads, contacts, energy budget, equilibrium ratios, next time step), and so are the
// equilibrium measures that reductions of the parts give at every step in between. The per-step
// exchange must be smaller than the whole-world gather it replaces.
TEST(DistributedStep, DeferredReplicaBitIdenticalAtEveryRefresh) {
  WorldSettings s = BrickPile::sliding_settings();
  s.damping = 0.1;
  const BrickPile pile = distributed_test_pile();
  const int steps = 150, every = 10;
  const Record oracle = run(pile.world(s, 20.0), steps, nullptr, nullptr, every);
  for (int parts : {2, 3}) {
    const PartRuns runs = run_parts(pile, s, 20.0, parts, steps, every, 25);
    const std::vector<Record>& records = runs.records;
    const std::vector<DistributionStats>& stats = runs.stats;
    for (int r = 0; r < parts; ++r) {
      const auto k = static_cast<std::size_t>(r);
      ASSERT_EQ(records[k].size(), oracle.size());
      for (std::size_t q = 0; q < oracle.size(); ++q)
        ASSERT_TRUE(records[k][q] == oracle[q])
            << parts << " parts, part " << r << ": first difference at step " << (q + 1) * every;
      const DistributionStats& d = stats[k];
      EXPECT_EQ(d.steps, steps);
      // Refreshes: at most one per record (the partitions every 25 steps migrate blocks point
      // to point, and there is no 200-step checkpoint within 150 steps); the bound also allows
      // a refresh per partition.
      EXPECT_LE(d.replica_refreshes, steps / every + steps / 25);
      // A whole-world refresh moves every block and slot; a step moves only a boundary's worth.
      const double per_step = static_cast<double>(d.bytes_received) / static_cast<double>(d.steps);
      const double per_refresh =
          static_cast<double>(d.replica_bytes_received) / static_cast<double>(d.replica_refreshes);
      EXPECT_LT(per_step, 0.5 * per_refresh) << parts << " parts, part " << r;
    }
  }
}

// The pile settling on its fixed base plate (gravity straight down), the world made whole every
// 20 steps: every contact with the plate is evaluated by the owner of its moving block, and no
// slot or ghost goes to the plate's owner for the plate (its loads are summed again when the world
// is made whole, and are one world's bits, plate included, at every refresh). So the plate's owner
// receives per step about what the others do, not that plus every slot of the bottom layer
// (100 of the pile's 362 cubes): 1.6 and 1.3 times the others' largest with 2 and 3 parts when
// the plate's slots went to its owner.
TEST(DistributedStep, BasePlateOwnerReceivesNoMoreThanTheOthers) {
  WorldSettings s;
  s.gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
  s.contact_mode = ContactMode::boon2012;
  s.threads = 1;
  const BrickPile pile = distributed_test_pile();
  const int steps = 60, every = 20;
  const World probe = pile.world(s, 30.0);
  const auto plate = std::find_if(probe.blocks().begin(), probe.blocks().end(),
                                  [](const Block& b) { return b.motion == Motion::fixed; });
  ASSERT_NE(plate, probe.blocks().end());
  const Record oracle = run(pile.world(s, 30.0), steps, nullptr, nullptr, every);
  for (int parts : {2, 3}) {
    const PartRuns runs = run_parts(pile, s, 30.0, parts, steps, every, 0);
    const std::vector<Record>& records = runs.records;
    const std::vector<DistributionStats>& stats = runs.stats;
    const std::vector<std::vector<int>>& owners = runs.owners;
    double others = 0.0, plate_owner = 0.0;
    const int holder = owners[0][static_cast<std::size_t>(plate->index)];
    for (int r = 0; r < parts; ++r) {
      const auto k = static_cast<std::size_t>(r);
      ASSERT_TRUE(records[k] == oracle) << parts << " parts, part " << r;
      const double per_step =
          static_cast<double>(stats[k].bytes_received) / static_cast<double>(stats[k].steps);
      if (r == holder)
        plate_owner = per_step;
      else
        others = std::max(others, per_step);
    }
    std::printf("%d parts: the plate's owner received %.0f B per step, the others at most %.0f B\n",
                parts, plate_owner, others);
    EXPECT_GT(others, 0.0);
    EXPECT_LT(plate_owner, 1.25 * others) << parts << " parts";
  }
}

// The world made whole only every 75 steps and never partitioned again, the pile sliding on its
// tilted base: over each stretch the processes keep their lists of own blocks and of the ghosts
// the last exchange brought, while blocks slide into pairs with another process's blocks. Every
// refresh is still one world's bits, and between the refreshes contacts across the boundaries
// formed that were not there before (pairs whose blocks reached each other's process as ghosts;
// a rebalance, which the measured pair times could still call for, would make the world whole).
TEST(DistributedStep, GhostListsFollowTheBlocksBetweenRareRefreshes) {
  WorldSettings s = BrickPile::sliding_settings();
  s.damping = 0.1;
  const BrickPile pile = distributed_test_pile();
  const int steps = 150, every = 75;
  const Record oracle = run(pile.world(s, 20.0), steps, nullptr, nullptr, every);
  // The contacts (a, b) of one world at the two refreshes.
  std::vector<std::vector<std::pair<int, int>>> touching;
  {
    World w = pile.world(s, 20.0);
    for (int k = 1; k <= steps; ++k) {
      w.step();
      if (k % every != 0) continue;
      touching.emplace_back();
      for (const Contact* c : w.contacts()) touching.back().emplace_back(c->a, c->b);
    }
  }
  ASSERT_EQ(touching.size(), 2u);
  for (int parts : {2, 3}) {
    const PartRuns runs = run_parts(pile, s, 20.0, parts, steps, every, 0);
    for (int r = 0; r < parts; ++r) {
      const auto k = static_cast<std::size_t>(r);
      ASSERT_TRUE(runs.records[k] == oracle) << parts << " parts, part " << r;
    }
    // Contacts across the boundaries at the last refresh that were not contacts at the first.
    const std::vector<int>& owner = runs.owners[0];
    const auto across = [&](const std::pair<int, int>& p) {
      return owner[static_cast<std::size_t>(p.first)] != owner[static_cast<std::size_t>(p.second)];
    };
    std::size_t formed = 0;
    for (const auto& p : touching[1]) {
      if (across(p) && !std::binary_search(touching[0].begin(), touching[0].end(), p)) ++formed;
    }
    std::printf("%d parts: %zu contacts across the boundaries formed between the refreshes\n",
                parts, formed);
    EXPECT_GT(formed, 0u) << parts << " parts";
  }
}

/// A world's saved state (World::save_state: every block with its loads, every pair slot with
/// its contact state and warm start, the counters, the divergence checkpoint, the energy
/// ledger's budget and per-block records) as bytes.
std::string saved_state(const World& w) {
  std::string out;
  StateWriter writer([&](std::string_view bytes) { out.append(bytes); });
  w.save_state(writer);
  writer.flush();
  return out;
}

/// One distributed world's run for the migration test: the saved state merged to process 0 at
/// `every` steps without making the world whole (save_state_to_root; empty on the other
/// processes), the state after a final synchronize(), the owners after each step, its figures.
struct MigrationRun {
  std::vector<std::string> merged;
  std::string whole;
  std::vector<std::vector<int>> owners;
  DistributionStats stats;
};

std::vector<MigrationRun> run_migration(const BrickPile& pile, const WorldSettings& s, int parts,
                                        int steps, int every, std::int64_t repartition,
                                        bool deferred) {
  auto meeting = std::make_shared<Meeting>(parts);
  std::vector<MigrationRun> out(static_cast<std::size_t>(parts));
  std::vector<std::thread> threads;
  for (int r = 0; r < parts; ++r) {
    WorldSettings sr = s;
    sr.distribution = std::make_shared<ThreadDistribution>(meeting, r, repartition);
    threads.emplace_back([&, r, sr] {
      MigrationRun& o = out[static_cast<std::size_t>(r)];
      World w = pile.world(sr, 20.0);
      w.set_deferred_replica(deferred);
      for (int k = 1; k <= steps; ++k) {
        w.step();
        o.owners.push_back(w.block_owners());
        if (k % every != 0) continue;
        std::string bytes;
        w.save_state_to_root([&](std::string_view piece) { bytes.append(piece); });
        o.merged.push_back(std::move(bytes));
      }
      o.stats = w.distribution_stats();
      w.synchronize();
      o.whole = saved_state(w);
    });
  }
  for (auto& t : threads) t.join();
  return out;
}

// The pile sliding on its tilted base, partitioned again every 15 steps while the caller defers
// the refresh (as `blockdem run` does): blocks cross the subdomain boundaries, and at each
// rebalance those whose owner changes go point to point to their new owners with their state,
// loads, energy records and the pair slots the new owners lack (World::migrate_blocks), without
// the whole world on any process. Oracles: one world alone, whose complete saved state (every
// block, slot, contact state, warm start, energy record and the divergence checkpoint of step
// 200, kept in parts from before the last rebalances) must be the distributed one's, byte for
// byte, when merged to process 0 from the owners at steps 70, 140 and 210 and when made whole
// at the end; and the same processes with the world made whole after every step, whose
// partitions (computed by partition_blocks on the whole world) must be the migrated ones at
// every step. No rebalance may make the world whole: one refresh only, the final one.
TEST(DistributedStep, RebalancesMigrateBlocksPointToPointBitIdentically) {
  WorldSettings s = BrickPile::sliding_settings();
  s.damping = 0.1;
  const BrickPile pile = distributed_test_pile();
  const int steps = 210, every = 70, interval = 15;
  std::vector<std::string> oracle;
  std::string oracle_whole;
  {
    World w = pile.world(s, 20.0);
    for (int k = 1; k <= steps; ++k) {
      w.step();
      if (k % every == 0) oracle.push_back(saved_state(w));
    }
    oracle_whole = saved_state(w);
  }
  for (int parts : {2, 3}) {
    const std::vector<MigrationRun> migrated =
        run_migration(pile, s, parts, steps, every, interval, true);
    const std::vector<MigrationRun> whole =
        run_migration(pile, s, parts, steps, every, interval, false);
    std::int64_t blocks_moved = 0, slots_moved = 0;
    for (int r = 0; r < parts; ++r) {
      const auto k = static_cast<std::size_t>(r);
      const MigrationRun& m = migrated[k];
      ASSERT_EQ(m.merged.size(), oracle.size());
      for (std::size_t q = 0; q < oracle.size(); ++q) {
        if (r == 0)
          EXPECT_TRUE(m.merged[q] == oracle[q])
              << parts << " parts: merged state differs at step " << (q + 1) * every;
        else
          EXPECT_TRUE(m.merged[q].empty());
      }
      EXPECT_TRUE(m.whole == oracle_whole) << parts << " parts, part " << r;
      EXPECT_TRUE(whole[k].whole == oracle_whole) << parts << " parts, part " << r;
      // The same partition at every step as the one computed on the whole world.
      ASSERT_EQ(m.owners.size(), whole[k].owners.size());
      for (std::size_t step = 0; step < m.owners.size(); ++step)
        ASSERT_TRUE(m.owners[step] == whole[k].owners[step])
            << parts << " parts, part " << r << ": partitions differ after step " << step + 1;
      const DistributionStats& d = m.stats;
      EXPECT_EQ(d.partitions, 1 + steps / interval) << parts << " parts";
      EXPECT_EQ(d.migrations, steps / interval) << parts << " parts";
      EXPECT_EQ(d.replica_refreshes, 0) << parts << " parts";
      EXPECT_EQ(d.checkpoint_gathers, 1) << parts << " parts";
      EXPECT_GT(d.migration_bytes_received, 0) << parts << " parts";
      blocks_moved += d.migrated_blocks;
      slots_moved += d.migrated_slots;
    }
    // Blocks changed owner: the partitions at the first and last rebalance differ.
    const std::vector<std::vector<int>>& owners = migrated[0].owners;
    EXPECT_NE(owners[interval - 1], owners.back()) << parts << " parts";
    std::printf("%d parts: %lld blocks and %lld slots migrated in %d rebalances\n", parts,
                static_cast<long long>(blocks_moved), static_cast<long long>(slots_moved),
                steps / interval);
    EXPECT_GT(blocks_moved, 0) << parts << " parts";
    EXPECT_GT(slots_moved, 0) << parts << " parts";
  }
}

}  // namespace
}  // namespace blockdem::test::distributed_step_test
