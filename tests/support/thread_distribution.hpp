// K worlds in K threads standing in for K processes (without MPI): an in-process all-gather
// (the collective the others are built on) that returns when every thread has given its part.
// The distributed step's tests compare such worlds with one world alone.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

#include "blockdem/parallel/rcb.hpp"
#include "blockdem/world/distribution.hpp"

namespace blockdem::test {

/// The meeting point of K threads: all_gather returns when every thread has given its part.
struct Meeting {
  explicit Meeting(int n) : size(n), parts(static_cast<std::size_t>(n)) {}
  std::mutex mutex;
  std::condition_variable cv;
  int size;
  int arrived = 0;
  int round = 0;
  std::vector<std::vector<char>> parts;
  std::vector<char> all;
  std::vector<std::size_t> counts;
};

class ThreadDistribution final : public PairDistribution {
 public:
  /// `repartition_interval`: steps between partitions (0: partition once).
  ThreadDistribution(std::shared_ptr<Meeting> m, int rank, std::int64_t repartition_interval = 0)
      : m_(std::move(m)), rank_(rank), repartition_interval_(repartition_interval) {}
  int rank() const override { return rank_; }
  int size() const override { return m_->size; }
  std::vector<int> partition(std::span<const Eigen::Vector3d> points,
                             std::span<const double> weights) const override {
    return recursive_coordinate_bisection(points, weights, m_->size);
  }
  std::int64_t repartition_interval() const override { return repartition_interval_; }
  std::vector<char> all_gather(const std::vector<char>& mine,
                               std::vector<std::size_t>& counts) override {
    std::unique_lock lock(m_->mutex);
    m_->parts[static_cast<std::size_t>(rank_)] = mine;
    const int round = m_->round;
    if (++m_->arrived == m_->size) {
      m_->all.clear();
      m_->counts.clear();
      for (const auto& p : m_->parts) {
        m_->all.insert(m_->all.end(), p.begin(), p.end());
        m_->counts.push_back(p.size());
      }
      m_->arrived = 0;
      ++m_->round;
      m_->cv.notify_all();
    } else {
      m_->cv.wait(lock, [&] { return m_->round != round; });
    }
    counts = m_->counts;
    return m_->all;
  }

 private:
  std::shared_ptr<Meeting> m_;
  int rank_;
  std::int64_t repartition_interval_;
};

}  // namespace blockdem::test
