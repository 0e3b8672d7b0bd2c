// The world's complete saved state: a world built afresh and loaded with it continues exactly
// (bit for bit) as the world it was saved from; states that do not fit are refused.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "validation/scenes.hpp"

namespace blockdem::test {
namespace {

// Three cubes on a fixed base pushed sideways: contacts with normal force and shear history.
World pushed_cubes() {
  WorldSettings s;
  s.gravity = Eigen::Vector3d(0, 0, -9.81);
  s.damping = 0.3;
  World w = linear_world(10e9, 1e9, 30.0, s);
  w.add_block(box_block({0.5, 0.2, 0.05}, {0, 0, -0.025}, 1207.0, Motion::fixed, "base"));
  for (int i = 0; i < 3; ++i) {
    Block cube = box_block(Eigen::Vector3d::Constant(0.046), {0.06 * i, 0, 0.023 - 1e-7}, 1207.0,
                           Motion::free, "cube" + std::to_string(i));
    cube.set_external_force(Eigen::Vector3d(0.2 * (i + 1), 0.0, 0.0));
    w.add_block(cube);
  }
  return w;
}

std::vector<std::uint8_t> saved(const World& w) {
  StateWriter out;
  w.save_state(out);
  return out.bytes();
}

void load(World& w, const std::vector<std::uint8_t>& bytes) {
  StateReader in(bytes.data(), bytes.size());
  w.load_state(in);
  EXPECT_TRUE(in.done());
}

// Oracle: the world that was never saved. Tolerance: none (the complete state, byte for byte).
TEST(WorldState, AFreshWorldLoadedWithTheStateContinuesBitIdentically) {
  World w = pushed_cubes();
  for (int k = 0; k < 250; ++k) w.step();  // past the divergence checkpoint at step 200
  ASSERT_EQ(w.contact_count(), 3u);
  ASSERT_GT(w.contacts()[0]->shear.force.norm(), 0.0);
  const auto state = saved(w);
  World restarted = pushed_cubes();
  load(restarted, state);
  EXPECT_EQ(saved(restarted), state);
  for (int k = 0; k < 300; ++k) {
    w.step();
    restarted.step();
  }
  EXPECT_EQ(saved(restarted), saved(w));
}

// A state handed on in pieces (a sink, as a restart checkpoint streams it into its file) is the
// in-memory writer's bytes, whatever the piece size: pieces smaller than one value (1 byte), a
// block's record (97) and larger than the whole state. Oracle: the in-memory writer, byte for
// byte; World::save_state_to_root (one process) gives the same bytes.
TEST(WorldState, AStateHandedOnInPiecesIsTheWholeWritersBytes) {
  World w = pushed_cubes();
  for (int k = 0; k < 250; ++k) w.step();
  const auto whole = saved(w);
  for (const std::size_t chunk : {std::size_t{1}, std::size_t{97}, std::size_t{1} << 20}) {
    std::vector<std::uint8_t> pieces;
    std::size_t calls = 0;
    StateWriter out(
        [&](std::string_view bytes) {
          ++calls;
          EXPECT_FALSE(bytes.empty());
          pieces.insert(pieces.end(), bytes.begin(), bytes.end());
        },
        chunk);
    w.save_state(out);
    out.flush();
    EXPECT_TRUE(out.bytes().empty());
    EXPECT_EQ(pieces, whole) << "chunk " << chunk;
    if (chunk < whole.size()) {
      EXPECT_GT(calls, whole.size() / (chunk + 64));
    }
  }
  std::vector<std::uint8_t> root;
  w.save_state_to_root(
      [&](std::string_view bytes) { root.insert(root.end(), bytes.begin(), bytes.end()); });
  EXPECT_EQ(root, whole);
}

// A block that stops (prescribed, at rest) and later moves freely again reads the impulses of
// its last free step (the energy ledger keeps them aside while it is not free). Saved while it
// is stopped, they must travel with the state: a restarted world whose ledger lost them would
// count another gravity and damping work. Oracle: the world that was never saved, byte for byte
// (its energy budget among the bytes).
TEST(WorldState, ABlockThatStopsAndMovesAgainContinuesBitIdentically) {
  World w = pushed_cubes();
  for (int k = 0; k < 40; ++k) w.step();
  Block& cube = w.blocks()[2];
  cube.motion = Motion::prescribed;
  cube.velocity.setZero();
  cube.angular_velocity.setZero();
  for (int k = 0; k < 20; ++k) w.step();
  const auto state = saved(w);
  World restarted = pushed_cubes();
  load(restarted, state);
  EXPECT_EQ(saved(restarted), state);
  for (World* x : {&w, &restarted}) x->blocks()[2].motion = Motion::free;
  for (int k = 0; k < 60; ++k) {
    w.step();
    restarted.step();
  }
  EXPECT_EQ(saved(restarted), saved(w));
  EXPECT_EQ(restarted.energy_budget().gravity_work, w.energy_budget().gravity_work);
  EXPECT_EQ(restarted.energy_budget().damping_dissipation, w.energy_budget().damping_dissipation);
}

// Three cubes turned 30 degrees about z on a fixed base, 62 mm apart: their boxes overlap, the
// cubes do not (7.7 mm apart across their faces), so the pairs between them are candidates
// without a contact. The outer cubes are pushed inwards, and contacts between the cubes form
// while the contacts with the base go on.
World near_cubes(int threads) {
  WorldSettings s;
  s.gravity = Eigen::Vector3d(0, 0, -9.81);
  s.damping = 0.3;
  s.threads = threads;
  World w = linear_world(10e9, 1e9, 30.0, s);
  w.add_block(box_block({0.5, 0.2, 0.05}, {0, 0, -0.025}, 1207.0, Motion::fixed, "base"));
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(30.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (int i = 0; i < 3; ++i) {
    Block cube = make_block(Polyhedron::box(Eigen::Vector3d::Constant(0.046))
                                .transformed(turn, {0.062 * i, 0, 0.023 - 1e-7}),
                            1207.0, "cube" + std::to_string(i));
    cube.set_external_force(Eigen::Vector3d(1.5 * (1 - i), 0.0, 0.0));
    w.add_block(cube);
  }
  return w;
}

// The pair store keeps a contact's state only for pairs that touch; the others keep their pair,
// bond and narrow-phase warm start. Oracle: the world that was never saved, with another thread
// count. Tolerance: none (the complete state, byte for byte).
TEST(WorldState, NearPairsAndContactsFormingLaterContinueBitIdentically) {
  World w = near_cubes(1);
  for (int k = 0; k < 20; ++k) w.step();
  ASSERT_EQ(w.contact_count(), 3u);         // the cubes on the base only
  ASSERT_EQ(w.candidate_pair_count(), 5u);  // and the two near pairs between the cubes
  const auto state = saved(w);
  World restarted = near_cubes(3);
  load(restarted, state);
  EXPECT_EQ(saved(restarted), state);
  // Until the cubes meet, and 200 steps more.
  int after = -1;
  for (int k = 0; k < 8000 && after < 200; ++k) {
    w.step();
    restarted.step();
    if (after >= 0 || w.contact_count() == 5u) ++after;
  }
  EXPECT_EQ(after, 200);  // the cubes met
  EXPECT_EQ(saved(restarted), saved(w));
  const auto contacts = w.contacts();
  ASSERT_EQ(contacts.size(), w.contact_count());
  for (std::size_t k = 1; k < contacts.size(); ++k)
    EXPECT_TRUE(contacts[k - 1]->a < contacts[k]->a ||
                (contacts[k - 1]->a == contacts[k]->a && contacts[k - 1]->b < contacts[k]->b));
}

// The divergence checkpoint keeps a candidate pair without a contact state (a near pair, bonded
// since the start) as its bond alone. Oracles: the slots it restores (the two near pairs come
// back with the three contacts, in (a, b) order), the saved state's bytes after a load, and the
// world it was saved from after both return to the checkpoint. Tolerance: none.
TEST(WorldState, ADivergenceCheckpointOfNearBondedPairsComesBackWhole) {
  World w = near_cubes(1);
  for (int k = 0; k < 20; ++k) w.step();
  ASSERT_EQ(w.contact_count(), 3u);
  ASSERT_EQ(w.candidate_pair_count(), 5u);
  w.save_checkpoint();  // now, with the near pairs
  const auto state = saved(w);
  World restarted = near_cubes(1);
  load(restarted, state);
  EXPECT_EQ(saved(restarted), state);
  for (World* x : {&w, &restarted}) {
    for (int k = 0; k < 30; ++k) x->step();
    x->restore_checkpoint();
    EXPECT_EQ(x->candidate_pair_count(), 5u);
    EXPECT_EQ(x->step_count(), 20);
  }
  EXPECT_EQ(saved(restarted), saved(w));
  for (int k = 0; k < 200; ++k) {
    w.step();
    restarted.step();
  }
  EXPECT_EQ(saved(restarted), saved(w));
}

// A checkpoint larger than settings().checkpoint_memory_limit is kept in a scratch file (here
// every one: the limit 0). Oracle: the same world with its checkpoints in memory: the saved state
// (which holds the checkpoint) after the checkpoint is taken, after both return to it, and after
// the checkpoint of step 200; a copy of the world shares the file and keeps it when its own next
// checkpoint goes to a file of its own. Tolerance: none (byte for byte).
TEST(WorldState, ACheckpointKeptInAFileIsTheCheckpointKeptInMemory) {
  World memory = near_cubes(1);
  World filed = near_cubes(1);
  filed.settings().checkpoint_memory_limit = 0;
  for (int k = 0; k < 20; ++k) {
    memory.step();
    filed.step();
  }
  memory.save_checkpoint();
  filed.save_checkpoint();
  EXPECT_EQ(memory.checkpoint_file_bytes(), 0u);
  ASSERT_GT(filed.checkpoint_file_bytes(), 0u);
  EXPECT_EQ(saved(filed), saved(memory));
  World copy = filed;
  for (int k = 0; k < 30; ++k) {
    for (World* x : {&memory, &filed, &copy}) x->step();
  }
  copy.save_checkpoint();  // step 50, in a new file
  for (World* x : {&memory, &filed}) {
    x->restore_checkpoint();
    EXPECT_EQ(x->step_count(), 20);
  }
  EXPECT_EQ(saved(filed), saved(memory));
  EXPECT_GT(filed.checkpoint_file_bytes(), 0u);  // left in its file after the restore
  copy.restore_checkpoint();
  EXPECT_EQ(copy.step_count(), 50);
  for (int k = 0; k < 200; ++k) {
    memory.step();
    filed.step();
  }
  ASSERT_GT(filed.checkpoint_file_bytes(), 0u);
  EXPECT_EQ(saved(filed), saved(memory));  // the checkpoint of step 200 in both
  // A restart's checkpoint goes to a file too, and so does its next one. With the default limit
  // it stays in memory.
  World restarted = near_cubes(1);
  restarted.settings().checkpoint_memory_limit = 0;
  load(restarted, saved(filed));
  EXPECT_EQ(restarted.checkpoint_file_bytes(), filed.checkpoint_file_bytes());
  EXPECT_EQ(saved(restarted), saved(filed));
  World in_memory = near_cubes(1);
  load(in_memory, saved(filed));
  EXPECT_EQ(in_memory.checkpoint_file_bytes(), 0u);
  EXPECT_EQ(saved(in_memory), saved(filed));
  restarted.save_checkpoint();
  memory.save_checkpoint();
  EXPECT_GT(restarted.checkpoint_file_bytes(), 0u);
  EXPECT_EQ(saved(restarted), saved(memory));
}

// A checkpoint file that cannot be made stops with the folder and the reason, and the last
// checkpoint is kept: the world returns to it. Oracle: the step it was taken at.
TEST(WorldState, ACheckpointFileThatCannotBeMadeIsAnErrorAndTheLastOneStays) {
  World w = near_cubes(1);
  w.settings().checkpoint_memory_limit = 0;
  for (int k = 0; k < 20; ++k) w.step();
  w.save_checkpoint();
  const char* old = std::getenv("TMPDIR");
  const std::string kept = old ? old : "";
  ::setenv("TMPDIR", "/nonexistent-blockdem-folder", 1);
  for (int k = 0; k < 10; ++k) w.step();
  try {
    w.save_checkpoint();
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-blockdem-folder"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("No such file or directory"), std::string::npos)
        << e.what();
  }
  if (old) {
    ::setenv("TMPDIR", kept.c_str(), 1);
  } else {
    ::unsetenv("TMPDIR");
  }
  w.restore_checkpoint();
  EXPECT_EQ(w.step_count(), 20);
}

TEST(WorldState, RemovedBlocksAreRemovedAgainByName) {
  World w = pushed_cubes();
  for (int k = 0; k < 50; ++k) w.step();
  w.remove_blocks({2});
  for (int k = 0; k < 50; ++k) w.step();
  World restarted = pushed_cubes();
  load(restarted, saved(w));
  ASSERT_EQ(restarted.blocks().size(), 3u);
  EXPECT_EQ(restarted.blocks()[2].name, "cube2");
  for (int k = 0; k < 50; ++k) {
    w.step();
    restarted.step();
  }
  EXPECT_EQ(saved(restarted), saved(w));
}

TEST(WorldState, StatesThatDoNotFitAreRefused) {
  World w = pushed_cubes();
  for (int k = 0; k < 20; ++k) w.step();
  auto state = saved(w);
  // Truncated.
  World a = pushed_cubes();
  const std::vector<std::uint8_t> cut(state.begin(), state.begin() + state.size() / 2);
  StateReader in(cut.data(), cut.size());
  EXPECT_THROW(a.load_state(in), StateError);
  // Another scene: a world whose blocks have other names.
  World other = linear_world(10e9, 1e9, 30.0);
  other.add_block(box_block({0.5, 0.2, 0.05}, {0, 0, -0.025}, 1207.0, Motion::fixed, "floor"));
  for (int i = 0; i < 3; ++i)
    other.add_block(box_block(Eigen::Vector3d::Constant(0.046), {0.06 * i, 0, 0.023}, 1207.0,
                              Motion::free, "other" + std::to_string(i)));
  StateReader whole(state.data(), state.size());
  EXPECT_THROW(other.load_state(whole), StateError);
}

}  // namespace
}  // namespace blockdem::test
