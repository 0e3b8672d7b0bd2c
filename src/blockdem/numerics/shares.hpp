// Contiguous shares of a list worked on threads, with the errors a share meets passed on.
#pragma once

#include <algorithm>
#include <cstdint>
#include <exception>
#include <vector>

namespace blockdem {

/// How many shares [0, count) is cut into for `threads` threads: several a thread (items differ
/// in cost), each of `least` items or more; one on one thread.
inline std::int64_t share_count(std::int64_t count, int threads, std::int64_t least) {
  if (threads <= 1) return 1;
  return std::max<std::int64_t>(1, std::min<std::int64_t>(8 * threads, count / least));
}

/// Calls work(k, begin, end) for the shares k of [0, count), on `threads` threads. An exception
/// thrown in a share (an allocation that fails) is caught there, and after every share has run
/// the first share's is thrown again: none may leave an OpenMP parallel region (the program
/// would end), and the first share's is the one a single thread meets first.
/// One share is a plain call, and one thread a plain loop: no parallel region (a world's passes
/// call this every step, where a small model's whole step takes microseconds).
template <class Work>
void for_each_share(std::int64_t shares, std::int64_t count, int threads, Work work) {
  if (shares == 1) {
    work(0, 0, count);
    return;
  }
  std::vector<std::exception_ptr> error(
      static_cast<std::size_t>(std::max<std::int64_t>(shares, 0)));
  const auto run = [&](std::int64_t k) {
    try {
      work(k, count * k / shares, count * (k + 1) / shares);
    } catch (...) {
      error[static_cast<std::size_t>(k)] = std::current_exception();
    }
  };
  if (threads <= 1) {
    for (std::int64_t k = 0; k < shares; ++k) run(k);
  } else {
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
    for (std::int64_t k = 0; k < shares; ++k) run(k);
  }
  for (const auto& e : error) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace blockdem
