// time_history.csv writer.
#include "blockdem/io/time_history.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>

#include "blockdem/numerics/units.hpp"

namespace blockdem {

TimeHistoryWriter::TimeHistoryWriter(const std::filesystem::path& path, const World& world,
                                     TimeHistoryOptions options, bool append)
    : options_(std::move(options)),
      interval_steps_(options_.interval_steps),
      interval_time_(options_.interval_time) {
  if (options_.max_rows < 2) throw std::invalid_argument("max_rows: must be at least 2");
  if (interval_time_ <= 0.0 && interval_steps_ <= 0)
    throw std::invalid_argument("interval: give a positive number of steps or seconds");
  std::vector<std::string> columns = {"time_s",
                                      "step",
                                      "stage",
                                      "time_step_s",
                                      "kinetic_energy_J",
                                      "elastic_energy_J",
                                      "gravity_work_J",
                                      "load_work_J",
                                      "boundary_work_J",
                                      "friction_dissipation_J",
                                      "damping_dissipation_J",
                                      "energy_residual_J",
                                      "energy_residual_ratio",
                                      "unbalanced_force_ratio",
                                      "kinetic_energy_ratio",
                                      "max_speed_m_s",
                                      "contacts",
                                      "sliding_contacts",
                                      "broken_bonds",
                                      "water_work_J",
                                      "seismic_work_J"};
  // With contact damping, its dissipation after the local damping's.
  dashpots_ = world.settings().contact_damping > 0.0;
  if (dashpots_) columns.insert(columns.begin() + 11, "contact_damping_J");
  for (const auto& name : options_.blocks) {
    const int i = world.find_block(name);
    if (i < 0) throw std::invalid_argument("history_blocks: no block named '" + name + "'");
    blocks_.push_back(i);
    for (const char* c :
         {"_ux_m", "_uy_m", "_uz_m", "_vx_m_s", "_vy_m_s", "_vz_m_s", "_rotation_deg"})
      columns.push_back(name + c);
  }
  for (const auto& name : options_.bolts) {
    columns.push_back(name + "_axial_force_N");
    columns.push_back(name + "_shear_force_N");
  }
  if (options_.base_motion) {
    for (const char* c : {"base_ax_m_s2", "base_ay_m_s2", "base_az_m_s2", "base_vx_m_s",
                          "base_vy_m_s", "base_vz_m_s", "base_ux_m", "base_uy_m", "base_uz_m"})
      columns.emplace_back(c);
  }
  next_coarsening_ = options_.max_rows / 2;
  csv_ = std::make_unique<CsvWriter>(path, std::move(columns), append);
}

void TimeHistoryWriter::save_state(StateWriter& w) const {
  w.pod(interval_steps_);
  w.pod(interval_time_);
  w.pod(rows_);
  w.pod(next_coarsening_);
  w.pod(last_step_);
  w.pod(next_time_);
}

void TimeHistoryWriter::load_state(StateReader& r) {
  r.pod(interval_steps_);
  r.pod(interval_time_);
  r.pod(rows_);
  r.pod(next_coarsening_);
  r.pod(last_step_);
  r.pod(next_time_);
  if (rows_ < 0 || rows_ > options_.max_rows || (interval_time_ <= 0.0 && interval_steps_ <= 0))
    throw StateError("saved time history state is corrupt");
}

void TimeHistoryWriter::coarsen() {
  if (rows_ < next_coarsening_) return;
  interval_steps_ *= 2;
  interval_time_ *= 2.0;
  next_coarsening_ += std::max<std::int64_t>(1, (options_.max_rows - next_coarsening_) / 2);
}

bool TimeHistoryWriter::due(const World& world) const {
  const std::int64_t level = world.step_count() - 1;
  return interval_time_ > 0.0 ? world.level_time() >= next_time_ : level % interval_steps_ == 0;
}

void TimeHistoryWriter::after_step(const World& world, const std::string& stage) {
  if (due(world)) write(world, stage);
}

void TimeHistoryWriter::write(const World& world, const std::string& stage) {
  const std::int64_t level = world.step_count() - 1;
  if (level < 0 || level == last_step_ || rows_ >= options_.max_rows) return;
  last_step_ = level;
  const double t = world.level_time();
  if (interval_time_ > 0.0) {
    while (next_time_ <= t) next_time_ += interval_time_;
  }
  // Everything below is at level n: the budget, the contacts and the blocks' level states.
  // A distributed world that is not whole gives each process its own blocks and contacts
  // exact: the counts and the largest speed are reduced exactly, the elastic energy's terms and
  // the chosen blocks' columns are merged to process 0 (which writes the file) in one process's
  // order, so the row is the same bytes without a whole-world refresh.
  const EnergyBudget& e = world.energy_budget();
  const auto contacts = world.counted_contacts();
  double normal_energy = 0.0;
  std::array<std::int64_t, 2> counts{static_cast<std::int64_t>(contacts.size()), 0};
  for (const Contact* c : contacts) counts[1] += c->sliding ? 1 : 0;
  std::array<double, 1> max_speed{0.0};
  for (const auto& b : world.blocks()) {
    if (b.is_dynamic() && world.counts_block(static_cast<std::size_t>(b.index)))
      max_speed[0] = std::max(max_speed[0], world.level_state(b.index).velocity.norm());
  }
  world.reduce_partials({}, max_speed, counts);
  world.merge_to_root(
      contacts.size(),
      [&](std::size_t k) {
        return (static_cast<std::uint64_t>(contacts[k]->a) << 32) |
               static_cast<std::uint32_t>(contacts[k]->b);
      },
      [&](std::size_t k, std::string& out) {
        const double term = 0.5 * contacts[k]->normal_force * contacts[k]->geometry.overlap;
        out.append(reinterpret_cast<const char*>(&term), sizeof term);
      },
      [&](std::string_view term) {
        double x = 0.0;
        std::memcpy(&x, term.data(), sizeof x);
        normal_energy += x;
      });
  // The chosen blocks' columns: u (3), v (3), the rotation from the initial orientation.
  constexpr std::size_t kColumns = 7;
  std::vector<std::size_t> mine;
  for (std::size_t j = 0; j < blocks_.size(); ++j) {
    if (world.counts_block(static_cast<std::size_t>(blocks_[j]))) mine.push_back(j);
  }
  std::vector<std::array<double, kColumns>> columns(blocks_.size());
  std::size_t merged = 0;
  world.merge_to_root(
      mine.size(), [&](std::size_t k) { return static_cast<std::uint64_t>(mine[k]); },
      [&](std::size_t k, std::string& out) {
        const int i = blocks_[mine[k]];
        const Block& b = world.blocks()[static_cast<std::size_t>(i)];
        const World::LevelState s = world.level_state(i);
        const Eigen::Vector3d u = s.position - b.initial_position;
        const double turn =
            Eigen::AngleAxisd(s.orientation * b.initial_orientation.conjugate()).angle();
        const std::array<double, kColumns> row{u.x(),
                                               u.y(),
                                               u.z(),
                                               s.velocity.x(),
                                               s.velocity.y(),
                                               s.velocity.z(),
                                               rad_to_deg(std::min(turn, 2 * kPi - turn))};
        out.append(reinterpret_cast<const char*>(row.data()), sizeof row);
      },
      [&](std::string_view row) {
        if (merged < columns.size()) std::memcpy(columns[merged].data(), row.data(), row.size());
        ++merged;
      });
  const double scale = e.scale();
  csv_->cell(t)
      .cell(static_cast<long long>(level))
      .cell(stage)
      .cell(world.last_time_step())
      .cell(e.kinetic)
      .cell(e.elastic)
      .cell(e.gravity_work)
      .cell(e.load_work)
      .cell(e.boundary_work)
      .cell(e.friction_dissipation)
      .cell(e.damping_dissipation);
  if (dashpots_) csv_->cell(e.contact_damping);
  csv_->cell(e.residual())
      .cell(scale > 0.0 ? e.residual() / scale : 0.0)
      .cell(world.equilibrium().unbalanced_force_ratio)
      .cell(normal_energy > 0.0 ? e.kinetic / normal_energy : 0.0)
      .cell(max_speed[0])
      .cell(static_cast<long long>(counts[0]))
      .cell(static_cast<long long>(counts[1]))
      .cell(static_cast<long long>(world.broken_bond_count()))
      .cell(e.water_work)
      .cell(e.seismic_work);
  for (const auto& row : columns) {
    for (const double x : row) csv_->cell(x);
  }
  // The chosen bolts' largest tendon force and dowel shear, found by name (a stage installs them).
  for (const auto& name : options_.bolts) {
    double axial = 0.0, shear = 0.0;
    for (const Bolt& b : world.bolts()) {
      if (b.spec.name != name || !b.active()) continue;
      axial = b.largest_axial_force(0.0, b.spec.length);
      for (const BoltCrossing& c : b.crossings) shear = std::max(shear, c.force.norm());
    }
    csv_->cell(axial).cell(shear);
  }
  if (options_.base_motion) {
    for (const Eigen::Vector3d* v : {&base_.acceleration, &base_.velocity, &base_.displacement})
      csv_->cell(v->x()).cell(v->y()).cell(v->z());
  }
  csv_->end_row();
  ++rows_;
  if (rows_ % 64 == 0) csv_->flush();
  coarsen();
}

}  // namespace blockdem
