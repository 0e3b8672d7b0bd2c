// Locating Python with matplotlib and running the plotting scripts.
#include "figures.hpp"

#include <cstdlib>
#include <filesystem>

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

std::string tools_dir() {
  if (const char* env = std::getenv("BLOCKDEM_TOOLS_DIR")) return env;
  return std::string(BLOCKDEM_SOURCE_DIR) + "/tools";
}

bool run_plot_script(const std::string& script, const std::vector<std::string>& args,
                     std::string& why) {
  const std::string path = tools_dir() + "/" + script;
  if (!std::filesystem::exists(path)) {
    why = "the plotting script " + path + " is missing (set BLOCKDEM_TOOLS_DIR)";
    return false;
  }
  std::string python;
  for (const char* candidate : {"/usr/bin/python3", "python3"}) {
    const std::string probe =
        std::string(candidate) + " -c 'import matplotlib, numpy' >/dev/null 2>&1";
    if (std::system(probe.c_str()) == 0) {
      python = candidate;
      break;
    }
  }
  if (python.empty()) {
    why =
        "no Python with matplotlib and numpy was found (on Debian: apt-get install "
        "python3-matplotlib)";
    return false;
  }
  std::string cmd = python;
  cmd.append(" ").append(quote(path));
  for (const auto& a : args) cmd.append(" ").append(quote(a));
  if (std::system(cmd.c_str()) != 0) {
    why = std::string("the plotting script failed: ");
    why.append(cmd);
    return false;
  }
  return true;
}

}  // namespace blockdem::cli
