// The collective operations of PairDistribution built on its all-gather: correct for any
// implementation (the in-process one of the tests), but every process receives everything.
#include "blockdem/world/distribution.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace blockdem {
namespace {

template <class T>
std::vector<char> to_bytes(const std::vector<T>& v) {
  std::vector<char> out(v.size() * sizeof(T));
  if (!v.empty()) std::memcpy(out.data(), v.data(), out.size());
  return out;
}

template <class T>
std::vector<T> from_bytes(const char* p, std::size_t bytes) {
  std::vector<T> out(bytes / sizeof(T));
  if (!out.empty()) std::memcpy(out.data(), p, out.size() * sizeof(T));
  return out;
}

}  // namespace

std::vector<std::vector<char>> PairDistribution::exchange(
    const std::vector<std::vector<char>>& to) {
  // One part per process: its byte count for every destination, then the bytes in rank order.
  const auto k = static_cast<std::size_t>(size());
  if (to.size() != k) throw std::logic_error("exchange: one part per process expected");
  std::vector<std::uint64_t> sizes(k);
  for (std::size_t r = 0; r < k; ++r)
    sizes[r] = static_cast<int>(r) == rank() ? 0 : static_cast<std::uint64_t>(to[r].size());
  std::vector<char> mine = to_bytes(sizes);
  for (std::size_t r = 0; r < k; ++r)
    if (static_cast<int>(r) != rank()) mine.insert(mine.end(), to[r].begin(), to[r].end());
  std::vector<std::size_t> counts;
  const std::vector<char> all = all_gather(mine, counts);
  std::vector<std::vector<char>> from(k);
  std::size_t begin = 0;
  const auto me = static_cast<std::size_t>(rank());
  for (std::size_t s = 0; s < k; ++s) {
    const auto head = from_bytes<std::uint64_t>(all.data() + begin, k * sizeof(std::uint64_t));
    std::size_t offset = begin + k * sizeof(std::uint64_t);
    for (std::size_t r = 0; r < me; ++r) offset += head[r];
    if (s != me)
      from[s].assign(all.begin() + static_cast<std::ptrdiff_t>(offset),
                     all.begin() + static_cast<std::ptrdiff_t>(offset + head[me]));
    begin += counts[s];
  }
  return from;
}

std::vector<double> PairDistribution::min(const std::vector<double>& mine) {
  std::vector<std::size_t> counts;
  const std::vector<char> all = all_gather(to_bytes(mine), counts);
  std::vector<double> out = mine;
  std::size_t begin = 0;
  for (std::size_t count : counts) {
    const auto part = from_bytes<double>(all.data() + begin, count);
    for (std::size_t i = 0; i < out.size() && i < part.size(); ++i)
      out[i] = std::min(out[i], part[i]);
    begin += count;
  }
  return out;
}

std::vector<std::int64_t> PairDistribution::sum(const std::vector<std::int64_t>& mine) {
  std::vector<std::size_t> counts;
  const std::vector<char> all = all_gather(to_bytes(mine), counts);
  std::vector<std::int64_t> out(mine.size(), 0);
  std::size_t begin = 0;
  for (std::size_t count : counts) {
    const auto part = from_bytes<std::int64_t>(all.data() + begin, count);
    for (std::size_t i = 0; i < out.size() && i < part.size(); ++i) out[i] += part[i];
    begin += count;
  }
  return out;
}

std::vector<char> PairDistribution::gather(const std::vector<char>& mine,
                                           std::vector<std::size_t>& counts) {
  std::vector<char> all = all_gather(mine, counts);
  if (rank() != 0) {
    all.clear();
    counts.clear();
  }
  return all;
}

void PairDistribution::broadcast(std::vector<char>& bytes) {
  std::vector<std::size_t> counts;
  const std::vector<char> all = all_gather(rank() == 0 ? bytes : std::vector<char>{}, counts);
  bytes.assign(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(counts.at(0)));
}

}  // namespace blockdem
