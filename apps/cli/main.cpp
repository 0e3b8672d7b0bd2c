// blockdem command-line program: one subcommand per job, registered from the table below.
#include <CLI/CLI.hpp>

#include <cstdlib>
#include <exception>
#include <iostream>
#include <stdexcept>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "commands.hpp"

namespace {

// glibc serves a request below its mmap threshold from the main heap, and the threshold grows
// to the size of each large mmapped block freed (up to 32 MiB): once a run has read its scenario
// text (12 MB at 1e5 blocks) the step's temporaries of a few MB (broad-phase lists, per-run
// contact lists) land in the heap, where their pages stay resident after they are freed, beside
// the stores allocated after them. A fixed threshold of 1 MiB keeps such blocks in their own
// mappings, returned when freed: the 1e5 pile's peak RSS falls by ~15 MB
// (bench/README.md, "The blocks' boxes in the world only, and the allocator's mmap threshold").
// MALLOC_MMAP_THRESHOLD_ in the environment still decides when set.
void fix_mmap_threshold() {
#if defined(__GLIBC__)
  if (std::getenv("MALLOC_MMAP_THRESHOLD_") == nullptr) mallopt(M_MMAP_THRESHOLD, 1 << 20);
#endif
}

}  // namespace

int main(int argc, char** argv) {
  fix_mmap_threshold();
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
  } catch (const std::exception& e) {
    std::cerr << "blockdem: internal error: " << e.what() << "\n";
    return 1;
  }
  return blockdem::cli::exit_code();
}
