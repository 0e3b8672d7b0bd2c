// Deterministic mutation fuzzing of `blockdem run`: 2,000 scenarios made from good ones by a
// fixed-seed generator (lines deleted, duplicated, swapped or cut; numbers replaced by extreme
// values; strings and keys replaced), each run for at most a few steps. Every run must end by
// itself with exit code 0, 2 or 3 (no signal, no crash, no other code), and a run that exits 2
// (an input error) must write nothing. Under a sanitizer (BLOCKDEM_TEST_SANITIZED=1), where each
// run costs a sanitized program's start, the first 500 of the same sequence.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli_runner.hpp"
#include "support/sanitized_run.hpp"
#include "support/temp_path.hpp"

namespace blockdem {
namespace {

namespace fs = std::filesystem;

const char* kStack = R"(title = "two blocks"
[settings]
damping = 0.7
rounding_distance = 2e-4
contact_mode = "boon2012"
[[materials]]
name = "rock"
density = 2600
[[joint_laws]]
name = "j"
normal = { law = "exponential", preset = "eq3" }
shear = { law = "continuously_yielding" }
[[blocks]]
name = "base"
material = "rock"
size = [1, 1, 0.2]
position = [0, 0, -0.1]
motion = "fixed"
[[blocks]]
name = "top"
material = "rock"
shape = "vertices"
vertices = [[0, 0, 0], [0.2, 0, 0], [0, 0.2, 0], [0.2, 0.2, 0], [0, 0, 0.2], [0.2, 0, 0.2], [0, 0.2, 0.2], [0.2, 0.2, 0.2]]
position = [-0.1, -0.1, 0]
velocity = [0.01, 0, 0]
[[blocks]]
name = "pusher"
material = "rock"
size = [0.1, 0.2, 0.2]
position = [0.3, 0, 0.1]
motion = "servo"
servo = { axis = [-1, 0, 0], target_force = 10 }
[[stages]]
name = "settle"
kind = "steps"
steps = 10
gravity = [0, 0, -9.81]
[[stages]]
name = "push"
kind = "steps"
steps = 5
servos = [{ block = "pusher", target_force = 20 }]
[output]
vtk = true
)";

const char* kBeam = R"([voussoir]
beam = "half"
blocks = 3
g_max = 5
ramp_steps = 3
max_steps_per_level = 10
normal = { law = "linear", stiffness = 10e9 }
shear = { law = "linear", stiffness = 1e9, friction_deg = 40 }
[settings]
contact_mode = "face_integrated"
)";

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

class Mutator {
 public:
  explicit Mutator(unsigned seed) : rng_(seed) {}

  std::string mutate(const std::string& text) {
    std::vector<std::string> lines = lines_of(text);
    const int edits = 1 + pick(3);
    for (int e = 0; e < edits && !lines.empty(); ++e) edit(lines);
    std::string out;
    for (const auto& l : lines) out += l + "\n";
    if (pick(20) == 0) out.resize(static_cast<std::size_t>(pick(static_cast<int>(out.size()) + 1)));
    return out;
  }

