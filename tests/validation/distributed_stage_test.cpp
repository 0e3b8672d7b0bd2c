// A loading stage over a world spread over K parts (threads standing in for processes, without
// MPI): the convergence checks, the servo check and the motion monitor read the world through
// exact reductions of each part's blocks and contacts, not through whole-world refreshes, and
// give one world's answers bit for bit: every check's measures and monitor report, the stage's
// result, the energy budget and the final state.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <thread>
#include <vector>

#include "blockdem/io/run_recorder.hpp"
#include "blockdem/io/time_history.hpp"
#include "blockdem/world/stage.hpp"
#include "blockdem/world/state_stream.hpp"
#include "brick_pile.hpp"
#include "support/temp_path.hpp"
#include "support/thread_distribution.hpp"

namespace blockdem::test {
namespace {

void put(std::vector<std::uint64_t>& out, double v) {
  out.push_back(std::bit_cast<std::uint64_t>(v));
}

void put_report(std::vector<std::uint64_t>& out, const MotionReport& r) {
  for (double v : {r.max_displacement, r.displacement_limit, r.max_speed, r.kinetic_energy,
                   r.load_work, r.elastic_energy_start, r.time_step_ratio})
    put(out, v);
  out.push_back(static_cast<std::uint64_t>(r.growing_checks));
  out.push_back(r.moving_blocks.size());
  for (int b : r.moving_blocks) out.push_back(static_cast<std::uint64_t>(b));
  out.push_back(r.mechanism ? 1 : 0);
}

struct Outcome {
  std::vector<std::uint64_t> bits;  ///< every check, the stage result, budget and final state
  std::int64_t checks = 0;
  DistributionStats stats;
};

/// Runs one equilibrium stage (it does not converge: the tilted gravity makes the pile slide)
/// with the runner's deferral: the world is made whole only where a caller reads it.
Outcome run(World w, const Stage& stage) {
  Outcome out;
  std::optional<MotionMonitor> monitor;
  // After every check: the monitor's report and the equilibrium measures, read without a
  // refresh (equilibrium() is collective on a world that is not whole).
  const AfterStepFn after = [&](const StageResume& at) {
    if (at.steps_done % stage.check_interval != 0) return false;
    ++out.checks;
    put_report(out.bits, monitor->report());
    const EquilibriumMeasures m = w.equilibrium();
    for (double v :
         {m.unbalanced_force_ratio, m.kinetic_energy, m.kinetic_energy_ratio, m.mean_contact_force})
      put(out.bits, v);
    out.bits.push_back(servos_settled(w) ? 1 : 0);
    return false;
  };
  StageSync sync;
  sync.after_step_synchronizes = true;
  const StageResult r = run_stage(w, stage, {}, &monitor, after, nullptr, {}, &sync);
  out.bits.push_back(static_cast<std::uint64_t>(r.steps));
  out.bits.push_back(r.converged ? 1 : 0);
  for (double v : {r.measures.unbalanced_force_ratio, r.measures.kinetic_energy_ratio, r.time})
    put(out.bits, v);
  put_report(out.bits, r.motion);
  const EnergyBudget& e = w.energy_budget();
  for (double v : {e.kinetic, e.elastic, e.gravity_work, e.load_work, e.boundary_work,
                   e.friction_dissipation, e.damping_dissipation, e.initial})
    put(out.bits, v);
  for (const Block& b : w.blocks()) {
    for (int k = 0; k < 3; ++k) put(out.bits, b.position[k]);
    for (int k = 0; k < 3; ++k) put(out.bits, b.velocity[k]);
  }
  out.stats = w.distribution_stats();
  return out;
}

// Reference: the same stage on one world (the oracle), bit for bit, for 2 and 3 parts. The
// parts must not have made the world whole at the checks: one refresh at most, at the stage's
// end, against one per check (24) when the checks read the whole world.
TEST(DistributedStage, ChecksFromReductionsBitIdenticalWithoutRefreshes) {
  WorldSettings s = BrickPile::sliding_settings();
  s.damping = 0.1;
  const BrickPile pile = distributed_test_pile();
  Stage stage;
  stage.name = "slide";
  stage.check_interval = 5;
  stage.min_steps = 10;
  stage.max_steps = 120;
  stage.mechanism.displacement_limit = 1e-4;  // small: blocks count as moving within the run
  const Outcome oracle = run(pile.world(s, 20.0), stage);
  ASSERT_EQ(oracle.checks, stage.max_steps / stage.check_interval - 1);  // the last one stops
  for (int parts : {2, 3}) {
    auto meeting = std::make_shared<Meeting>(parts);
    std::vector<Outcome> outcomes(static_cast<std::size_t>(parts));
    std::vector<std::thread> threads;
    for (int r = 0; r < parts; ++r) {
      WorldSettings sr = s;
      sr.distribution = std::make_shared<ThreadDistribution>(meeting, r);
      threads.emplace_back(
          [&, r, sr] { outcomes[static_cast<std::size_t>(r)] = run(pile.world(sr, 20.0), stage); });
    }
    for (auto& t : threads) t.join();
    for (int r = 0; r < parts; ++r) {
      const Outcome& o = outcomes[static_cast<std::size_t>(r)];
      EXPECT_EQ(o.checks, oracle.checks);
      ASSERT_EQ(o.bits.size(), oracle.bits.size()) << parts << " parts, part " << r;
      for (std::size_t q = 0; q < o.bits.size(); ++q)
        ASSERT_EQ(o.bits[q], oracle.bits[q]) << parts << " parts, part " << r << ", word " << q;
      EXPECT_EQ(o.stats.steps, stage.max_steps);
      EXPECT_LE(o.stats.replica_refreshes, 1) << parts << " parts, part " << r;
    }
  }
}

/// The files a steps stage writes as the scenario runner writes them: a time_history.csv row
/// every 10 steps (with some blocks' columns, the resting base plate's among them), and at the
/// stage's end history.csv, blocks.csv, contacts.csv and the last row, without a whole world.
struct Files {
  std::vector<std::string> text;  ///< the files (process 0's for a distributed world)
  std::int64_t refreshes = 0;
  std::int64_t merges = 0;
};

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

Files write_outputs(World w, const Stage& stage, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  {
    TimeHistoryWriter history(
        dir / "time_history.csv", w,
        TimeHistoryOptions{10, 0.0, 20000, {"c0", "c150", "c361", "base"}, {}});
    RunRecorder recorder(dir, false);
    StageSync sync;
    sync.after_step_synchronizes = true;
    sync.on_step_reads = [](const World&) { return false; };
    sync.end_synchronizes = false;
    std::optional<MotionMonitor> monitor;
    const StageResult r = run_stage(
        w, stage, {}, &monitor, {}, nullptr,
        [&](const World& world, const Stage& s, std::int64_t) {
          history.after_step(world, s.name);
        },
        &sync);
    recorder.record(w, r, 0);
    history.write(w, stage.name);
    history.flush();
  }
  Files f;
  for (const char* name : {"time_history.csv", "history.csv", "blocks.csv", "contacts.csv"})
    f.text.push_back(read_text(dir / name));
  f.refreshes = w.distribution_stats().replica_refreshes;
  f.merges = w.distribution_stats().output_merges;
  return f;
}

// The outputs of a stage over 2 and 3 parts, written by part 0 from reductions and merges of
// every part's own blocks and contacts (World::merge_to_root), are one world's files byte for
// byte, and no part made the world whole: not for the rows, nor at the stage's end.
TEST(DistributedStage, OutputsMergedWithoutRefreshesByteIdentical) {
  WorldSettings s = BrickPile::sliding_settings();
  const BrickPile pile;  // its history columns name blocks of the whole pile
  Stage stage;
  stage.name = "slide";
  stage.kind = Stage::Kind::steps;
  stage.steps = 60;
  const auto root = temp_path("merged_outputs");
  std::filesystem::remove_all(root);
  const Files oracle = write_outputs(pile.world(s, 20.0), stage, root / "one");
  for (int parts : {2, 3}) {
    auto meeting = std::make_shared<Meeting>(parts);
    std::vector<Files> files(static_cast<std::size_t>(parts));
    std::vector<std::thread> threads;
    for (int r = 0; r < parts; ++r) {
      WorldSettings sr = s;
      sr.distribution = std::make_shared<ThreadDistribution>(meeting, r);
      const auto dir = root / (std::to_string(parts) + "_" + std::to_string(r));
      threads.emplace_back([&, r, sr, dir] {
        files[static_cast<std::size_t>(r)] = write_outputs(pile.world(sr, 20.0), stage, dir);
      });
    }
    for (auto& t : threads) t.join();
    for (std::size_t k = 0; k < oracle.text.size(); ++k) {
      EXPECT_GT(oracle.text[k].size(), 200u) << "file " << k;
      EXPECT_EQ(files[0].text[k], oracle.text[k]) << parts << " parts, file " << k;
    }
    for (const Files& f : files) {
      EXPECT_EQ(f.refreshes, 0) << parts << " parts";
      // 7 rows (levels 0, 10, ..., 50 and the stage's last, 2 merges each), the stage's end (3:
      // the resting plate's contact force, blocks, contacts).
      EXPECT_EQ(f.merges, 7 * 2 + 3) << parts << " parts";
    }
  }
}

/// A world's complete state (World::save_state: blocks, pair slots, counters and the divergence
/// checkpoint), the bytes of a restart file's world.
std::vector<std::uint8_t> state_bytes(const World& w) {
  StateWriter out;
  w.save_state(out);
  return out.bytes();
}

/// Steps `w` to step `to` with the refresh deferred, as the runner steps it (no reader of the
/// whole world in between), then makes it whole.
void step_to(World& w, std::int64_t to) {
  w.set_deferred_replica(true);
  while (w.step_count() < to) w.step();
  w.synchronize();
  w.set_deferred_replica(false);
}

/// What a world goes through in the divergence checkpoint's test: its state at step 450 (the
/// checkpoint of step 400 inside), then a run made to diverge after step 630 (max_speed lowered
/// below every moving block's speed), its message and its state reset to the checkpoint of step
/// 600.
struct Diverged {
  std::vector<std::uint8_t> at_450, reset;
  std::string message;
  std::int64_t reset_step = -1;
  DistributionStats stats;
};

Diverged diverge(World w) {
  Diverged d;
  step_to(w, 450);
  d.at_450 = state_bytes(w);
  w.set_deferred_replica(true);
  while (w.step_count() < 630) w.step();
  w.settings().max_speed = 1e-9;
  try {
    w.step();
  } catch (const DivergenceError& e) {
    d.message = e.what();
  }
  w.set_deferred_replica(false);
  d.reset_step = w.step_count();
  d.reset = state_bytes(w);
  d.stats = w.distribution_stats();
  return d;
}

// The divergence checkpoint (every 200 steps) kept in parts: each part keeps its own blocks and
// pairs, and the parts are gathered only when the world is made whole (here at step 450) or the
// run diverges. The state with the gathered checkpoint, the divergence's message and the world
// reset to the checkpoint are one world's bit for bit, on 2 and 3 parts, with 2 refreshes (one
// at step 450, one at the divergence) where each checkpoint made one (3 more here).
TEST(DistributedStage, CheckpointInPartsGatheredAndResetBitIdentical) {
  WorldSettings s = BrickPile::sliding_settings();
  s.damping = 0.1;
  const BrickPile pile = distributed_test_pile();
  const Diverged oracle = diverge(pile.world(s, 20.0));
  ASSERT_NE(oracle.message.find("the run diverged at step 631"), std::string::npos)
      << oracle.message;
  ASSERT_EQ(oracle.reset_step, 600);
  ASSERT_NE(oracle.at_450, oracle.reset);
  for (int parts : {2, 3}) {
    auto meeting = std::make_shared<Meeting>(parts);
    std::vector<Diverged> runs(static_cast<std::size_t>(parts));
    std::vector<std::thread> threads;
    for (int r = 0; r < parts; ++r) {
      WorldSettings sr = s;
      sr.distribution = std::make_shared<ThreadDistribution>(meeting, r);
      threads.emplace_back(
          [&, r, sr] { runs[static_cast<std::size_t>(r)] = diverge(pile.world(sr, 20.0)); });
    }
    for (auto& t : threads) t.join();
    for (int r = 0; r < parts; ++r) {
      const Diverged& d = runs[static_cast<std::size_t>(r)];
      EXPECT_TRUE(d.at_450 == oracle.at_450) << parts << " parts, part " << r;
      EXPECT_EQ(d.message, oracle.message) << parts << " parts, part " << r;
      EXPECT_EQ(d.reset_step, oracle.reset_step);
      EXPECT_TRUE(d.reset == oracle.reset) << parts << " parts, part " << r;
      EXPECT_EQ(d.stats.replica_refreshes, 2) << parts << " parts, part " << r;
      EXPECT_EQ(d.stats.checkpoint_gathers, 2) << parts << " parts, part " << r;
      EXPECT_GT(d.stats.checkpoint_bytes_received, 0);
    }
  }
}

// A restart file written from 2 parts (the state at step 450, its divergence checkpoint gathered
// from parts) continues on one world and on 2 parts to the state of the run that never stopped
// (step 650, whose checkpoint of step 600 was again kept in parts on 2).
TEST(DistributedStage, RestartFromTwoPartsContinuesOnOneAndTwoBitIdentically) {
  WorldSettings s = BrickPile::sliding_settings();
  s.damping = 0.1;
  const BrickPile pile = distributed_test_pile();
  World straight = pile.world(s, 20.0);
  step_to(straight, 650);
  const std::vector<std::uint8_t> oracle = state_bytes(straight);

  const auto on_parts = [&](int parts, const std::vector<std::uint8_t>* from, std::int64_t to) {
    auto meeting = std::make_shared<Meeting>(parts);
    std::vector<std::vector<std::uint8_t>> out(static_cast<std::size_t>(parts));
    std::vector<std::thread> threads;
    for (int r = 0; r < parts; ++r) {
      WorldSettings sr = s;
      sr.distribution = std::make_shared<ThreadDistribution>(meeting, r);
      threads.emplace_back([&, r, sr] {
        World w = pile.world(sr, 20.0);
        if (from) {
          StateReader in(from->data(), from->size());
          w.load_state(in);
        }
        step_to(w, to);
        out[static_cast<std::size_t>(r)] = state_bytes(w);
      });
    }
    for (auto& t : threads) t.join();
    for (int r = 1; r < parts; ++r) EXPECT_TRUE(out[static_cast<std::size_t>(r)] == out[0]);
    return out[0];
  };
  const std::vector<std::uint8_t> written = on_parts(2, nullptr, 450);
  World one = pile.world(s, 20.0);
  StateReader in(written.data(), written.size());
  one.load_state(in);
  step_to(one, 650);
  EXPECT_TRUE(state_bytes(one) == oracle) << "restarted on one world";
  EXPECT_TRUE(on_parts(2, &written, 650) == oracle) << "restarted on 2 parts";
}

}  // namespace
}  // namespace blockdem::test
