// Figures are drawn by tools/plot_*.py with matplotlib; this finds a Python that has it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace blockdem::cli {

/// Runs `python tools/<script> args...` with the first of /usr/bin/python3 and python3 that can
/// import matplotlib. Returns true on success; otherwise `why` says what was missing or failed.
bool run_plot_script(const std::string& script, const std::vector<std::string>& args,
                     std::string& why);

/// Folder of the program's data (plot scripts, case files): $BLOCKDEM_DATA_DIR, else
/// share/blockdem beside the executable (a build folder) or ../share/blockdem (an installation).
std::filesystem::path data_dir();
/// Folder of the plot scripts: $BLOCKDEM_TOOLS_DIR, else data_dir()/tools.
std::string tools_dir();

struct PlotOutcome {
  bool written = false;            ///< every PNG was written
  std::vector<std::string> files;  ///< the PNG file names written
  std::string message;             ///< why not, when not written (for the user)
};

/// The Python interpreter for the plots: /usr/bin/python3 if it exists (Debian's, which has
/// matplotlib), else "python3" from PATH.
std::string default_python();

/// Runs `python tools/calibration_plot.py DIR` (in tools_dir()) on a directory holding
/// calibration.json and the fit CSVs. Never throws for a missing interpreter, script or matplotlib:
/// the outcome says what happened.
PlotOutcome run_calibration_plots(const std::filesystem::path& dir, const std::string& python);

}  // namespace blockdem::cli
