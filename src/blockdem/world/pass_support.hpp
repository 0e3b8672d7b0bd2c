// Small helpers of the step's passes over slots and blocks: the OpenMP team a pass runs in, and
// prefetch hints for the block records a pass reads some slots ahead (hints change no result).
#pragma once

#include <cstddef>

#include "blockdem/dynamics/block.hpp"
#include "blockdem/geometry/halfspace.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace blockdem::pass_support {

// The size of the current OpenMP team and this thread's rank in it (1 and 0 outside OpenMP).
inline int team_size() {
#ifdef _OPENMP
  return omp_get_num_threads();
#else
  return 1;
#endif
}

inline int team_rank() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

// Prefetching for the per-pair passes. The slots are in (a, b) order: a pair's block a is
// mostly the last pair's, but its block b lies anywhere up to a layer of blocks away in memory,
// and in a scene of 1e5 blocks what lies between no longer fits the caches. Each pass asks for
// the block record of a pair some slots ahead (its per-pair fields, the first bytes of the record:
// see Block) and, fewer slots ahead, once the record is near, for the block's world planes.
// Prefetches are hints: they change no result.
constexpr std::size_t kPrefetchRecord = 16;  // slots ahead: a block's record
constexpr std::size_t kPrefetchPlanes = 8;   // slots ahead: its world planes

// The record's per-pair fields, bytes [0, 120) (see Block): three cache lines at most.
inline void prefetch_record(const Block& b) {
  const char* p = reinterpret_cast<const char*>(&b);
  __builtin_prefetch(p);
  __builtin_prefetch(p + 64);
  __builtin_prefetch(p + 119);
}

// The fields the loads' scatter reads and writes: bytes [0, 200) of the record.
inline void prefetch_loads(const Block& b) {
  const char* p = reinterpret_cast<const char*>(&b);
  __builtin_prefetch(p, 1);
  __builtin_prefetch(p + 64, 1);
  __builtin_prefetch(p + 128, 1);
  __builtin_prefetch(p + 199, 1);
}

inline void prefetch_planes(const Block& b) {
  const char* p = reinterpret_cast<const char*>(b.world_planes.data());
  const std::size_t bytes = b.world_planes.size() * sizeof(Halfspace);
  for (std::size_t o = 0; o < bytes; o += 64) __builtin_prefetch(p + o);
}

}  // namespace blockdem::pass_support
