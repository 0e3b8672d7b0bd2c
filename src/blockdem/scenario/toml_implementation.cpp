// The toml++ parser's implementation, compiled here from the library's headers with the
// settings of CMakeLists.txt (numbers through std::from_chars); every other file includes the
// declarations only (TOML_HEADER_ONLY=0).
#define TOML_IMPLEMENTATION
#include <toml++/toml.h>
