// The blockdem subcommands: each file cmd_<name>.cpp registers one with the CLI11 app.
#pragma once

#include <CLI/CLI.hpp>

namespace blockdem::cli {

/// Version string of the program.
const char* version();
/// Exit code set by the subcommand that ran (0 on success).
int exit_code();
/// Records the exit code the program returns.
void set_exit_code(int code);

void register_run(CLI::App& app);
void register_reproduce(CLI::App& app);
void register_analytic(CLI::App& app);
void register_lab(CLI::App& app);
void register_calibrate(CLI::App& app);
void register_generate(CLI::App& app);

}  // namespace blockdem::cli
