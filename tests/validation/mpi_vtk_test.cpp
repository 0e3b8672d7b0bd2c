// VTK frames of `mpirun -np K blockdem run`: each process writes the blocks and contacts it owns
// as a piece (NAME_pK.vtu) and process 0 a .pvtu index per frame, listed by the .pvd files. The
// frames of 2 and 3 processes, read with VTK's own readers (compare_vtk_frames.py), equal those of
// one process. Skipped when the build has no MPI.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "brick_pile.hpp"
#include "support/temp_path.hpp"

// A namespace of this file's own: the unity build (cmake/build_speed.cmake) compiles it together
// with other test files that define helpers of the same names.
namespace blockdem::test::mpi_vtk_test {
namespace {

namespace fs = std::filesystem;

#ifdef BLOCKDEM_TEST_MPIEXEC
constexpr const char* kMpiexec = BLOCKDEM_TEST_MPIEXEC;
#else
constexpr const char* kMpiexec = nullptr;
#endif

int exit_code(const std::string& cmd) {
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// `blockdem run` on `ranks` processes (0: without mpirun), oversubscribed and allowed as root
/// as CI runs it, waiting processes yielding their core (tests/support/mpi_launcher.hpp says
/// why), the blocks partitioned again every 30 steps so that blocks and contacts change owner
/// between frames.
void run(int ranks, const fs::path& scenario, const fs::path& out) {
  std::ostringstream c;
  if (ranks > 0)
    c << kMpiexec << " --oversubscribe --allow-run-as-root --mca mpi_yield_when_idle 1 "
      << "-x OMP_NUM_THREADS=1 "
      << "-x BLOCKDEM_MPI_REBALANCE_STEPS=30 -np " << ranks << " ";
  c << BLOCKDEM_CLI_PATH << " run '" << scenario.string() << "' --out '" << out.string()
    << "' --quiet --no-figures --threads 1";
  ASSERT_EQ(exit_code(c.str()), 0) << c.str();
}

/// compare_vtk_frames.py: every frame of `other` (K processes) read with VTK equals `one`'s.
void expect_same_frames(const fs::path& one, const fs::path& other, int ranks) {
  const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const std::string cmd = python +
                          " '" BLOCKDEM_SOURCE_DIR "/tests/validation/compare_vtk_frames.py' '" +
                          one.string() + "' '" + other.string() + "' " + std::to_string(ranks);
  // No skip: without python3-vtk9 the script fails, and so does this test.
  EXPECT_EQ(exit_code(cmd), 0) << cmd;
}

class MpiVtk : public ::testing::Test {
 protected:
  void SetUp() override {
    if (kMpiexec == nullptr) GTEST_SKIP() << "built without MPI (BLOCKDEM_MPI=OFF)";
    dir_ = temp_path("mpi_vtk");
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  fs::path dir_;
};

// A pile of 97 cubes (3 layers) shaken sideways (gravity (60, 25, -98.1) m/s^2), two stages of
// 150 steps, frames every 20 steps and at the stage ends: 17 frames, most of them inside stages,
// with owners changing between frames. Reference: the one-process run (whole .vtu frames).
// Tolerance: none (points, cell types, polyhedron faces and every array equal after sorting the
// cells by block index, the contacts by their pair).
TEST_F(MpiVtk, PiecesOfTwoAndThreeRanksReadAsTheOneProcessFrames) {
  BrickPile pile;
  pile.n = 6;
  pile.layers = 3;
  const std::string toml =
      pile.toml("face_integrated", 20.0, Eigen::Vector3d(60, 25, -98.1), 150) + "[output]\n";
  const fs::path scenario = dir_ / "pile.toml";
  std::ofstream(scenario) << toml << "vtk_interval = 20\n";
  for (int ranks : {0, 2, 3}) run(ranks, scenario, dir_ / ("out" + std::to_string(ranks)));
  // One process: whole frames only, as without MPI.
  EXPECT_TRUE(fs::exists(dir_ / "out0/vtk/blocks_000000.vtu"));
  EXPECT_FALSE(fs::exists(dir_ / "out0/vtk/blocks_000000.pvtu"));
  for (int ranks : {2, 3}) {
    SCOPED_TRACE(std::to_string(ranks) + " processes");
    const fs::path vtk = dir_ / ("out" + std::to_string(ranks)) / "vtk";
    EXPECT_TRUE(fs::exists(vtk / "blocks_000016.pvtu"));
    EXPECT_TRUE(fs::exists(vtk / ("contacts_000016_p" + std::to_string(ranks - 1) + ".vtu")));
    EXPECT_FALSE(fs::exists(vtk / "blocks_000017.pvtu"));
    EXPECT_FALSE(fs::exists(vtk / "blocks_000000.vtu"));
    expect_same_frames(dir_ / "out0", dir_ / ("out" + std::to_string(ranks)), ranks);
  }
}

}  // namespace
}  // namespace blockdem::test::mpi_vtk_test
