// Rock slicing cost (rockmass/rock_slicer.hpp): a box cut by three persistent joint sets into
// about N blocks, N = 1e3, 1e4, 1e5 (target: 1e5 blocks in at most 5 s on one core, cost
// growing no faster than N log N).
//
// Run: blockdem_bench --benchmark_filter=RockSlicing --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true
// One iteration is one whole slicing of the region; counters give the block count and the CPU
// time per block (CPU time, not real time: the machine is shared).
#include <benchmark/benchmark.h>

#include <cmath>

#include "blockdem/rockmass/rock_slicer.hpp"

namespace blockdem {
namespace {

JointSet set(const char* name, double dip, double dir, double spacing) {
  JointSet s;
  s.name = name;
  s.dip_deg = dip;
  s.dip_direction_deg = dir;
  s.spacing.mean = spacing;
  s.origin = Eigen::Vector3d(50.3, 50.7, 50.1);
  return s;
}

// A 100 m cube; spacing chosen so that the sets make about N blocks: orthogonal sets make
// (100/s)^3 blocks; the oblique sets (dips 35, 70, 85 degrees) cut blocks of volume
// s^3 / |det(n1, n2, n3)|.
RockMassSpec spec(long n, bool oblique) {
  RockMassSpec sp;
  sp.region = Region::box({0, 0, 0}, {100, 100, 100});
  if (oblique) {
    const JointSet a = set("J1", 35, 120, 1), b = set("J2", 70, 230, 1), c = set("J3", 85, 10, 1);
    Eigen::Matrix3d m;
    m << a.normal(), b.normal(), c.normal();
    const double s = std::cbrt(1e6 * std::abs(m.determinant()) / static_cast<double>(n));
    sp.joint_sets = {set("J1", 35, 120, s), set("J2", 70, 230, s), set("J3", 85, 10, s)};
  } else {
    const double s = 100.0 / std::cbrt(static_cast<double>(n));
    sp.joint_sets = {set("J1", 90, 90, s), set("J2", 90, 0, s), set("J3", 0, 0, s)};
  }
  return sp;
}

void run(benchmark::State& state, bool oblique) {
  const RockMassSpec sp = spec(state.range(0), oblique);
  std::size_t blocks = 0;
  for (auto _ : state) {
    const RockMass rm = slice_rock_mass(sp);
    blocks = rm.blocks.size();
    benchmark::DoNotOptimize(rm.blocks.data());
  }
  state.counters["blocks"] = static_cast<double>(blocks);
  // Seconds of CPU time per block (printed with an SI prefix: 2.1u = 2.1 µs).
  state.counters["time_per_block"] =
      benchmark::Counter(static_cast<double>(blocks) * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_RockSlicing_Orthogonal(benchmark::State& state) {
  run(state, false);
}
void BM_RockSlicing_Oblique(benchmark::State& state) {
  run(state, true);
}

BENCHMARK(BM_RockSlicing_Orthogonal)
    ->Arg(1000)
    ->Arg(10000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RockSlicing_Oblique)
    ->Arg(1000)
    ->Arg(10000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace blockdem
