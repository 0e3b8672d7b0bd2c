// time_history.csv: rows at the interval, every row at one time level, the size cap.
#include "blockdem/io/time_history.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "../../validation/scenes.hpp"
#include "support/temp_path.hpp"

namespace blockdem {
namespace {

using Table = std::vector<std::map<std::string, std::string>>;

Table read_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream hs(line);
  for (std::string cell; std::getline(hs, cell, ',');) header.push_back(cell);
  Table rows;
  while (std::getline(in, line)) {
    std::stringstream ls(line);
    std::map<std::string, std::string> row;
    std::size_t i = 0;
    for (std::string cell; std::getline(ls, cell, ',') && i < header.size(); ++i)
      row[header[i]] = cell;
    rows.push_back(row);
  }
  return rows;
}

double num(const std::map<std::string, std::string>& row, const std::string& key) {
  return std::stod(row.at(key));
}

// Free fall from rest (v_{-1/2} = 0) with Δt = 1e-3 s, a row every 10 steps. Central differences
// give, at level n (t_n = n Δt): z_n = z_0 − g t_n²/2 − g Δt t_n/2 and the centred velocity
// v_n = −g (t_n + Δt/2), exactly; the budget's gravity work is m g (z_0 − z_n) and its kinetic
// energy ½ m v_{n−1/2} v_{n+1/2} = ½ m g² (t_n² + Δt t_n), so the residual is round-off.
// Tolerance 1e-9 relative (the CSV's 12 significant digits).
TEST(TimeHistory, RowsAtTheIntervalDescribeOneTimeLevel) {
  const double g = 9.81, dt = 1e-3;
  WorldSettings s;
  s.gravity = {0, 0, -g};
  s.time_step = dt;
  World w = test::linear_world(1e10, 1e9, 40, s);
  w.add_block(test::box_block({0.1, 0.1, 0.1}, {0, 0, 10}, 1000.0, Motion::free, "stone"));
  const auto dir = test::temp_path("time_history_test");
  std::filesystem::create_directories(dir);
  {
    TimeHistoryWriter h(dir / "time_history.csv", w, {10, 0.0, 1000, {"stone"}, {}});
    for (int k = 0; k < 100; ++k) {
      w.step();
      h.after_step(w, "fall");
    }
    h.write(w, "fall");  // the stage end: level 99
    EXPECT_EQ(h.rows(), 11);
  }
  const Table rows = read_csv(dir / "time_history.csv");
  ASSERT_EQ(rows.size(), 11u);
  const double m = 1.0;  // 1000 kg/m^3 × 1e-3 m^3
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    const double n = i < 10 ? 10.0 * static_cast<double>(i) : 99.0;
    const double t = n * dt;
    EXPECT_NEAR(num(r, "step"), n, 0.0);
    EXPECT_NEAR(num(r, "time_s"), t, 1e-12);
    const double drop = 0.5 * g * t * t + 0.5 * g * dt * t;
    EXPECT_NEAR(-num(r, "stone_uz_m"), drop, 1e-9 * drop + 1e-15);
    EXPECT_NEAR(-num(r, "stone_vz_m_s"), g * (t + 0.5 * dt), 1e-9 * g * (t + dt));
    EXPECT_NEAR(num(r, "gravity_work_J"), m * g * drop, 1e-9 * m * g * drop + 1e-15);
    EXPECT_NEAR(num(r, "kinetic_energy_J"), 0.5 * m * g * g * (t * t + dt * t),
                1e-9 * m * g * g * (t * t + dt * t) + 1e-15);
    EXPECT_LT(std::abs(num(r, "energy_residual_J")), 1e-9 * m * g * drop + 1e-12);
  }
}

// The cap: with max_rows = 8 and a row every step, the interval doubles when half the rows still
// allowed are used (after 4, 6, 7 rows) and the file stops at 8 rows.
TEST(TimeHistory, NeverExceedsMaxRowsAndCoarsens) {
  WorldSettings s;
  s.time_step = 1e-3;
  World w = test::linear_world(1e10, 1e9, 40, s);
  w.add_block(test::box_block({0.1, 0.1, 0.1}, {0, 0, 0}, 1000.0));
  const auto path = test::temp_path("time_history_cap.csv");
  TimeHistoryWriter h(path, w, {1, 0.0, 8, {}, {}});
  for (int k = 0; k < 200; ++k) {
    w.step();
    h.after_step(w, "s");
  }
  EXPECT_EQ(h.rows(), 8);
  EXPECT_EQ(h.interval_steps(), 16);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace blockdem
