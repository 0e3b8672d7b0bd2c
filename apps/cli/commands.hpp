// The blockdem subcommands: each file cmd_<name>.cpp registers one with the CLI11 app.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace blockdem::cli {

/// Version string of the program.
const char* version();
/// Exit code set by the subcommand that ran (0 on success).
int exit_code();
/// Records the exit code the program returns.
void set_exit_code(int code);

/// An option's check: a finite number > 0 ("a finite positive number of WHAT, got TEXT"; CLI11's
/// own PositiveNumber lets nan and inf through and prints its range to 300 digits).
CLI::Validator positive_number(const std::string& what);
/// A --threads of `threads` checked against this machine (0: the default): more than
/// thread_limit() is an input error, std::invalid_argument (exit code 2, before anything is
/// written).
void check_thread_count(int threads);

void register_run(CLI::App& app);
void register_reproduce(CLI::App& app);
void register_analytic(CLI::App& app);
void register_lab(CLI::App& app);
void register_calibrate(CLI::App& app);
void register_generate(CLI::App& app);
void register_keyblocks(CLI::App& app);

}  // namespace blockdem::cli
