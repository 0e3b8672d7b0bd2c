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

#include "blockdem/io/output_error.hpp"
#include "commands.hpp"

namespace {

// How OpenMP's threads wait at the end of a parallel pass. The library's own default spins for
// a while before it sleeps; on a machine whose other cores are busy, a spinning thread takes the
// core that the thread still working needs, and two threads run slower than one (bench/README.md,
// "Threads on a busy machine"). The library reads the policy from the environment when the
// program loads, before main: so the program starts itself again, once, with the policy set. A
// policy the user set (OMP_WAIT_POLICY or GOMP_SPINCOUNT) is kept.
void choose_wait_policy(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr || std::getenv("GOMP_SPINCOUNT") != nullptr) return;
  if (setenv("OMP_WAIT_POLICY", "passive", 1) != 0) return;
  // Started again from its file's path, so that the process keeps its name ("blockdem" in ps,
  // top and pgrep; started as /proc/self/exe it would be "exe"), else as /proc/self/exe (the file
  // moved or removed since).
  std::array<char, 4096> self{};
  const ssize_t length = readlink("/proc/self/exe", self.data(), self.size() - 1);
  if (length > 0) execv(self.data(), argv);
  execv("/proc/self/exe", argv);
  // Not started again (no /proc): run on under the library's default.
}

}  // namespace

int main(int argc, char** argv) {
  choose_wait_policy(argv);
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