 private:
  int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }

  void edit(std::vector<std::string>& lines) {
    const std::size_t i = static_cast<std::size_t>(pick(static_cast<int>(lines.size())));
    switch (pick(6)) {
      case 0:
        lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(i));
        break;
      case 1:
        lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(i), lines[i]);
        break;
      case 2:
        std::swap(lines[i], lines[static_cast<std::size_t>(pick(static_cast<int>(lines.size())))]);
        break;
      case 3:
      case 4:
        lines[i] = replace_number(lines[i]);
        break;
      default:
        lines[i] = replace_word(lines[i]);
        break;
    }
  }

  std::string replace_number(const std::string& line) {
    static const std::vector<std::string> extremes = {"0",
                                                      "-1",
                                                      "1e308",
                                                      "-1e308",
                                                      "1e-308",
                                                      "nan",
                                                      "inf",
                                                      "-inf",
                                                      "9223372036854775807",
                                                      "-9223372036854775808",
                                                      "0.5",
                                                      "1e6",
                                                      "3",
                                                      "\"x\"",
                                                      "[]",
                                                      "[1, 2]",
                                                      "true"};
    static const std::regex number(R"([-+]?[0-9]+(\.[0-9]*)?([eE][-+]?[0-9]+)?)");
    std::vector<std::smatch> found;
    for (auto it = std::sregex_iterator(line.begin(), line.end(), number);
         it != std::sregex_iterator(); ++it)
      found.push_back(*it);
    if (found.empty()) return line;
    const std::smatch& m = found[static_cast<std::size_t>(pick(static_cast<int>(found.size())))];
    return line.substr(0, static_cast<std::size_t>(m.position())) +
           extremes[static_cast<std::size_t>(pick(static_cast<int>(extremes.size())))] +
           line.substr(static_cast<std::size_t>(m.position() + m.length()));
  }

  std::string replace_word(const std::string& line) {
    static const std::vector<std::string> words = {
        "name",  "law",        "kind",       "steps",    "fixed",  "free",
        "servo", "box",        "planes",     "vertices", "linear", "degrading",
        "\"\"",  "[[blocks]]", "[settings]", "=",        "{",      "]"};
    static const std::regex word(R"([A-Za-z_]+)");
    std::vector<std::smatch> found;
    for (auto it = std::sregex_iterator(line.begin(), line.end(), word);
         it != std::sregex_iterator(); ++it)
      found.push_back(*it);
    if (found.empty()) return line;
    const std::smatch& m = found[static_cast<std::size_t>(pick(static_cast<int>(found.size())))];
    return line.substr(0, static_cast<std::size_t>(m.position())) +
           words[static_cast<std::size_t>(pick(static_cast<int>(words.size())))] +
           line.substr(static_cast<std::size_t>(m.position() + m.length()));
  }

  std::mt19937 rng_;
};

TEST(MutationFuzz, MutatedScenariosEndWithADefinedExitCode) {
  const fs::path dir = test::temp_path("mutation_fuzz");
  fs::remove_all(dir);
  fs::create_directories(dir);
  {
    // The unmutated scenario runs to the end.
    std::ofstream(dir / "good.toml") << kStack;
    const test::CommandOutput r =
        test::run_cli("run '" + (dir / "good.toml").string() + "' --out '" +
                      (dir / "good").string() + "' --max-steps 20 --quiet --no-figures");
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  Mutator mutator(20261125);
  std::map<int, int> codes;
  const int scenarios = test::sanitized_run() ? 500 : 2000;
  for (int n = 0; n < scenarios; ++n) {
    const std::string text = mutator.mutate(n % 4 == 3 ? kBeam : kStack);
    const fs::path file = dir / "case.toml";
    const fs::path out = dir / ("out" + std::to_string(n));
    std::ofstream(file) << text;
    // With the threads' wait policy the program would choose itself (apps/cli/main.cpp): it
    // then runs without starting itself again, which halves the cost of a run that reads its
    // scenario and stops.
    const test::CommandOutput r =
        test::run_cli("run '" + file.string() + "' --out '" + out.string() +
                          "' --max-steps 20 --quiet --no-figures",
                      "OMP_WAIT_POLICY=passive ");
    ++codes[r.exit_code];
    const bool defined = r.exit_code == 0 || r.exit_code == 2 || r.exit_code == 3;
    EXPECT_TRUE(defined) << "scenario " << n << " exit " << r.exit_code << "\n"
                         << r.err << "\n--- scenario ---\n"
                         << text;
    if (r.exit_code == 2) {
      EXPECT_FALSE(fs::exists(out)) << "scenario " << n << ": input error but files written\n"
                                    << r.err << "\n--- scenario ---\n"
                                    << text;
    }
    fs::remove_all(out);
    if (::testing::Test::HasFailure()) break;  // one scenario is enough to reproduce
  }
  std::ostringstream summary;
  for (const auto& [code, count] : codes) summary << " exit " << code << ": " << count << ";";
  std::printf("mutation fuzz:%s\n", summary.str().c_str());
  // Both halves of the promise are exercised: some mutants run (more than 5 %), most are input
  // errors.
  EXPECT_GT(codes[0] + codes[3], scenarios / 20);
  EXPECT_GT(codes[2], scenarios / 20);
}

}  // namespace
}  // namespace blockdem
