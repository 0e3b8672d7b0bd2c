// Determinism of the parallel step: a brick pile of some hundreds of blocks that slides and
// shakes gives bit-identical states, loads and contacts with 1, 2 and 3 threads (the serial run
// is the oracle), in the library and through `blockdem run --threads N`, and with 20 bolts
// solved side by side.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "brick_pile.hpp"
#include "support/sanitized_run.hpp"
#include "support/temp_path.hpp"

// A namespace of this file's own: the unity build (cmake/build_speed.cmake) compiles it together
// with other test files that define helpers of the same names.
namespace blockdem::test::parallel_determinism_test {
namespace {

/// Appends the bytes of doubles to a record; comparing records compares every bit.
struct Bytes {
  std::vector<unsigned char> data;
  void add(const double* p, std::size_t n) {
    const auto* c = reinterpret_cast<const unsigned char*>(p);
    data.insert(data.end(), c, c + n * sizeof(double));
  }
  void add(double v) { add(&v, 1); }
  void add(const Eigen::Vector3d& v) { add(v.data(), 3); }
};

struct PileRun {
  std::vector<Bytes> steps;  ///< one record per step: every block and contact
  std::size_t sliding = 0;   ///< sliding contacts summed over the steps
  std::size_t min_contacts = 1u << 30, max_contacts = 0;
};

PileRun run_pile(int threads, ContactMode mode, int steps) {
  WorldSettings s;
  s.gravity = Eigen::Vector3d(60.0, 25.0, -98.1);  // tilted 10 g: the pile slides on its base
  s.contact_mode = mode;
  s.threads = threads;
  const BrickPile pile;
  World w = pile.world(s, 20.0);
  EXPECT_EQ(w.thread_count(), threads);
  PileRun r;
  for (int k = 0; k < steps; ++k) {
    w.step();
    Bytes rec;
    rec.add(w.time());
    for (const Block& b : w.blocks()) {
      rec.add(b.position);
      rec.add(b.velocity);
      rec.add(b.angular_velocity);
      rec.add(b.angular_momentum);
      rec.add(b.orientation.coeffs().data(), 4);
      rec.add(b.force);
      rec.add(b.torque);
      rec.add(b.contact_force);
    }
    const auto contacts = w.contacts();
    for (const Contact* c : contacts) {
      rec.add(static_cast<double>(c->a));
      rec.add(static_cast<double>(c->b));
      rec.add(c->geometry.point);
      rec.add(c->geometry.normal);
      rec.add(c->geometry.overlap);
      rec.add(c->geometry.area);
      rec.add(c->normal_force);
      rec.add(c->force_point());
      rec.add(c->shear.force);
      rec.add(c->shear.elastic_displacement);
      rec.add(c->shear.plastic_slip);
      rec.add(c->sliding ? 1.0 : 0.0);
      r.sliding += c->sliding ? 1 : 0;
    }
    r.min_contacts = std::min(r.min_contacts, contacts.size());
    r.max_contacts = std::max(r.max_contacts, contacts.size());
    const EquilibriumMeasures m = w.equilibrium();
    rec.add(m.unbalanced_force_ratio);
    rec.add(m.kinetic_energy);
    rec.add(m.kinetic_energy_ratio);
    rec.add(w.next_time_step());
    r.steps.push_back(std::move(rec));
  }
  return r;
}

void expect_identical(const PileRun& serial, const PileRun& parallel, int threads) {
  ASSERT_EQ(serial.steps.size(), parallel.steps.size());
  for (std::size_t k = 0; k < serial.steps.size(); ++k) {
    ASSERT_TRUE(serial.steps[k].data == parallel.steps[k].data)
        << threads << " threads: first difference at step " << k + 1;
  }
}

class ParallelStep : public ::testing::TestWithParam<ContactMode> {};

// Oracle: the serial run. Tolerance: none (every bit). The scene is not trivial: hundreds of
// contacts that form and break, and sliding ones. Under a sanitizer a quarter of the steps,
// which still holds all of these (ThreadSanitizer looks for races in every step alike).
TEST_P(ParallelStep, BitIdenticalForOneTwoAndThreeThreads) {
  const int steps = (GetParam() == ContactMode::boon2012 ? 200 : 80) / (sanitized_run() ? 4 : 1);
  const PileRun one = run_pile(1, GetParam(), steps);
  EXPECT_GT(BrickPile{}.block_count(), 300);
  EXPECT_GT(one.min_contacts, 300u) << "the pile must be in contact";
  EXPECT_NE(one.min_contacts, one.max_contacts) << "contacts must form or break";
  EXPECT_GT(one.sliding, 0u) << "some contacts must slide";
  for (int threads : {2, 3}) expect_identical(one, run_pile(threads, GetParam(), steps), threads);
}

INSTANTIATE_TEST_SUITE_P(BothModes, ParallelStep,
                         ::testing::Values(ContactMode::boon2012, ContactMode::face_integrated),
                         [](const auto& p) { return std::string(to_string(p.param)); });

// Bolts solved side by side (World::apply_bolts: 16 bolts or more on several threads, their loads
// added in bolt order afterwards): the pile above, shaken by the same tilted gravity, with 20
// grouted bolts with dowels down through its columns into the base, gives the same bits with 1
// and 3 threads: every block's state and loads and every bolt's tendon and dowel forces, at every
// step. Oracle: the serial run; tolerance: none. Under a sanitizer a quarter of the steps.
TEST(ParallelBolts, BitIdenticalForOneAndThreeThreads) {
  const int steps = sanitized_run() ? 25 : 100;
  const auto run = [&](int threads) {
    WorldSettings s;
    s.gravity = Eigen::Vector3d(60.0, 25.0, -98.1);
    s.contact_mode = ContactMode::boon2012;
    s.threads = threads;
    const BrickPile pile;
    World w = pile.world(s, 20.0);
    // The pile's top face, from its four layers of cubes pressed together by `preclose` each.
    const double top = pile.layers * (pile.size - pile.preclose);
    for (int k = 0; k < 20; ++k) {
      BoltSpec b;
      b.name = "b";
      b.name += std::to_string(k);  // (not "b" + ...: GCC 12 warns of a bound it makes up)
      // Inside a cube of every layer (0.2 of a cube from the odd layers' faces), 1 mm below the
      // top, down to the middle of the base.
      b.start = Eigen::Vector3d((k % 5 + 1.3) * pile.size, (k / 5 + 1.3) * pile.size, top - 1e-3);
      b.direction = -Eigen::Vector3d::UnitZ();
      b.length = top - 1e-3 + 0.5 * pile.size;
      b.axial_stiffness = 1e6;
      b.bond_stiffness = 1e7;
      b.shear_stiffness = 1e5;
      w.install_bolt(b);
    }
    std::vector<Bytes> record;
    for (int k = 0; k < steps; ++k) {
      w.step();
      Bytes rec;
      for (const Block& b : w.blocks()) {
        rec.add(b.position);
        rec.add(b.velocity);
        rec.add(b.angular_velocity);
        rec.add(b.force);
        rec.add(b.torque);
      }
      for (const Bolt& b : w.bolts()) {
        for (const Tendon::Element& e : b.tendon.elements) rec.add(e.force);
        for (const BoltCrossing& c : b.crossings) rec.add(c.force);
      }
      record.push_back(std::move(rec));
    }
    double largest = 0.0;
    for (const Bolt& b : w.bolts()) {
      largest = std::max(largest, std::abs(b.largest_axial_force(0.0, 1.0)));
      for (const BoltCrossing& c : b.crossings) largest = std::max(largest, c.force.norm());
    }
    EXPECT_EQ(w.bolt_count(Bolt::State::intact) + w.bolt_count(Bolt::State::yielded), 20);
    return std::make_pair(record, largest);
  };
  const auto [one, largest] = run(1);
  EXPECT_GT(largest, 0.0) << "the bolts must carry load (tendon or dowel)";
  const auto [three, largest3] = run(3);
  ASSERT_EQ(one.size(), three.size());
  for (std::size_t k = 0; k < one.size(); ++k) {
    ASSERT_TRUE(one[k].data == three[k].data) << "step " << k + 1 << " differs with 3 threads";
  }
  EXPECT_EQ(largest, largest3);
}

std::string read_file(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

/// summary.json without the lines that may differ between runs: wall time and thread count.
std::string summary_without_timing(const std::filesystem::path& p) {
  std::istringstream in(read_file(p));
  std::string line, out;
  while (std::getline(in, line)) {
    if (line.find("\"wall_time_s\"") != std::string::npos) continue;
    if (line.find("\"threads\"") != std::string::npos) continue;
    out += line + "\n";
  }
  return out;
}

// The CLI: every output file of `blockdem run --threads N` is byte-identical for N = 1, 2, 3,
// except summary.json's wall time and thread count; summary.json records the thread count.
// Under a sanitizer two stages of 25 steps instead of 100, as ParallelStep above: the same files
// are written and compared (its length is breadth; 73 s under AddressSanitizer at 100 steps).
TEST(ParallelStepCli, RunOutputsByteIdenticalForOneTwoAndThreeThreads) {
  const auto dir = temp_path("parallel_cli");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto scenario = dir / "pile.toml";
  {
    std::ofstream f(scenario);
    f << BrickPile{}.toml("boon2012", 20.0, Eigen::Vector3d(60.0, 25.0, -98.1),
                          sanitized_run() ? 25 : 100);
  }
  std::vector<std::filesystem::path> outs;
  for (int threads : {1, 2, 3}) {
    std::string leaf = "out";
    leaf += std::to_string(threads);
    const auto out = dir / leaf;
    std::ostringstream cmd;
    cmd << BLOCKDEM_CLI_PATH << " run " << scenario.string() << " --out " << out.string()
        << " --quiet --no-figures --threads " << threads;
    ASSERT_EQ(std::system(cmd.str().c_str()), 0) << cmd.str();
    std::ostringstream key;
    key << "\"threads\": " << threads;
    EXPECT_NE(read_file(out / "summary.json").find(key.str()), std::string::npos);
    outs.push_back(out);
  }
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(outs[0])) {
    if (!entry.is_regular_file()) continue;
    const auto rel = std::filesystem::relative(entry.path(), outs[0]);
    for (std::size_t t = 1; t < outs.size(); ++t) {
      ASSERT_TRUE(std::filesystem::exists(outs[t] / rel)) << rel;
      if (rel == "summary.json") {
        EXPECT_EQ(summary_without_timing(entry.path()), summary_without_timing(outs[t] / rel));
      } else {
        EXPECT_TRUE(read_file(entry.path()) == read_file(outs[t] / rel))
            << rel << " differs with " << t + 1 << " threads";
      }
    }
    ++files;
  }
  EXPECT_GE(files, 5u);  // history, blocks, contacts, summary, vtk files
}

}  // namespace
}  // namespace blockdem::test::parallel_determinism_test
