// The `mpirun` command line of the tests that start `blockdem run` on several processes. The
// launcher is BLOCKDEM_TEST_MPIEXEC, given by the build when it has MPI; without it kMpiexec is
// null and those tests skip.
#pragma once

#include <string>

namespace blockdem::test {

#ifdef BLOCKDEM_TEST_MPIEXEC
inline constexpr const char* kMpiexec = BLOCKDEM_TEST_MPIEXEC;
#else
inline constexpr const char* kMpiexec = nullptr;
#endif

/// The launcher for `ranks` processes, up to the program: oversubscribed (the CI machine has 2
/// cores), allowed as root (CI), one OpenMP thread per process, then `options` (launcher options
/// such as "-x NAME=VALUE ", each ending with a space). Also the first part of an MPMD line
/// (`... -np 1 PROGRAM : -np 1 OTHER`): the options hold for every part.
/// A waiting process yields its core (mpi_yield_when_idle): Open MPI spins otherwise whenever
/// the processes fit the cores, and on 2 cores shared with ctest's other test and the other
/// processes of a run, spinning processes took the cores from the ones with work (a 2-process
/// run of the voussoir beam: 77 s against 34 s, measured under load).
/// The processes talk through Open MPI's own point-to-point layer (pml ob1, shared memory on one
/// machine): left to choose, each process spent about 0.2 s at its start looking for network
/// hardware a one-machine test does not use (a 2-process run of a 10-step scenario: 0.60 s
/// against 0.39 s; the 21 Mpi* tests, one after the other: 92 s against 82 s).
/// Once a process has ended with a non-zero code (an input error, a stage cut short, a signal,
/// a death), mpirun ends the others at once (odls_base_sigkill_timeout 0) unless `options` set
/// the timeout: by default it waits up to a second before its SIGTERM and as long before its
/// SIGKILL, which every such run paid (a 2-process run ending with exit code 3 after 10 steps:
/// 1.2-2.2 s against 0.16 s). A collective stop loses nothing by it: no process exits before
/// process 0 has written its files, and the tests then also check that none needs the grace.
inline std::string mpirun(int ranks, const std::string& options = "") {
  // Appended in place (GCC 12 warns wrongly, -Warray-bounds, on the chain of operator+).
  std::string line(kMpiexec);
  line.append(
      " --oversubscribe --allow-run-as-root --mca mpi_yield_when_idle 1 --mca pml ob1 "
      "-x OMP_NUM_THREADS=1 ");
  if (options.find("odls_base_sigkill_timeout") == std::string::npos)
    line.append("--mca odls_base_sigkill_timeout 0 ");
  line.append(options).append("-np ").append(std::to_string(ranks)).append(" ");
  return line;
}

}  // namespace blockdem::test
