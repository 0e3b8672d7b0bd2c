// Shared state of the command-line program: version and exit code.
#include "commands.hpp"

namespace blockdem::cli {
namespace {
int g_exit_code = 0;
}

const char* version() {
  return BLOCKDEM_VERSION;
}
int exit_code() {
  return g_exit_code;
}
void set_exit_code(int code) {
  g_exit_code = code;
}

}  // namespace blockdem::cli
