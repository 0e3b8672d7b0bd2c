// Figures are drawn by tools/plot_*.py with matplotlib; this finds a Python that has it.
#pragma once

#include <string>
#include <vector>

namespace blockdem::cli {

/// Runs `python tools/<script> args...` with the first of /usr/bin/python3 and python3 that can
/// import matplotlib. Returns true on success; otherwise `why` says what was missing or failed.
bool run_plot_script(const std::string& script, const std::vector<std::string>& args,
                     std::string& why);

/// Folder of the project's scripts: $BLOCKDEM_TOOLS_DIR, else the source tree's tools/.
std::string tools_dir();

}  // namespace blockdem::cli
