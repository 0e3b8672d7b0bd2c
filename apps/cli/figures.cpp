// Locating Python with matplotlib and running the plotting scripts.
#include "figures.hpp"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

namespace blockdem::cli {
namespace {

std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') {
      out.append("'\\''");
    } else {
      out.push_back(c);
    }
  }
  out.push_back('\'');
  return out;
}

}  // namespace

std::filesystem::path data_dir() {
  if (const char* env = std::getenv("BLOCKDEM_DATA_DIR")) return env;
  std::error_code error;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) return "share/blockdem";
  const std::filesystem::path bin = exe.parent_path();
  for (const auto& candidate :
       {bin / "share" / "blockdem", bin.parent_path() / "share" / "blockdem"}) {
    if (std::filesystem::is_directory(candidate, error)) return candidate;
  }
  return bin.parent_path() / "share" / "blockdem";
}

std::string tools_dir() {
  if (const char* env = std::getenv("BLOCKDEM_TOOLS_DIR")) return env;
  return (data_dir() / "tools").string();
}

bool run_plot_script(const std::string& script, const std::vector<std::string>& args,
                     std::string& why) {
  const std::string path = tools_dir() + "/" + script;
  if (!std::filesystem::exists(path)) {
    why = "the plotting script " + path +
          " is missing (reinstall blockdem, or set BLOCKDEM_DATA_DIR)";
    return false;
  }
  // The interpreter is looked for once per process: a probe imports matplotlib (0.3 s), and a
  // run draws several figures.
  static const std::string python = [] {
    for (const char* candidate : {"/usr/bin/python3", "python3"}) {
      const std::string probe =
          std::string(candidate) + " -c 'import matplotlib, numpy' >/dev/null 2>&1";
      if (std::system(probe.c_str()) == 0) return std::string(candidate);
    }
    return std::string();
  }();
  if (python.empty()) {
    why =
        "no Python with matplotlib and numpy was found (on Debian: apt-get install "
        "python3-matplotlib)";
    return false;
  }
  std::string cmd = python;
  cmd.append(" ").append(quote(path));
  for (const auto& a : args) cmd.append(" ").append(quote(a));
  // The script's own output (a traceback, when it fails) stays out of the run's messages: a
  // failure is one line, the script and the last line it printed (the error).
  cmd.append(" 2>&1");
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (pipe == nullptr) {
    why = "could not start " + python;
    return false;
  }
  std::string output;
  std::array<char, 4096> buffer{};
  std::size_t count = 0;
  while ((count = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    output.append(buffer.data(), count);
  const int status = ::pclose(pipe);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return true;
  std::istringstream lines(output);
  std::string line, last;
  while (std::getline(lines, line))
    if (!line.empty()) last = line;
  why = script + " failed" + (last.empty() ? std::string() : ": " + last);
  return false;
}

std::string default_python() {
  std::error_code error;
  return std::filesystem::exists("/usr/bin/python3", error) ? "/usr/bin/python3" : "python3";
}

PlotOutcome run_calibration_plots(const std::filesystem::path& dir, const std::string& python) {
  PlotOutcome outcome;
  const std::filesystem::path script = std::filesystem::path(tools_dir()) / "calibration_plot.py";
  std::error_code error;
  if (!std::filesystem::exists(script, error)) {
    outcome.message = "the plot script " + script.string() + " is missing";
    return outcome;
  }
  const std::string command =
      quote(python) + " " + quote(script.string()) + " " + quote(dir.string()) + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) {
    outcome.message = "could not start " + python;
    return outcome;
  }
  std::string output;
  std::array<char, 4096> buffer{};
  std::size_t count = 0;
  while ((count = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) {
    output.append(buffer.data(), count);
  }
  const int status = ::pclose(pipe);
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::istringstream lines(output);
  std::string line;
  if (code == 0) {
    // The script prints the PNG file names it wrote, one per line.
    while (std::getline(lines, line)) {
      if (line.size() > 4 && line.substr(line.size() - 4) == ".png") outcome.files.push_back(line);
    }
    outcome.written = true;
    return outcome;
  }
  std::string last;
  while (std::getline(lines, line)) {
    if (!line.empty()) last = line;
  }
  if (code == 3) {
    outcome.message = "matplotlib is unavailable to " + python + " (" + last + ")";
  } else if (code == 127) {
    outcome.message = "the Python interpreter " + python + " was not found";
  } else {
    outcome.message = python + " " + script.string() + " failed (exit code " +
                      std::to_string(code) + ")" + (last.empty() ? "" : ": " + last);
  }
  return outcome;
}

}  // namespace blockdem::cli
