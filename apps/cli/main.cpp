// blockdem command-line program: one subcommand per job, registered from the table below.
#include <CLI/CLI.hpp>

#include <exception>
#include <filesystem>
#include <iostream>
#include <new>
#include <stdexcept>

#include "blockdem/io/output_error.hpp"
#include "commands.hpp"

int main(int argc, char** argv) {
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
