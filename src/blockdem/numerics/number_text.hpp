// Numbers in messages as printf prints them: %g gives 1e-08 where std::to_string gives 0.000000.
#pragma once

#include <cstdio>
#include <string>

namespace blockdem {

/// `v` printed with `format` (a printf conversion of one double; default %g, 6 significant
/// digits).
inline std::string number_text(double v, const char* format = "%g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

}  // namespace blockdem
