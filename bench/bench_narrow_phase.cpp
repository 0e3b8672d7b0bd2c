// Benchmarks of the whole Boon et al. (2012) narrow phase per candidate pair (overlap LP, analytic
// centre, normal, chord overlap, slice area: boon2012_contact), against the same pipeline with the
// LP solved by COIN-OR CLP, on 46 mm cube face contacts and random hull pairs, cold and warm.
//
// Run: blockdem_bench --benchmark_filter=Narrow --benchmark_repetitions=10
//      --benchmark_report_aggregates_only=true
// Each benchmark iteration is one candidate pair, so the reported time is the time per pair.
// bench/ratios.py prints the CLP / fast ratios from a JSON report of the same run.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "blockdem/collision/boon2012.hpp"
#include "oracle/clp_boon2012.hpp"
#include "support/random_shapes.hpp"

namespace blockdem {
namespace {

using test_shapes::Planes;

// One candidate pair at consecutive time steps of a small rigid motion of B.
struct PairPath {
  Planes a;
  std::vector<Planes> b;  // [step]
  double extent = 0.0;    // (m), as the world passes it: twice the sum of the bounding radii
};

// A set of pairs; solves cycle through the pairs (fastest) and walk the steps forward and back
// (ping-pong), so that consecutive solves of a pair are neighbouring steps, as in a simulation.
struct Scene {
  std::vector<PairPath> pairs;
};

constexpr int kSteps = 64;
constexpr double kCube = 0.046;                           // voussoir block edge (m)
const double kCubeRadius = 0.5 * kCube * std::sqrt(3.0);  // its bounding radius (m)

const PairPath& pair_at(const Scene& scene, long i, int& pair, int& step) {
  const long pairs = static_cast<long>(scene.pairs.size());
  pair = static_cast<int>(i % pairs);
  const long phase = (i / pairs) % (2 * kSteps);
  step = static_cast<int>(phase < kSteps ? phase : 2 * kSteps - 1 - phase);
  return scene.pairs[pair];
}

// B moved by `step` increments of a rigid motion: turn `omega` (rad per step) about `axis`
// through `centre`, and translation `velocity` (m per step).
Planes moved(const Planes& b, const Eigen::Vector3d& centre, const Eigen::Vector3d& axis,
             double omega, const Eigen::Vector3d& velocity, int step) {
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(omega * step, axis).toRotationMatrix();
  return test_shapes::transformed(b, turn, centre - turn * centre + step * velocity);
}

// Cube B on cube A (46 mm), faces in contact with a closure of `closure` (m; negative: a gap),
// B offset sideways by up to 2 mm. `aligned`: world axes, as in the voussoir beam, B moving by
// 1 nm per step (closure and slip); otherwise the pair randomly oriented, B tilted by 0.1 mrad
// (a wedge-shaped overlap) and turning by a further 10 nrad per step about a horizontal axis.
Scene cube_scene(bool aligned, double closure) {
  test_shapes::Rng rng(aligned ? 11 : 12);
  Scene scene;
  const Eigen::Vector3d half = Eigen::Vector3d::Constant(0.5 * kCube);
  for (int p = 0; p < 16; ++p) {
    const Eigen::Matrix3d frame =
        aligned ? Eigen::Matrix3d::Identity() : test_shapes::random_rotation(rng);
    const Eigen::Vector3d centre_b =
        frame * Eigen::Vector3d(test_shapes::uniform(rng, -2e-3, 2e-3),
                                test_shapes::uniform(rng, -2e-3, 2e-3), kCube - closure);
    const Eigen::Vector3d horizontal = frame * Eigen::Vector3d::UnitX();
    PairPath path;
    path.a = test_shapes::box(half, frame, Eigen::Vector3d::Zero());
    path.extent = 4.0 * kCubeRadius;
    const Planes b0 = moved(test_shapes::box(half, frame, centre_b), centre_b, horizontal,
                            aligned ? 0.0 : 1e-4, Eigen::Vector3d::Zero(), 1);
    const double omega = aligned ? 0.0 : 1e-8;
    const Eigen::Vector3d velocity = frame * Eigen::Vector3d(1e-9, 0.0, -1e-9);
    for (int s = 0; s < kSteps; ++s)
      path.b.push_back(moved(b0, centre_b, horizontal, omega, velocity, s));
    scene.pairs.push_back(path);
  }
  return scene;
}

// Random sphere-tangent hulls of 8..14 planes, in-radius 20 mm, B's vertex pushed 20 µm into a
// random face of A; B turns by 0.1 µrad and moves by 1 nm per step.
Scene hull_scene() {
  test_shapes::Rng rng(13);
  Scene scene;
  const double radius = 0.02;
  for (int p = 0; p < 64; ++p) {
    PairPath path;
    path.a = test_shapes::transformed(
        test_shapes::random_hull(rng, 8 + static_cast<int>(rng() % 7), radius),
        test_shapes::random_rotation(rng), Eigen::Vector3d(0.01, -0.02, 0.005));
    const Planes b_body = test_shapes::random_hull(rng, 8 + static_cast<int>(rng() % 7), radius);
    const Planes b =
        test_shapes::place_vertex_on_face(path.a, rng() % path.a.size(), b_body, -2e-5);
    const std::vector<Eigen::Vector3d> va = test_shapes::vertices(path.a);
    const std::vector<Eigen::Vector3d> vb = test_shapes::vertices(b);
    Eigen::Vector3d centre_b = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& v : vb) centre_b += v / static_cast<double>(vb.size());
    path.extent = 2.0 * (test_shapes::diameter(va) + test_shapes::diameter(vb));
    const Eigen::Vector3d axis = test_shapes::random_unit_vector(rng);
    const Eigen::Vector3d velocity = 1e-9 * test_shapes::random_unit_vector(rng);
    for (int s = 0; s < kSteps; ++s) path.b.push_back(moved(b, centre_b, axis, 1e-7, velocity, s));
    scene.pairs.push_back(path);
  }
  return scene;
}

const char* const kSceneNames[] = {"cube face aligned (voussoir)", "cube face tilted 0.1 mrad",
                                   "random hulls", "cubes 10 um apart"};

const Scene& scene(int which) {
  static const Scene aligned = cube_scene(true, 1e-5);
  static const Scene tilted = cube_scene(false, 1e-5);
  static const Scene hulls = hull_scene();
  static const Scene apart = cube_scene(true, -1e-5);
  const Scene* all[] = {&aligned, &tilted, &hulls, &apart};
  return *all[which];
}

// Counts contacts found, to show that the scene does what it says.
void finish(benchmark::State& state, long calls, long touching) {
  state.counters["touching"] = static_cast<double>(touching) / static_cast<double>(calls);
  state.SetLabel(kSceneNames[state.range(0)]);
}

const Boon2012Settings kSettings{};  // r_round = 0.2 mm, as the paper's code

void BM_Narrow_FastCold(benchmark::State& state) {
  const Scene& sc = scene(static_cast<int>(state.range(0)));
  long i = 0;
  long touching = 0;
  for (auto _ : state) {
    int pair = 0, step = 0;
    const PairPath& path = pair_at(sc, i++, pair, step);
    const ContactGeometry g = boon2012_contact(path.a, path.b[step], path.extent, kSettings);
    touching += g.touching ? 1 : 0;
    benchmark::DoNotOptimize(g);
  }
  finish(state, i, touching);
}

void BM_Narrow_FastWarm(benchmark::State& state) {
  const Scene& sc = scene(static_cast<int>(state.range(0)));
  std::vector<Boon2012Cache> caches(sc.pairs.size());
  for (std::size_t p = 0; p < sc.pairs.size(); ++p) {
    boon2012_contact(sc.pairs[p].a, sc.pairs[p].b[0], sc.pairs[p].extent, kSettings, &caches[p]);
  }
  long i = static_cast<long>(sc.pairs.size());  // start at step 1
  long touching = 0;
  for (auto _ : state) {
    int pair = 0, step = 0;
    const PairPath& path = pair_at(sc, i++, pair, step);
    const ContactGeometry g =
        boon2012_contact(path.a, path.b[step], path.extent, kSettings, &caches[pair]);
    touching += g.touching ? 1 : 0;
    benchmark::DoNotOptimize(g);
  }
  finish(state, i - static_cast<long>(sc.pairs.size()), touching);
}

void BM_Narrow_ClpCold(benchmark::State& state) {
  const Scene& sc = scene(static_cast<int>(state.range(0)));
  long i = 0;
  long touching = 0;
  for (auto _ : state) {
    int pair = 0, step = 0;
    const PairPath& path = pair_at(sc, i++, pair, step);
    const ContactGeometry g =
        oracle::clp_boon2012_contact(path.a, path.b[step], path.extent, kSettings);
    touching += g.touching ? 1 : 0;
    benchmark::DoNotOptimize(g);
  }
  finish(state, i, touching);
}

void BM_Narrow_ClpWarm(benchmark::State& state) {
  const Scene& sc = scene(static_cast<int>(state.range(0)));
  std::vector<Boon2012Cache> caches(sc.pairs.size());
  std::vector<oracle::ClpInscribedBallSolver> solvers(sc.pairs.size());
  for (std::size_t p = 0; p < sc.pairs.size(); ++p) {
    oracle::clp_boon2012_contact(sc.pairs[p].a, sc.pairs[p].b[0], sc.pairs[p].extent, kSettings,
                                 &caches[p], &solvers[p]);
  }
  long i = static_cast<long>(sc.pairs.size());
  long touching = 0;
  for (auto _ : state) {
    int pair = 0, step = 0;
    const PairPath& path = pair_at(sc, i++, pair, step);
    const ContactGeometry g = oracle::clp_boon2012_contact(
        path.a, path.b[step], path.extent, kSettings, &caches[pair], &solvers[pair]);
    touching += g.touching ? 1 : 0;
    benchmark::DoNotOptimize(g);
  }
  finish(state, i - static_cast<long>(sc.pairs.size()), touching);
}

BENCHMARK(BM_Narrow_FastCold)->DenseRange(0, 3);
BENCHMARK(BM_Narrow_FastWarm)->DenseRange(0, 3);
BENCHMARK(BM_Narrow_ClpCold)->DenseRange(0, 3);
BENCHMARK(BM_Narrow_ClpWarm)->DenseRange(0, 3);

}  // namespace
}  // namespace blockdem
