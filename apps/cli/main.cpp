// blockdem command-line program: one subcommand per job, registered from the table below.
#include <CLI/CLI.hpp>

#include <unistd.h>

#include <array>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <new>
#include <stdexcept>
#include <string_view>

#include "blockdem/io/output_error.hpp"
#include "commands.hpp"

namespace {

// The environment the program runs in, set before the libraries read it: they read it when the
// program loads, before main, so the program starts itself again, once, with it set. A setting
// the user made is kept.
//
// How OpenMP's threads wait at the end of a parallel pass. The library's own default spins for
// a while before it sleeps; on a machine whose other cores are busy, a spinning thread takes the
// core that the thread still working needs, and two threads run slower than one (bench/README.md,
// "Threads on a busy machine"). OMP_WAIT_POLICY=passive unless the user set it or GOMP_SPINCOUNT.
//
// `blockdem generate` makes a million cells and blocks in small allocations it keeps to the end,
// and in a virtual machine each page of them costs a page fault: with glibc's allocator on
// transparent huge pages (GLIBC_TUNABLES=glibc.malloc.hugetlb=1; where the system offers them)
// the million-block rock mass of bench/million.sh was cut and written in 20.5 s instead of 29.7 s
// (bench/README.md, "A million blocks generated on every core"). Only there: a run's memory is
// sized by its 4 KB pages (docs/rock-mass.md).
void choose_environment(int argc, char** argv) {
  bool again = false;
  if (std::getenv("OMP_WAIT_POLICY") == nullptr && std::getenv("GOMP_SPINCOUNT") == nullptr)
    again |= setenv("OMP_WAIT_POLICY", "passive", 1) == 0;
  if (argc > 1 && std::string_view(argv[1]) == "generate" &&
      std::getenv("GLIBC_TUNABLES") == nullptr)
    again |= setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1", 1) == 0;
  if (!again) return;
  // Started again from its file's path, so that the process keeps its name ("blockdem" in ps,
  // top and pgrep; started as /proc/self/exe it would be "exe"), else as /proc/self/exe (the file
  // moved or removed since).
  std::array<char, 4096> self{};
  const ssize_t length = readlink("/proc/self/exe", self.data(), self.size() - 1);
  if (length > 0) execv(self.data(), argv);
  execv("/proc/self/exe", argv);
  // Not started again (no /proc): run on under the libraries' defaults.
}

}  // namespace

int main(int argc, char** argv) {
  choose_environment(argc, argv);
  CLI::App app{"blockdem: rigid polyhedral blocks with compliant joints, for jointed rock masses"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("blockdem ") + blockdem::cli::version());

  // The subcommands. Each registers its own options and its callback.
  blockdem::cli::register_run(app);
  blockdem::cli::register_reproduce(app);
  blockdem::cli::register_analytic(app);
  blockdem::cli::register_lab(app);
  blockdem::cli::register_calibrate(app);
  blockdem::cli::register_generate(app);
  blockdem::cli::register_keyblocks(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // A bad command line is an input error like any other: exit code 2 (README, exit codes).
    std::cerr << "blockdem: error: " << e.what() << "\nRun with --help for more information.\n";
    return 2;
  } catch (const std::invalid_argument& e) {
    // A subcommand's check of a value it was given.
    std::cerr << "blockdem: error: " << e.what() << "\n";
    return 2;
  } catch (const std::bad_alloc&) {
    // The system's limit, not a defect: exit code 4 (README, exit codes).
    std::cerr << "blockdem: error: out of memory: the model needs more memory than the system "
                 "gives this program (a smaller model, or a machine with more memory)\n";
    return 4;
  } catch (const blockdem::OutputError& e) {
    // A folder that cannot be written, a full disk.
    std::cerr << "blockdem: error: " << e.what() << "\n";
    return 4;
  } catch (const std::filesystem::filesystem_error& e) {
    std::cerr << "blockdem: error: " << e.what() << "\n";
    return 4;
  } catch (const std::exception& e) {
    std::cerr << "blockdem: internal error: " << e.what() << "\n";
    return 1;
  }
  return blockdem::cli::exit_code();
}
