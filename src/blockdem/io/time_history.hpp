// time_history.csv: the state of a run within its stages, one row every so many steps or seconds
// of model time, every row at one time level (World::level_state), with the energy budget.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "blockdem/dynamics/base_motion.hpp"
#include "blockdem/io/csv.hpp"
#include "blockdem/world/state_stream.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

struct TimeHistoryOptions {
  std::int64_t interval_steps = 100;  ///< a row every this many steps (0: use interval_time)
  double interval_time = 0.0;         ///< or every this much model time (s), when > 0
  /// The file never exceeds this many rows: each time half of the rows still allowed are used,
  /// the interval doubles (about interval × max_rows × log2(max_rows) / 2 steps are covered).
  std::int64_t max_rows = 20000;
  std::vector<std::string> blocks;  ///< blocks whose displacement and velocity get columns
  /// Bolts whose largest tendon force and largest dowel shear get columns (N; 0 before the
  /// stage that installs them and after they rupture). One process only (bolts are).
  std::vector<std::string> bolts;
  /// Columns of a dynamic stage's base motion (base_ax_m_s2 ... base_uz_m: the history's
  /// acceleration, velocity and displacement at the row's time, set by set_base; zero outside
  /// a dynamic stage). Only when a stage moves a base: other runs' files keep their columns.
  bool base_motion = false;
};

class TimeHistoryWriter {
 public:
  /// Creates `path` and writes the header. Throws std::invalid_argument for a block name the
  /// world does not have, std::runtime_error when the file cannot be written. With `append`, the
  /// file holds the rows of a run being restarted; load_state() then continues it.
  TimeHistoryWriter(const std::filesystem::path& path, const World& world,
                    TimeHistoryOptions options, bool append = false);

  /// Called after every step: writes a row when the interval has passed.
  void after_step(const World& world, const std::string& stage);
  /// Whether after_step writes a row now (it reads only the world's time and step counters).
  bool due(const World& world) const;
  /// Writes a row at the world's current level unless one was just written (a stage end).
  void write(const World& world, const std::string& stage);

  std::int64_t rows() const { return rows_; }
  std::int64_t interval_steps() const { return interval_steps_; }
  double interval_time() const { return interval_time_; }

  /// The base motion's kinematics at the next row's time (TimeHistoryOptions::base_motion).
  void set_base(const BaseKinematics& k) { base_ = k; }

  /// Writes the buffered rows to the file.
  void flush() { csv_->flush(); }
  /// Where the file stands (rows, interval, next coarsening, last row, next time), for a restart.
  void save_state(StateWriter& w) const;
  /// Throws StateError for bytes that are not a writer's state.
  void load_state(StateReader& r);

 private:
  void coarsen();
  TimeHistoryOptions options_;
  std::unique_ptr<CsvWriter> csv_;
  std::vector<int> blocks_;
  std::int64_t interval_steps_ = 0;
  double interval_time_ = 0.0;
  std::int64_t rows_ = 0;
  std::int64_t next_coarsening_ = 0;  ///< rows at which the interval doubles next
  std::int64_t last_step_ = -1;       ///< level step of the last row
  double next_time_ = 0.0;            ///< model time of the next row (s)
  BaseKinematics base_;               ///< the base columns' values
  bool dashpots_ = false;  ///< the contact_damping_J column (the world has contact damping)
};

}  // namespace blockdem
