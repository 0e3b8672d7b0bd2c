// `mpirun -np K blockdem run`: the outputs of K = 1, 2, 3 processes are byte-identical to those
// of one process started without mpirun (the oracle; the VTK frames of 2 and 3 processes, written
// in pieces, equal through VTK's reader), for a settling brick pile, a shaken pile
// whose blocks cross subdomain boundaries and change owner, a jointed rock mass whose bonds break
// until it collapses, and a voussoir beam; and bad input
// (more processes than blocks, a scenario that one process cannot read, a process that fails
// alone, a process that dies) stops every process. Skipped when the build has no MPI
// (BLOCKDEM_MPI=OFF).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "brick_pile.hpp"
#include "stability_support.hpp"
#include "support/mpi_launcher.hpp"
#include "support/temp_path.hpp"

namespace blockdem::test {
namespace {

namespace fs = std::filesystem;

std::string read_file(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

int exit_code(const std::string& cmd) {
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// summary.json without what may differ between process counts: wall time, ranks, the
/// per-process figures of the distributed work and the record of the VTK files (pieces on more
/// than one process).
nlohmann::json comparable_summary(const fs::path& p) {
  nlohmann::json j = nlohmann::json::parse(read_file(p));
  j.erase("wall_time_s");
  j.erase("ranks");
  j.erase("distribution");
  nlohmann::json files = nlohmann::json::array();
  for (const auto& f : j.at("files"))
    if (f.at("path").get<std::string>().rfind("vtk/", 0) != 0) files.push_back(f);
  j["files"] = files;
  return j;
}

/// Runs `args` once without mpirun and with mpirun -np 1, 2, 3 (each must exit with `code`; 3: a
/// stage cut short, whose outputs are still written) and checks that every output file
/// is byte-identical to the single process's (summary.json: as comparable_summary). Returns the
/// summaries of the runs on 2 and 3 processes. The one-process run is the oracle: the
/// distributed step moves contacts byte for byte and sums loads in the serial order.
std::vector<nlohmann::json> expect_same_outputs(const fs::path& dir, const std::string& args,
                                                const std::string& env = "", int code = 0) {
  std::vector<fs::path> outs;
  std::vector<nlohmann::json> summaries;
  std::vector<std::string> cmds;
  for (int ranks : {0, 1, 2, 3}) {
    const std::string launcher = ranks == 0 ? "" : mpirun(ranks, env);
    cmds.push_back(launcher + BLOCKDEM_CLI_PATH + " run " + args + " --out " +
                   (dir / ("out" + std::to_string(ranks))).string() +
                   " --quiet --no-figures --threads 1");
  }
  // The runs without mpirun and on one process take one core each: they run side by side (the
  // MPI tests run alone, on the 2 cores CI has); those on 2 and 3 processes after, one by one.
  std::vector<int> codes(cmds.size(), -1);
  {
    auto alone = std::async(std::launch::async, exit_code, cmds[0]);
    codes[1] = exit_code(cmds[1]);
    codes[0] = alone.get();
  }
  codes[2] = exit_code(cmds[2]);
  codes[3] = exit_code(cmds[3]);
  for (int ranks : {0, 1, 2, 3}) {
    const fs::path out = dir / ("out" + std::to_string(ranks));
    const std::string& cmd = cmds[static_cast<std::size_t>(ranks)];
    EXPECT_EQ(codes[static_cast<std::size_t>(ranks)], code) << cmd;
    const nlohmann::json s = nlohmann::json::parse(read_file(out / "summary.json"));
    EXPECT_EQ(s.at("ranks").get<int>(), ranks == 0 ? 1 : ranks) << cmd;
    if (ranks >= 2) summaries.push_back(s);
    outs.push_back(out);
  }
  std::size_t files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(outs[0])) {
    if (!entry.is_regular_file()) continue;
    const fs::path rel = fs::relative(entry.path(), outs[0]);
    for (std::size_t k = 1; k < outs.size(); ++k) {
      const int ranks = static_cast<int>(k);
      // VTK frames of 2 and 3 processes are pieces by construction: compared through VTK's
      // reader below.
      if (ranks >= 2 && *rel.begin() == "vtk") continue;
      EXPECT_TRUE(fs::exists(outs[k] / rel)) << rel << " missing with " << ranks << " ranks";
      if (rel == "summary.json") {
        EXPECT_EQ(comparable_summary(entry.path()), comparable_summary(outs[k] / rel))
            << ranks << " ranks";
      } else {
        EXPECT_TRUE(read_file(entry.path()) == read_file(outs[k] / rel))
            << rel << " differs with " << ranks << " ranks";
      }
    }
    ++files;
  }
  EXPECT_GE(files, 4u);  // history, blocks, contacts, summary (+ vtk)
  if (fs::exists(outs[0] / "vtk")) {
    // The pieces and .pvtu indices, read with VTK, equal the one-process frames (to 0).
    const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
    // Both comparisons side by side (one core each).
    std::vector<std::string> compare;
    for (int ranks : {2, 3}) {
      compare.push_back(python +
                        " '" BLOCKDEM_SOURCE_DIR "/tests/validation/compare_vtk_frames.py' '" +
                        outs[0].string() + "' '" + outs[static_cast<std::size_t>(ranks)].string() +
                        "' " + std::to_string(ranks) + " > /dev/null");
    }
    auto first = std::async(std::launch::async, exit_code, compare[0]);
    EXPECT_EQ(exit_code(compare[1]), 0) << compare[1];
    EXPECT_EQ(first.get(), 0) << compare[0];
  }
  return summaries;
}

class MpiRun : public ::testing::Test {
 protected:
  void SetUp() override {
    if (kMpiexec == nullptr) GTEST_SKIP() << "built without MPI (BLOCKDEM_MPI=OFF)";
    dir_ = temp_path("mpi_" +
                     std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p;
  }
  /// A 10-step pile run on two processes, process 1 with TMPDIR=`tmpdir`, into dir_/out: the
  /// launcher's exit code, and what the processes printed on stderr in `err`.
  int run_with_process_one_tmpdir(const fs::path& tmpdir, std::string& err) const {
    const fs::path scenario =
        write("pile.toml", BrickPile{}.toml("boon2012", 30.0, Eigen::Vector3d(0, 0, -9.81), 10));
    const fs::path log = dir_ / "log.txt";
    const std::string tail =
        " --out " + (dir_ / "out").string() + " --quiet --no-figures --threads 1";
    const std::string cmd = mpirun(1) + BLOCKDEM_CLI_PATH + " run " + scenario.string() + tail +
                            " : -np 1 env TMPDIR=" + tmpdir.string() + " " + BLOCKDEM_CLI_PATH +
                            " run " + scenario.string() + tail + " 2> " + log.string();
    const int code = exit_code(cmd);
    err = read_file(log);
    return code;
  }
  fs::path dir_;
};

// A 4-layer pile of 362 cubes with small initial velocities settling under gravity on a fixed
// plate, two stages of 1000 steps: positions (blocks.csv), contacts, time_history.csv and the
// energies in summary.json (printed to 17 digits) as from one process, with the whole world
// gathered only for the divergence checkpoints.
TEST_F(MpiRun, SettlingPileSameOutputsOnOneTwoThreeRanks) {
  // time_history.csv with some blocks' columns (on every side of the subdomains, and the
  // resting base plate).
  const fs::path scenario =
      write("pile.toml", BrickPile{}.toml("boon2012", 30.0, Eigen::Vector3d(0, 0, -9.81), 1000) +
                             "[output]\nhistory_blocks = [\"c0\", \"c150\", \"c361\", \"base\"]\n");
  const auto summaries = expect_same_outputs(dir_, scenario.string());
  for (const auto& s : summaries) {
    // Each process evaluated a share of the pairs and saw other processes' blocks as ghosts.
    ASSERT_EQ(s.at("distribution").size(), s.at("ranks").get<std::size_t>());
    const auto ranks = s.at("ranks").get<double>();
    double pairs = 0.0;
    for (const auto& rank : s.at("distribution")) pairs += rank.at("pairs_per_step").get<double>();
    for (const auto& rank : s.at("distribution")) {
      EXPECT_GT(rank.at("pairs_per_step").get<double>(), 0.0);
      EXPECT_GT(rank.at("ghost_blocks_per_step").get<double>(), 0.0);
      // The neighbour exchange against an all-gather of every other process's pair slots (504
      // bytes each), which every process would receive every step: at most half of it here.
      const double all_gather = 504.0 * pairs * (ranks - 1.0) / ranks;
      EXPECT_LT(rank.at("bytes_received_per_step").get<double>(), 0.5 * all_gather);
      // The whole world is gathered only at the stages' checks (every 10 steps), history rows
      // (every 100), divergence checkpoints (every 200) and the stages' starts and ends: two
      // stages of 1000 steps, against 2000 refreshes if it were gathered after every step.
      EXPECT_LE(rank.at("replica_refreshes").get<int>(),
                2 * (1000 / 10 + 1000 / 100 + 1000 / 200 + 2));
      // Exactly: only the second stage's start and a new partition that does not migrate make
      // the world whole (a rebalance, should the processes' pair times call for one, migrates
      // blocks point to point instead).
      // The time_history.csv rows (every 100 steps) come from reductions and merges to process
      // 0 (20 more refreshes, one per row, if read from a whole world); the divergence
      // checkpoints (every 200 steps) are kept in parts (10 more refreshes if taken from a
      // whole world), gathered at the next refresh (the one of step 1000 at that start).
      EXPECT_EQ(rank.at("replica_refreshes").get<int>(),
                1 + (rank.at("partitions").get<int>() - 1 - rank.at("migrations").get<int>()));
      EXPECT_GE(rank.at("checkpoint_gathers").get<int>(), 1);
      EXPECT_LE(rank.at("checkpoint_gathers").get<int>(),
                rank.at("replica_refreshes").get<int>() + 1);
      // The rows merged to process 0 (2 merges each: elastic energy terms, the blocks'
      // columns), and each stage's end (5: its last row's 2, the resting plate's contact
      // force, blocks.csv, contacts.csv).
      EXPECT_EQ(rank.at("output_merges").get<int>(), 2 * 10 * 2 + 2 * 5);
    }
  }
}

// The pile shaken by a steep sideways gravity (60, 25, -98.1) m/s^2 in mode face_integrated:
// blocks slide and topple across subdomain boundaries; the blocks are partitioned again every
// 25 steps (BLOCKDEM_MPI_REBALANCE_STEPS), so blocks and their contacts change owner (two stages
// of 200 steps: on 2 processes 17 partitions and 378 and 376 blocks migrated, as many as two
// stages of 400 steps partitioned every 50 steps migrated).
TEST_F(MpiRun, ShakenPileRepartitionedSameOutputs) {
  const fs::path scenario =
      write("shaken.toml",
            BrickPile{}.toml("face_integrated", 20.0, Eigen::Vector3d(60, 25, -98.1), 200));
  const auto summaries =
      expect_same_outputs(dir_, scenario.string(), "-x BLOCKDEM_MPI_REBALANCE_STEPS=25 ");
  for (const auto& s : summaries) {
    int migrated = 0;
    for (const auto& rank : s.at("distribution")) {
      EXPECT_GE(rank.at("partitions").get<int>(), 16);  // 400 steps / 25
      migrated += rank.at("migrated_blocks").get<int>();
    }
    EXPECT_GT(migrated, 0);
  }
}

// A rock mass cut by three joint sets (82 blocks), its joints bonded (cohesion 20 kPa, tensile
// strength 10 kPa), under a steep sideways gravity: bonds break and blocks slide across
// subdomain boundaries, the blocks are partitioned again every 50 steps, and the second stage's
// stronger push makes the run diverge: the world is reset to its divergence checkpoint (kept in
// parts, its bonded pairs as bonds alone, gathered) and the run stops as a collapse (exit 3)
// with the outputs of the last good state.
TEST_F(MpiRun, JointedRockMassBreakingAndCollapsingSameOutputs) {
  const std::string toml = R"(title = "jointed rock mass under a steep sideways gravity"
[settings]
damping = 0.3
contact_mode = "boon2012"
[output]
vtk = false
[[materials]]
name = "rock"
density = 2600.0
[[joint_laws]]
name = "joint"
normal = { law = "linear", stiffness = 2e7 }
shear = { law = "linear", stiffness = 5e5, friction_deg = 20, cohesion = 2e4, tensile_strength = 1e4, residual_friction_deg = 15 }
[rock_mass]
region = { min = [0, 0, 0], max = [5, 3, 4] }
material = "rock"
law = "joint"
min_block_volume = 0.002
[[joint_sets]]
dip_deg = 80
dip_direction_deg = 10
spacing = 1.2
origin = [0.37, 0.37, 0.37]
[[joint_sets]]
dip_deg = 70
dip_direction_deg = 100
spacing = 1.3
origin = [0.61, 0.61, 0.61]
[[joint_sets]]
dip_deg = 15
dip_direction_deg = 230
spacing = 1.1
origin = [0.23, 0.23, 0.23]
[[boundaries]]
faces = ["z_min"]
condition = "fixed"
[[stages]]
name = "shake"
gravity = [60.0, 20.0, -98.1]
kind = "steps"
steps = 500
[[stages]]
name = "shove"
gravity = [800.0, 240.0, -98.1]
kind = "steps"
steps = 1500
)";
  const fs::path scenario = write("rock_mass.toml", toml);
  const auto summaries = expect_same_outputs(dir_, scenario.string() + " 2> /dev/null",
                                             "-x BLOCKDEM_MPI_REBALANCE_STEPS=50 ", 3);
  ASSERT_EQ(summaries.size(), 2u);
  for (const auto& s : summaries) {
    EXPECT_EQ(s.at("status").get<std::string>(), "collapsed");
    EXPECT_EQ(s.at("blocks").get<int>(), 82);
    EXPECT_GT(s.at("broken_bonds").get<int>(), 0);
    EXPECT_NE(s.at("message").get<std::string>().find("diverged"), std::string::npos);
    int migrated = 0;
    for (const auto& rank : s.at("distribution")) {
      migrated += rank.at("migrated_blocks").get<int>();
      EXPECT_GE(rank.at("checkpoint_gathers").get<int>(), 1);  // the reset's
    }
    EXPECT_GT(migrated, 0);
  }
}

// A voussoir beam of the Boon et al. (2015) study (Table 2 case 1), its preload cut short after
// 300 steps (exit code 3, not converged; the outputs up to there are written all the same).
TEST_F(MpiRun, VoussoirBeamSameOutputs) {
  const fs::path scenario = fs::path(BLOCKDEM_SOURCE_DIR) / "scenarios/boon2015/T2-1.toml";
  expect_same_outputs(dir_, scenario.string() + " --max-steps 300 2> /dev/null", "", 3);
}

// A factor of safety by strength reduction: three blocks side by side on an incline (psi 30,
// phi 40: F = tan 40 / tan 30 = 1.453 for each), the trials placed by the critical factor
// extrapolated from the failed trials' accelerations. Every trial (strength_reduction.csv, with
// its acceleration), the estimate and the bracket as from one process, which places each trial
// by the estimate of the trials before it: a process that measured another acceleration would
// place its next trial elsewhere. (3,000 steps per trial: the failed ones end not converged,
// each with its acceleration; the estimate is 1.4534, as with 12,000, in a quarter of the steps.)
TEST_F(MpiRun, StrengthReductionSameTrialsEstimateAndBracket) {
  std::string text = incline_scenario(30.0, 40.0, 0.1, 0.02,
                                      "[[stages]]\nname = \"srm\"\nkind = \"strength_reduction\"\n"
                                      "factor_bounds = [0.8, 3.0]\ntolerance = 0.02\n"
                                      "max_steps = 3000\n");
  const std::string more =
      "[[blocks]]\nname = \"left\"\nmaterial = \"rock\"\nsize = [0.1, 0.1, 0.02]\n"
      "position = [-0.3, 0.0, 0.01]\n"
      "[[blocks]]\nname = \"right\"\nmaterial = \"rock\"\nsize = [0.1, 0.1, 0.03]\n"
      "position = [0.3, 0.0, 0.015]\n";
  text.insert(text.find("[[stages]]"), more);
  const fs::path scenario = write("incline.toml", text);
  // The last run's (3 processes') closing lines: the answer once, from process 0.
  const fs::path err = dir_ / "err.txt";
  const auto summaries = expect_same_outputs(dir_, scenario.string() + " 2> " + err.string());
  const std::string said = read_file(err);
  EXPECT_EQ(said.find("factor of safety"), said.rfind("factor of safety")) << said;
  EXPECT_NE(said.find("blockdem: factor of safety 1.45"), std::string::npos) << said;
  for (const auto& s : summaries) {
    const auto& fos = s.at("factor_of_safety");
    EXPECT_EQ(fos.at("search"), "extrapolate");
    EXPECT_TRUE(fos.at("extrapolated").is_number());
    EXPECT_LE(fos.at("last_stable").get<double>(), 1.4534 * 1.005);
    EXPECT_GE(fos.at("first_failed").get<double>(), 1.4534 * 0.995);
  }
  EXPECT_TRUE(fs::exists(dir_ / "out3" / "strength_reduction.csv"));
}

// Bad input: 3 processes for 2 blocks. Every process stops; one message; exit code 2; nothing
// written.
TEST_F(MpiRun, MoreRanksThanBlocksIsAnInputError) {
  BrickPile tiny;
  tiny.n = 1;
  tiny.layers = 1;  // the plate and one cube
  const fs::path scenario =
      write("tiny.toml", tiny.toml("boon2012", 30.0, Eigen::Vector3d(0, 0, -9.81), 10));
  const fs::path out = dir_ / "out";
  const fs::path log = dir_ / "log.txt";
  const std::string cmd = mpirun(3) + BLOCKDEM_CLI_PATH + " run " + scenario.string() + " --out " +
                          out.string() + " --quiet 2> " + log.string();
  EXPECT_EQ(exit_code(cmd), 2);
  const std::string err = read_file(log);
  EXPECT_NE(err.find("cannot run 2 blocks on 3 processes"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(out));
}

// A deep initial overlap on several processes: spread over processes, each checks a share of
// the candidate pairs at the set-up, and the error must still name the first offending pair in
// (i, j) order, as one process does. Six 0.1 m cubes 0.3 m apart on a fixed base, the fourth
// and the sixth sunk 1 mm into it (k_n = 1e10 Pa/m: 1e7 Pa, 26 times the bound of 100 rho g H):
// the pairs (base, cube) are the only candidates, so on 2 and 3 processes the two offending ones
// fall in different processes' shares.
TEST_F(MpiRun, InitialOverlapFoundOnTwoProcessesNamesTheFirstPairAsOneProcess) {
  std::ostringstream s;
  s << "[[materials]]\nname = \"rock\"\ndensity = 2600.0\n"
       "[[joint_laws]]\nname = \"joint\"\nnormal = { law = \"linear\", stiffness = 1e10 }\n"
       "shear = { law = \"linear\", stiffness = 1e9, friction_deg = 35 }\n"
       "[[blocks]]\nname = \"base\"\nmaterial = \"rock\"\nsize = [2.0, 0.5, 0.05]\n"
       "position = [0.75, 0.0, -0.025]\nmotion = \"fixed\"\n";
  for (int c = 1; c <= 6; ++c) {
    const double z = (c == 4 || c == 6) ? 0.049 : 0.05;
    s << "[[blocks]]\nname = \"cube" << c << "\"\nmaterial = \"rock\"\nsize = [0.1, 0.1, 0.1]\n"
      << "position = [" << 0.3 * (c - 1) << ", 0.0, " << z << "]\n";
  }
  s << "[[stages]]\nname = \"settle\"\ngravity = [0.0, 0.0, -9.81]\nmax_steps = 10\n";
  const fs::path scenario = write("sunk.toml", s.str());
  for (int ranks : {0, 2, 3}) {
    const fs::path out = dir_ / ("out" + std::to_string(ranks));
    const fs::path log = dir_ / ("log" + std::to_string(ranks) + ".txt");
    const std::string cmd = (ranks == 0 ? std::string() : mpirun(ranks)) + BLOCKDEM_CLI_PATH +
                            " run " + scenario.string() + " --out " + out.string() +
                            " --quiet 2> " + log.string();
    EXPECT_EQ(exit_code(cmd), 2) << cmd;
    const std::string err = read_file(log);
    EXPECT_NE(err.find("blocks \"base\" and \"cube4\" overlap by"), std::string::npos) << err;
    EXPECT_EQ(err.find("cube6"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(out)) << ranks << " processes";
  }
}

// Bad input on one process only (MPMD: process 1 is given a broken file): every process stops
// with process 1's message, exit code 2, nothing written.
TEST_F(MpiRun, ScenarioFailingOnOneRankStopsAll) {
  const fs::path good =
      write("good.toml", BrickPile{}.toml("boon2012", 30.0, Eigen::Vector3d(0, 0, -9.81), 10));
  const fs::path bad = write("bad.toml", "title = \"bad\"\n[settings]\ndamping = 2.0\n");
  const fs::path out = dir_ / "out";
  const fs::path log = dir_ / "log.txt";
  const std::string tail = " --out " + out.string() + " --quiet";
  const std::string cmd = mpirun(1) + BLOCKDEM_CLI_PATH + " run " + good.string() + tail +
                          " : -np 1 " + BLOCKDEM_CLI_PATH + " run " + bad.string() + tail + " 2> " +
                          log.string();
  EXPECT_EQ(exit_code(cmd), 2) << cmd;
  const std::string err = read_file(log);
  EXPECT_NE(err.find(bad.string()), std::string::npos) << err;
  EXPECT_NE(err.find("damping"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(out));
}

// A failure on process 1 alone (an exception: its scratch folder, in its temporary folder, can be
// made, but no file in it, as the file's path would be longer than PATH_MAX, 4,096 bytes on
// Linux): every process stops, and process 1 removes its scratch folder before it aborts. A file
// the system will not let it write is not a defect: exit code 4, "error", not "internal error".
TEST_F(MpiRun, ProcessFailingAloneRemovesItsScratchFolder) {
  // Process 1's temporary folder, 4,072 characters long: its scratch folder adds
  // "/blockdem-rank1-<pid>" (17 to 23 characters; the path fits in 4,095), each output file at
  // least 11 more ("/blocks.csv"; it does not).
  fs::path tmp = dir_ / "tmp";
  while (4072 - tmp.string().size() > 250) tmp /= std::string(200, 'd');
  tmp /= std::string(4072 - tmp.string().size() - 1, 'd');
  ASSERT_EQ(tmp.string().size(), 4072u);
  fs::create_directories(tmp);
  std::string err;
  EXPECT_EQ(run_with_process_one_tmpdir(tmp, err), 4);
  EXPECT_NE(err.find("blockdem: error on process 1: cannot write"), std::string::npos) << err;
  EXPECT_TRUE(fs::is_empty(tmp)) << "process 1's scratch folder was left";
}

// A process whose TMPDIR names no folder (a node without it) has nowhere for its scratch files:
// every process stops before anything is written, exit code 2, the reason printed once.
TEST_F(MpiRun, ProcessWithoutTemporaryFolderStopsEveryProcessBeforeWriting) {
  const fs::path missing = dir_ / "no_such_folder";
  std::string err;
  EXPECT_EQ(run_with_process_one_tmpdir(missing, err), 2);
  const std::string why =
      "process 1 has no temporary folder for its scratch files (TMPDIR=" + missing.string() + ")";
  EXPECT_NE(err.find(why), std::string::npos) << err;
  EXPECT_EQ(err.find(why), err.rfind(why)) << "printed more than once: " << err;
  EXPECT_FALSE(fs::exists(dir_ / "out")) << "an output folder was written";
  EXPECT_FALSE(fs::exists(missing));
}

// A process killed in the middle of a run: the others are stopped by the launcher, the run
// fails, and no summary.json claims a finished run.
TEST_F(MpiRun, DeadRankStopsTheRunWithoutSummary) {
  const fs::path scenario = write(
      "long.toml", BrickPile{}.toml("face_integrated", 20.0, Eigen::Vector3d(0, 0, -9.81), 200000));
  const fs::path out = dir_ / "out";
  const std::string tail = " --out " + out.string() + " --quiet --no-figures --threads 1";
  const std::string cmd = mpirun(1) + BLOCKDEM_CLI_PATH + " run " + scenario.string() + tail +
                          " : -np 1 timeout -s KILL 3 " + BLOCKDEM_CLI_PATH + " run " +
                          scenario.string() + tail + " > /dev/null 2>&1";
  EXPECT_NE(exit_code(cmd), 0) << cmd;
  EXPECT_FALSE(fs::exists(out / "summary.json"));
}

}  // namespace
}  // namespace blockdem::test
