// This process's resident memory (Linux: /proc/self/status), for the run's memory report and
// the memory benchmarks (bench/memory_ranks.sh); elsewhere the figures are unknown (-1).
#pragma once

#include <cstdint>

namespace blockdem {

struct ResidentMemory {
  std::int64_t current = -1;  ///< resident set size now (B); -1: unknown
  std::int64_t peak = -1;     ///< its largest since the start or the last restart_peak (B)
};

ResidentMemory resident_memory();

/// Gives the heap's free pages back to the system (glibc's malloc_trim), so that the resident
/// size falls after a large temporary (the scene read to build the world) is freed.
void release_free_heap();

/// Starts the peak of resident_memory() again from the current size (Linux: `5` written to
/// /proc/self/clear_refs). Tools that read the process's peak afterwards (`/usr/bin/time -v`)
/// see only what came after. False when the system does not allow it.
bool restart_peak();

}  // namespace blockdem
