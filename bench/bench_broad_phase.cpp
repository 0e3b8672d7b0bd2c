// Broad phase: sweep and prune against the uniform grid on the boxes of a 3D running-bond brick
// pile (10 layers, n x n cubes per even layer; the layout of bench/make_pile.py) with a base
// plate, N = 1e3, 1e4, 1e5 boxes, 1 and 2 threads. Each iteration finds every candidate pair.
//
// Run: blockdem_bench --benchmark_filter=BroadPhase --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "blockdem/collision/broad_phase.hpp"
#include "blockdem/collision/uniform_grid.hpp"

namespace blockdem {
namespace {

// Boxes of the pile: n x n cubes per even layer, (n-1) x (n-1) shifted by half per odd layer.
void pile_boxes(int n, std::vector<Eigen::Vector3d>& lo, std::vector<Eigen::Vector3d>& hi) {
  const double s = 0.046, pre = 5e-8;
  lo = {Eigen::Vector3d(-s, -s, -s)};
  hi = {Eigen::Vector3d((n + 1) * s, (n + 1) * s, 0.0)};
  for (int l = 0; l < 10; ++l) {
    const int m = l % 2 == 0 ? n : n - 1;
    const double shift = l % 2 == 0 ? 0.0 : 0.5 * s;
    const double z = l * s - (l + 1) * pre;
    for (int i = 0; i < m; ++i) {
      for (int j = 0; j < m; ++j) {
        const Eigen::Vector3d c(shift + i * s, shift + j * s, z);
        lo.push_back(c);
        hi.push_back(c + Eigen::Vector3d::Constant(s));
      }
    }
  }
}

template <class BroadPhase>
void BM_BroadPhase(benchmark::State& state) {
  std::vector<Eigen::Vector3d> lo, hi;
  pile_boxes(static_cast<int>(state.range(0)), lo, hi);
  const int threads = static_cast<int>(state.range(1));
  BroadPhase bp;
  std::vector<std::pair<int, int>> pairs;
  for (auto _ : state) {
    bp.find_pairs(
        lo, hi, [](int, int) { return true; }, pairs, threads);
    benchmark::DoNotOptimize(pairs.data());
  }
  state.counters["boxes"] = static_cast<double>(lo.size());
  state.counters["pairs"] = static_cast<double>(pairs.size());
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(lo.size()));
}

void pile_sizes(benchmark::internal::Benchmark* b) {
  for (int n : {10, 32, 100}) {
    for (int t : {1, 2}) b->Args({n, t});
  }
  b->ArgNames({"n", "threads"})->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK_TEMPLATE(BM_BroadPhase, SweepAndPrune)->Apply(pile_sizes);
BENCHMARK_TEMPLATE(BM_BroadPhase, UniformGrid)->Apply(pile_sizes);

}  // namespace
}  // namespace blockdem
