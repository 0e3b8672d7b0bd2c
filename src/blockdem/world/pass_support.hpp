// Small helpers of the step's passes over slots and blocks: the OpenMP team a pass runs in, and
// prefetch hints for the block records a pass reads some slots ahead, and the kernel's hints and
// page returns for the large stores (none changes a result).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "blockdem/dynamics/block.hpp"
#include "blockdem/geometry/halfspace.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif
#ifdef __linux__
#include <sys/mman.h>
#include <unistd.h>
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

// The refresh of blocks in index order: the records follow each other, but each block's shape
// and its planes, vertices and world planes lie elsewhere on the heap, a chain of waits per block.
// Some blocks ahead the shape's record is asked for; fewer blocks ahead, once it is near, the
// arrays it points to and the block's world planes.
constexpr std::size_t kPrefetchShape = 8;   // blocks ahead: the shape's record
constexpr std::size_t kPrefetchArrays = 4;  // blocks ahead: its planes and vertices
inline void prefetch_shape(const Block& b) {
  __builtin_prefetch(b.shape.record_address());
}
inline void prefetch_shape_arrays(const Block& b) {
  const auto lines = [](const void* p, std::size_t bytes, int write) {
    const char* c = static_cast<const char*>(p);
    for (std::size_t o = 0; o < bytes; o += 64) {
      if (write != 0) {
        __builtin_prefetch(c + o, 1);
      } else {
        __builtin_prefetch(c + o);
      }
    }
  };
  lines(b.shape.planes().data(), b.shape.planes().size() * sizeof(Halfspace), 0);
  lines(b.shape.vertices().data(), b.shape.vertices().size() * sizeof(Eigen::Vector3d), 0);
  lines(b.world_planes.data(), b.world_planes.size() * sizeof(Halfspace), 1);
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

#ifdef __linux__
// The whole pages inside [p, p + bytes) of a store of 64 MiB or more (madvise wants a
// page-aligned start), as {begin, end, page size}; an empty range for a smaller store or where
// the page size is unknown.
struct PageRange {
  std::uintptr_t begin = 0, end = 0, page = 0;
  bool empty() const { return end <= begin; }
};
inline PageRange large_store_pages(const void* p, std::size_t bytes) {
  const long page_size = sysconf(_SC_PAGESIZE);
  if (p == nullptr || page_size <= 0 || bytes < (std::size_t{64} << 20)) return {};
  const auto page = static_cast<std::uintptr_t>(page_size);
  const auto first = reinterpret_cast<std::uintptr_t>(p);
  return {(first + page - 1) / page * page, (first + bytes) / page * page, page};
}
#endif

// Asks for huge pages (2 MiB on x86-64) for the storage [p, p + bytes), 64 MiB or more, where the
// kernel has them to give (transparent huge pages set to "madvise" or "always"): one page fault
// and one mapping per 2 MiB instead of 512. For a large store written from its start soon after it
// is allocated: what is resident grows by whole huge pages, so at most 2 MiB beyond what is
// written. On this project's test machine, 1.28 GB mapped and written once on 2 threads took
// 0.27-0.32 s with huge pages and 1.06-1.07 s without (a 30-line C++ program, 1 December 2026).
// A hint: nothing elsewhere or on an error, and it changes no result.
inline void prefer_huge_pages(void* p, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const PageRange r = large_store_pages(p, bytes);
  if (!r.empty()) madvise(reinterpret_cast<void*>(r.begin), r.end - r.begin, MADV_HUGEPAGE);
#else
  (void)p;
  (void)bytes;
#endif
}

// Maps the pages of [p, p + bytes) for writing, on `threads` threads at once, before one thread
// fills them: a fresh allocation of a large store (a million-block model's pair slots, 1.3 GB) is
// otherwise faulted in page by page by the thread that fills it, and a page fault is dear in a
// virtual machine. Linux 5.14's MADV_POPULATE_WRITE maps them in the kernel; a write of a zero
// byte to each page then makes the mapping for the process too (in this project's test machine's
// virtual machine that first write from the program costs as much again: 1.28 GB written by one
// thread in 1.7 s, in 0.9 s after the pages were mapped and each written once on 2 threads, and
// the store's own filling then takes 0.06 s). Only for storage that holds no objects yet: the
// bytes written are the storage's, not an object's. Nothing elsewhere or on an error: it changes
// no result.
inline void populate_pages(void* p, std::size_t bytes, int threads) {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
  const PageRange r = large_store_pages(p, bytes);
  if (r.empty()) return;
  const std::uintptr_t begin = r.begin, end = r.end, page = r.page;
  const std::int64_t pages = static_cast<std::int64_t>((end - begin) / page);
  const std::int64_t parts = std::max(threads, 1);
  prefer_huge_pages(p, bytes);
#pragma omp parallel for num_threads(threads) schedule(static) if (threads > 1)
  for (std::int64_t k = 0; k < parts; ++k) {
    const std::uintptr_t from = begin + static_cast<std::uintptr_t>(pages * k / parts) * page;
    const std::uintptr_t to = begin + static_cast<std::uintptr_t>(pages * (k + 1) / parts) * page;
    if (to <= from) continue;
    madvise(reinterpret_cast<void*>(from), to - from, MADV_POPULATE_WRITE);
    for (std::uintptr_t q = from; q < to; q += page) *reinterpret_cast<volatile char*>(q) = 0;
  }
#else
  (void)p;
  (void)bytes;
  (void)threads;
#endif
}

// Gives back the memory of a store's spare room, [size, capacity), where it is large: a store
// that holds far fewer elements than it has room for (the contact store after the first step of
// a scene: room for a state per candidate pair, about one in four used in a rock mass). The
// room's whole pages are returned to the kernel (madvise MADV_DONTNEED: the address space stays
// the store's, and a page written again later comes back zeroed), where shrink_to_fit would
// copy the elements to a new allocation while the old one is still held: 548 MB copied at the
// million-block rock mass's first step, its peak resident memory raised by as much. Below 64 MiB
// of spare room, and where madvise is not there, shrink_to_fit. The spare room holds no
// elements, so what is in its pages is not read; no result changes.
template <class T>
void release_spare_room(std::vector<T>& store) {
#if defined(__linux__) && defined(MADV_DONTNEED)
  const std::size_t spare = (store.capacity() - store.size()) * sizeof(T);
  const PageRange r = large_store_pages(store.data() + store.size(), spare);
  if (r.page != 0) {  // 64 MiB or more of spare room
    if (!r.empty()) madvise(reinterpret_cast<void*>(r.begin), r.end - r.begin, MADV_DONTNEED);
    return;
  }
#endif
  store.shrink_to_fit();
}

}  // namespace blockdem::pass_support
