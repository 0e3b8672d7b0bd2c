// `blockdem reproduce` reports each case as it starts and ends when stderr is not a terminal (here
// a file): a "started" line before a "finished" line per case, counted [i/n], and the finished
// line's status and step count are those the case's own summary.json records.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "support/cli_runner.hpp"
#include "support/temp_path.hpp"

namespace blockdem {
namespace {

namespace fs = std::filesystem;

TEST(ReproduceProgress, ALineAsEachCaseStartsAndEnds) {
  const fs::path out = test::temp_path("reproduce_progress");
  fs::remove_all(out);
  const test::CommandOutput r = test::run_cli(
      "reproduce boon2015 --case T2-1 --mode boon2012 "
      "--no-figures --out '" +
      out.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto summary = nlohmann::json::parse(std::ifstream(out / "T2-1" / "summary.json"));
  const std::string steps = std::to_string(summary["steps"].get<long long>());
  const std::string status = summary["status"].get<std::string>();

  std::istringstream lines(r.err);
  int started = 0, finished = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("[1/1] T2-1", 0) != 0) continue;
    if (line.find(" started ") != std::string::npos) {
      EXPECT_EQ(finished, 0) << "finished before it started:\n" << r.err;
      ++started;
    }
    if (line.find(" finished ") != std::string::npos) {
      ++finished;
      EXPECT_NE(line.find(": " + status + ", " + steps + " steps in "), std::string::npos)
          << line << "\nsummary.json: " << status << ", " << steps << " steps";
    }
  }
  EXPECT_EQ(started, 1) << r.err;
  EXPECT_EQ(finished, 1) << r.err;
}

}  // namespace
}  // namespace blockdem
