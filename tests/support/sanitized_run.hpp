// Whether the tests run under a sanitizer: scripts/sanitize.sh and scripts/sanitize_thread.sh set
// BLOCKDEM_TEST_SANITIZED=1, where a step is 10 to 100 times slower. A few tests whose length
// serves only their timing or their breadth (a signal that must fall inside a stage, a fuzzer's
// number of mutants, the steps of a determinism check) are shorter there; what they assert is
// the same, and the ordinary run keeps the full length.
#pragma once

#include <cstdlib>
#include <string_view>

namespace blockdem::test {

inline bool sanitized_run() {
  const char* value = std::getenv("BLOCKDEM_TEST_SANITIZED");
  return value != nullptr && std::string_view(value) == "1";
}

}  // namespace blockdem::test
