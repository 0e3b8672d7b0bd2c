// Whole time steps of a 3D running-bond brick pile (tests/validation/brick_pile.hpp, the layout
// of bench/make_pile.py: 4 layers of n x n and (n-1) x (n-1) cubes on a base plate, at rest under
// 1 g, damping 0.7), both contact modes, 1 and 2 threads. Counters: contacts, and
// contact_updates, a rate (contacts x steps per second of real time).
//
// Run: blockdem_bench --benchmark_filter=Pile --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "validation/brick_pile.hpp"

namespace blockdem {
namespace {

void BM_PileStep(benchmark::State& state) {
  test::BrickPile pile;
  pile.n = static_cast<int>(state.range(0));
  pile.kick = 0.0;
  WorldSettings s;
  s.gravity = Eigen::Vector3d(0, 0, -9.81);
  s.damping = 0.7;
  s.contact_mode = state.range(2) == 0 ? ContactMode::boon2012 : ContactMode::face_integrated;
  s.threads = static_cast<int>(state.range(1));
  World w = pile.world(s, 40.0);
  for (int k = 0; k < 20; ++k) w.step();  // every contact formed and warm
  double contacts = 0.0;
  for (auto _ : state) {
    w.step();
    contacts += static_cast<double>(w.contact_count());
  }
  state.counters["blocks"] = static_cast<double>(w.blocks().size());
  state.counters["contacts"] = static_cast<double>(w.contact_count());
  state.counters["contact_updates"] = benchmark::Counter(contacts, benchmark::Counter::kIsRate);
  state.SetItemsProcessed(state.iterations());  // steps per second
}

BENCHMARK(BM_PileStep)
    ->ArgNames({"n", "threads", "face_integrated"})
    ->ArgsProduct({{10, 32}, {1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace blockdem
