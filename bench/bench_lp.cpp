// Benchmarks of the overlap LP (Boon et al. 2012): the fast active-set solver against COIN-OR CLP
// on cube-cube face contacts and random hull pairs, cold and warm started along trajectories.
//
// Run: blockdem_bench --benchmark_filter=LP --benchmark_repetitions=10
//      --benchmark_report_aggregates_only=true
// Each benchmark iteration is one LP solve, so the reported time is the time per solve.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "blockdem/collision/inscribed_ball.hpp"
#include "oracle/clp_lp.hpp"
#include "support/random_shapes.hpp"

namespace blockdem {
namespace {

using test_shapes::Planes;

// A set of contact pairs, each given at `kSteps` consecutive time steps of a small rigid motion
// of B; solves walk the steps forward and back (ping-pong), so that consecutive solves of a pair
// are always neighbouring steps, as in a simulation.
struct Scene {
  std::vector<std::vector<Planes>> steps;  // [pair][step]
};

constexpr int kSteps = 64;

// Pair p at step s, for the i-th solve of a scene (pairs cycle fastest).
const Planes& pair_at(const Scene& scene, long i, int& pair) {
  const long pairs = static_cast<long>(scene.steps.size());
  pair = static_cast<int>(i % pairs);
  const long phase = (i / pairs) % (2 * kSteps);
  const long step = phase < kSteps ? phase : 2 * kSteps - 1 - phase;
  return scene.steps[pair][step];
}

// B moved by `step` increments of a rigid motion: turn `omega` (rad per step) about `axis`
// through B's reference point `centre`, and translation `velocity` (m per step).
Planes moved(const Planes& b, const Eigen::Vector3d& centre, const Eigen::Vector3d& axis,
             double omega, const Eigen::Vector3d& velocity, int step) {
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(omega * step, axis).toRotationMatrix();
  return test_shapes::transformed(b, turn, centre - turn * centre + step * velocity);
}

// (a) Cube on cube (unit cubes), faces in contact with a closure of 1e-4 and a lateral offset;
// the whole pair randomly oriented. `tilt` turns B about a horizontal axis (rad). The motion per
// step is 1e-7 m of closure and 1e-7 rad of tilt.
Scene cube_face_scene(double tilt) {
  test_shapes::Rng rng(7);
  Scene scene;
  const Eigen::Vector3d half = Eigen::Vector3d::Constant(0.5);
  for (int p = 0; p < 16; ++p) {
    const Eigen::Matrix3d frame = test_shapes::random_rotation(rng);
    const Eigen::Vector3d centre_b =
        frame * Eigen::Vector3d(test_shapes::uniform(rng, -0.2, 0.2),
                                test_shapes::uniform(rng, -0.2, 0.2), 1.0 - 1e-4);
    const Eigen::Vector3d horizontal = frame * Eigen::Vector3d(1.0, 0.0, 0.0);
    const Planes a = test_shapes::box(half, frame, Eigen::Vector3d::Zero());
    const Planes b = moved(test_shapes::box(half, frame, centre_b), centre_b, horizontal, tilt,
                           Eigen::Vector3d::Zero(), 1);
    std::vector<Planes> steps;
    for (int s = 0; s < kSteps; ++s) {
      const double omega = tilt == 0.0 ? 0.0 : 1e-7;
      steps.push_back(test_shapes::concat(
          a, moved(b, centre_b, horizontal, omega, frame * Eigen::Vector3d(0, 0, -1e-7), s)));
    }
    scene.steps.push_back(steps);
  }
  return scene;
}

// (b) Random sphere-tangent hulls of 8..14 planes each (16..28 per pair), B's vertex pushed
// 1e-3 into a random face of A; B turns 1e-5 rad and moves 1e-5 m per step.
Scene random_hull_scene() {
  test_shapes::Rng rng(8);
  Scene scene;
  for (int p = 0; p < 64; ++p) {
    const Planes a = test_shapes::transformed(
        test_shapes::random_hull(rng, 8 + static_cast<int>(rng() % 7), 0.4),
        test_shapes::random_rotation(rng), Eigen::Vector3d(0.3, -0.2, 0.1));
    const Planes b_body = test_shapes::random_hull(rng, 8 + static_cast<int>(rng() % 7), 0.4);
    const Planes b = test_shapes::place_vertex_on_face(a, rng() % a.size(), b_body, -1e-3);
    // B turns about the mean of its vertices.
    Eigen::Vector3d centre_b = Eigen::Vector3d::Zero();
    const std::vector<Eigen::Vector3d> vb = test_shapes::vertices(b);
    for (const Eigen::Vector3d& v : vb) centre_b += v / static_cast<double>(vb.size());
    const Eigen::Vector3d axis = test_shapes::random_unit_vector(rng);
    const Eigen::Vector3d velocity = 1e-5 * test_shapes::random_unit_vector(rng);
    std::vector<Planes> steps;
    for (int s = 0; s < kSteps; ++s) {
      steps.push_back(test_shapes::concat(a, moved(b, centre_b, axis, 1e-5, velocity, s)));
    }
    scene.steps.push_back(steps);
  }
  return scene;
}

const Scene& scene(int which) {
  static const Scene cube_aligned = cube_face_scene(0.0);
  static const Scene cube_tilted = cube_face_scene(1e-3);
  static const Scene hulls = random_hull_scene();
  return which == 0 ? cube_aligned : (which == 1 ? cube_tilted : hulls);
}

void set_label(benchmark::State& state) {
  const char* names[] = {"cube face aligned", "cube face tilted 1 mrad", "random hulls"};
  state.SetLabel(names[state.range(0)]);
}

void BM_LP_FastCold(benchmark::State& state) {
  const Scene& sc = scene(static_cast<int>(state.range(0)));
  long i = 0;
  long iterations = 0;
  for (auto _ : state) {
    int pair = 0;
    const InscribedBall ball = largest_inscribed_ball(pair_at(sc, i++, pair));
    iterations += ball.iterations;
    benchmark::DoNotOptimize(ball);
  }
  state.counters["lp_steps"] = static_cast<double>(iterations) / static_cast<double>(i);
  set_label(state);
}

void BM_LP_FastWarm(benchmark::State& state) {
  const Scene& sc = scene(static_cast<int>(state.range(0)));
  std::vector<InscribedBall> previous(sc.steps.size());
  for (std::size_t p = 0; p < sc.steps.size(); ++p) {
    previous[p] = largest_inscribed_ball(sc.steps[p][0]);
  }
  long i = static_cast<long>(sc.steps.size());  // start at step 1
  long iterations = 0;
  for (auto _ : state) {
    int pair = 0;
    const Planes& planes = pair_at(sc, i++, pair);
    previous[pair] = largest_inscribed_ball(planes, previous[pair]);
    iterations += previous[pair].iterations;
    benchmark::DoNotOptimize(previous[pair]);
  }
  state.counters["lp_steps"] =
      static_cast<double>(iterations) / static_cast<double>(i - static_cast<long>(sc.steps.size()));
  set_label(state);
}

void BM_LP_ClpCold(benchmark::State& state) {
  const Scene& sc = scene(static_cast<int>(state.range(0)));
  long i = 0;
  for (auto _ : state) {
    int pair = 0;
    benchmark::DoNotOptimize(oracle::clp_inscribed_ball(pair_at(sc, i++, pair)));
  }
  set_label(state);
}

void BM_LP_ClpWarm(benchmark::State& state) {
  const Scene& sc = scene(static_cast<int>(state.range(0)));
  std::vector<oracle::ClpInscribedBallSolver> solvers(sc.steps.size());
  for (std::size_t p = 0; p < sc.steps.size(); ++p) solvers[p].solve(sc.steps[p][0]);
  long i = static_cast<long>(sc.steps.size());
  for (auto _ : state) {
    int pair = 0;
    const Planes& planes = pair_at(sc, i++, pair);
    benchmark::DoNotOptimize(solvers[pair].solve(planes));
  }
  set_label(state);
}

BENCHMARK(BM_LP_FastCold)->DenseRange(0, 2);
BENCHMARK(BM_LP_FastWarm)->DenseRange(0, 2);
BENCHMARK(BM_LP_ClpCold)->DenseRange(0, 2);
BENCHMARK(BM_LP_ClpWarm)->DenseRange(0, 2);

}  // namespace
}  // namespace blockdem
