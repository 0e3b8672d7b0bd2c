// Benchmarks of whole time steps (World::step: geometry, broad phase, narrow phase, joint laws,
// integration, checks) for stacks of N blocks under gravity: a column of N cubes on a fixed base,
// and a running-bond wall of N cubes; contact mode boon2012 (the paper's), and the wall also in
// mode face_integrated for comparison.
//
// Run: blockdem_bench --benchmark_filter=World --benchmark_repetitions=10
//      --benchmark_report_aggregates_only=true
// Each benchmark iteration is one time step; items_per_second is steps per second (real time).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>

#include "validation/scenes.hpp"

namespace blockdem {
namespace {

constexpr double kEdge = 0.046;      // cube edge, as the voussoir blocks (m)
constexpr double kDensity = 1207.0;  // gypsum (kg/m^3)
constexpr double kNormal = 1e10;     // joint normal stiffness (Pa/m), Table 2 of the paper
constexpr double kShear = 1e9;       // joint shear stiffness (Pa/m)
constexpr double kFriction = 40.0;   // (degrees)
constexpr double kGravity = 9.81;    // (m/s^2)
constexpr int kWarmUpSteps = 20;     // steps before timing, so that every contact has formed

WorldSettings settings(ContactMode mode) {
  WorldSettings s;
  s.contact_mode = mode;
  s.gravity = Eigen::Vector3d(0, 0, -kGravity);
  s.damping = 0.7;
  return s;
}

// Static closure of a joint carrying `blocks` cubes (m): their weight over k_n times the face.
double closure_under(int blocks) {
  const double weight = kDensity * kEdge * kEdge * kEdge * kGravity;
  return blocks * weight / (kNormal * kEdge * kEdge);
}

// A column of n cubes on a fixed base plate, each joint closed by its static closure, so the
// column starts near equilibrium with all n contacts in place.
World column(int n, ContactMode mode) {
  World w = test::linear_world(kNormal, kShear, kFriction, settings(mode));
  w.add_block(test::box_block({0.2, 0.2, 0.05}, {0, 0, -0.025}, kDensity, Motion::fixed, "base"));
  double bottom = 0.0;
  for (int i = 0; i < n; ++i) {
    bottom -= closure_under(n - i);
    w.add_block(test::box_block({kEdge, kEdge, kEdge}, {0, 0, bottom + kEdge / 2}, kDensity));
    bottom += kEdge;
  }
  return w;
}

// A running-bond wall of n cubes in rows of ceil(sqrt(n)) (odd rows shifted by half a block) on
// a fixed base: each cube rests on two below across half faces; cubes in a row touch side by
// side without overlap (candidate pairs that are not contacts). Joints start closed by the
// static closure of the rows above.
World wall(int n, ContactMode mode) {
  World w = test::linear_world(kNormal, kShear, kFriction, settings(mode));
  const int width = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  const int rows = (n + width - 1) / width;
  const double length = (width + 1) * kEdge;
  w.add_block(test::box_block({length + 0.1, 0.2, 0.05}, {length / 2, 0, -0.025}, kDensity,
                              Motion::fixed, "base"));
  double bottom = 0.0;
  int placed = 0;
  for (int row = 0; row < rows && placed < n; ++row) {
    bottom -= closure_under(rows - row);
    const double shift = (row % 2 == 0) ? 0.0 : kEdge / 2;
    for (int k = 0; k < width && placed < n; ++k, ++placed) {
      w.add_block(test::box_block({kEdge, kEdge, kEdge},
                                  {shift + (k + 0.5) * kEdge, 0, bottom + kEdge / 2}, kDensity));
    }
    bottom += kEdge;
  }
  return w;
}

void run(benchmark::State& state, World w) {
  for (int i = 0; i < kWarmUpSteps; ++i) w.step();
  for (auto _ : state) w.step();
  state.SetItemsProcessed(state.iterations());
  state.counters["blocks"] = static_cast<double>(w.blocks().size() - 1);
  state.counters["contacts"] = static_cast<double>(w.contact_count());
}

void BM_World_Column(benchmark::State& state) {
  run(state, column(static_cast<int>(state.range(0)), ContactMode::boon2012));
}

void BM_World_Wall(benchmark::State& state) {
  run(state, wall(static_cast<int>(state.range(0)), ContactMode::boon2012));
}

void BM_World_WallFaceIntegrated(benchmark::State& state) {
  run(state, wall(static_cast<int>(state.range(0)), ContactMode::face_integrated));
}

// The same wall without the joints' twisting resistance (issue 14: its cost in a whole step).
void BM_World_WallFaceIntegratedNoTwist(benchmark::State& state) {
  World w = wall(static_cast<int>(state.range(0)), ContactMode::face_integrated);
  w.settings().twist = false;
  run(state, std::move(w));
}

BENCHMARK(BM_World_Column)
    ->Arg(10)
    ->Arg(100)
    ->Arg(1000)
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK(BM_World_Wall)
    ->Arg(10)
    ->Arg(100)
    ->Arg(1000)
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK(BM_World_WallFaceIntegrated)
    ->Arg(10)
    ->Arg(100)
    ->Arg(1000)
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK(BM_World_WallFaceIntegratedNoTwist)
    ->Arg(10)
    ->Arg(100)
    ->Arg(1000)
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();

}  // namespace
}  // namespace blockdem
