// Run outputs: CSV columns carry their unit in the name.
#include "blockdem/io/run_recorder.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "blockdem/io/output_error.hpp"
#include "blockdem/numerics/units.hpp"

namespace blockdem {

RunRecorder::RunRecorder(const std::filesystem::path& dir, bool vtk, bool tables, bool append,
                         std::filesystem::path pieces)
    : dir_(dir), pieces_(pieces.empty() ? dir / "vtk" : std::move(pieces)), vtk_(vtk) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec) throw OutputError("cannot create output folder " + dir_.string() + ": " + ec.message());
  if (vtk_) {
    std::filesystem::create_directories(dir_ / "vtk", ec);
    blocks_pvd_ = std::make_unique<PvdCollection>(dir_ / "vtk" / "blocks.pvd");
    contacts_pvd_ = std::make_unique<PvdCollection>(dir_ / "vtk" / "contacts.pvd");
  }
  if (tables) {
    history_ = std::make_unique<CsvWriter>(
        dir_ / "history.csv",
        std::vector<std::string>{"level", "stage", "converged", "steps", "time_s", "time_step_s",
                                 "gravity_x_m_s2", "gravity_y_m_s2", "gravity_z_m_s2", "g_level",
                                 "unbalanced_force_ratio", "kinetic_energy_J",
                                 "kinetic_energy_ratio", "contacts", "mean_contact_force_N",
                                 "max_overlap_mm", "water_force_N"},
        append);
    blocks_ = std::make_unique<CsvWriter>(dir_ / "blocks.csv",
                                          std::vector<std::string>{"level",
                                                                   "stage",
                                                                   "block",
                                                                   "group",
                                                                   "x_m",
                                                                   "y_m",
                                                                   "z_m",
                                                                   "ux_mm",
                                                                   "uy_mm",
                                                                   "uz_mm",
                                                                   "rotation_deg",
                                                                   "rotation_x_deg",
                                                                   "rotation_y_deg",
                                                                   "rotation_z_deg",
                                                                   "vx_m_s",
                                                                   "vy_m_s",
                                                                   "vz_m_s",
                                                                   "contact_fx_N",
                                                                   "contact_fy_N",
                                                                   "contact_fz_N",
                                                                   "water_fx_N",
                                                                   "water_fy_N",
                                                                   "water_fz_N"},
                                          append);
  }
  contacts_ = std::make_unique<CsvWriter>(dir_ / "contacts.csv",
                                          std::vector<std::string>{"level",
                                                                   "stage",
                                                                   "block_a",
                                                                   "block_b",
                                                                   "x_m",
                                                                   "y_m",
                                                                   "z_m",
                                                                   "nx",
                                                                   "ny",
                                                                   "nz",
                                                                   "overlap_mm",
                                                                   "area_mm2",
                                                                   "normal_stress_MPa",
                                                                   "normal_force_N",
                                                                   "shear_force_N",
                                                                   "shear_x_N",
                                                                   "shear_y_N",
                                                                   "shear_z_N",
                                                                   "plastic_slip_mm",
                                                                   "sliding",
                                                                   "integrated",
                                                                   "force_point_x_m",
                                                                   "force_point_y_m",
                                                                   "force_point_z_m",
                                                                   "compressed_area_mm2",
                                                                   "peak_stress_MPa",
                                                                   "peak_closure_mm"},
                                          append);
}

namespace {

// The columns of blocks.csv and contacts.csv (the headers in RunRecorder's constructor).
constexpr std::size_t kBlockColumns = 23;
constexpr std::size_t kContactColumns = 27;

// One row of blocks.csv: block b at the world's level state, with the contact force on it (N).
void block_row(CsvWriter& csv, const World& world, const Block& b, int level,
               const std::string& stage, const Eigen::Vector3d& contact_force) {
  const Eigen::Vector3d& origin = world.settings().origin;  // positions out in user coordinates
  // One instant per row: the level state at which the contact forces were evaluated.
  const World::LevelState st = world.level_state(b.index);
  const Eigen::Vector3d u = 1e3 * (st.position - b.initial_position);
  const Eigen::AngleAxisd turn(st.orientation * b.initial_orientation.conjugate());
  const double angle = turn.angle() > kPi ? turn.angle() - 2 * kPi : turn.angle();
  const Eigen::Vector3d r = rad_to_deg(angle) * turn.axis();
  csv.cell(level)
      .cell(stage)
      .cell(b.name)
      .cell(b.group())
      .cell(st.position.x() + origin.x())
      .cell(st.position.y() + origin.y())
      .cell(st.position.z() + origin.z())
      .cell(u.x())
      .cell(u.y())
      .cell(u.z())
      .cell(r.norm())
      .cell(r.x())
      .cell(r.y())
      .cell(r.z())
      .cell(st.velocity.x())
      .cell(st.velocity.y())
      .cell(st.velocity.z())
      .cell(contact_force.x())
      .cell(contact_force.y())
      .cell(contact_force.z())
      .cell(b.water_force().x())
      .cell(b.water_force().y())
      .cell(b.water_force().z());
  csv.end_row();
}

// One row of contacts.csv.
void contact_row(CsvWriter& csv, const World& world, const Contact& c, int level,
                 const std::string& stage) {
  const Eigen::Vector3d& origin = world.settings().origin;
  const auto& gm = c.geometry;
  csv.cell(level)
      .cell(stage)
      .cell(world.blocks()[c.a].name)
      .cell(world.blocks()[c.b].name)
      .cell(gm.point.x() + origin.x())
      .cell(gm.point.y() + origin.y())
      .cell(gm.point.z() + origin.z())
      .cell(gm.normal.x())
      .cell(gm.normal.y())
      .cell(gm.normal.z())
      .cell(1e3 * gm.overlap)
      .cell(1e6 * gm.area)
      .cell(1e-6 * c.normal_stress)
      .cell(c.normal_force)
      .cell(c.shear.force.norm())
      .cell(c.shear.force.x())
      .cell(c.shear.force.y())
      .cell(c.shear.force.z())
      .cell(1e3 * c.shear.plastic_slip)
      .cell(c.sliding ? 1 : 0)
      .cell(c.integrated ? 1 : 0)
      .cell(c.force_point().x() + origin.x())
      .cell(c.force_point().y() + origin.y())
      .cell(c.force_point().z() + origin.z())
      .cell(1e6 * c.compressed_area())
      .cell(1e-6 * c.peak_stress())
      .cell(1e3 * c.peak_closure());
  csv.end_row();
}

std::uint64_t pair_key(const Contact& c) {
  return (static_cast<std::uint64_t>(c.a) << 32) | static_cast<std::uint32_t>(c.b);
}

}  // namespace

void RunRecorder::record(const World& world, const StageResult& stage, int level) {
  // A distributed world that is not whole: each process its own blocks and the contacts it
  // owns, exact; the counts and the largest overlap reduced exactly, and the rows merged to
  // process 0 (which writes the files) in one process's order, by block index and by (a, b)
  // (World::merge_to_root). The files are the same bytes as one process's, and no process
  // holds the whole world.
  const auto contacts = world.counted_contacts();
  std::array<double, 1> max_overlap{0.0};
  for (const Contact* c : contacts) max_overlap[0] = std::max(max_overlap[0], c->geometry.overlap);
  std::array<std::int64_t, 1> contact_count{static_cast<std::int64_t>(contacts.size())};
  world.reduce_partials({}, max_overlap, contact_count);
  const Eigen::Vector3d& g = world.settings().gravity;
  const bool whole = world.replica_complete();
  const Eigen::Vector3d water = world.total_water_force();  // collective
  if (history_) {
    history_->cell(level)
        .cell(stage.name)
        .cell(stage.converged ? 1 : 0)
        .cell(static_cast<long long>(stage.steps))
        .cell(world.level_time())
        .cell(world.last_time_step())
        .cell(g.x())
        .cell(g.y())
        .cell(g.z())
        .cell(g.norm() / kOneG)
        .cell(stage.measures.unbalanced_force_ratio)
        .cell(stage.measures.kinetic_energy)
        .cell(stage.measures.kinetic_energy_ratio)
        .cell(static_cast<long long>(contact_count[0]))
        .cell(stage.measures.mean_contact_force)
        .cell(1e3 * max_overlap[0])
        .cell(water.norm());
    history_->end_row();
    history_->flush();

    if (whole) {
      for (const auto& b : world.blocks())
        block_row(*blocks_, world, b, level, stage.name, b.contact_force);
    } else {
      const auto resting = world.resting_contact_forces();
      std::vector<const Block*> mine;
      for (const auto& b : world.blocks()) {
        if (world.counts_block(static_cast<std::size_t>(b.index))) mine.push_back(&b);
      }
      CsvWriter rows(kBlockColumns);
      world.merge_to_root(
          mine.size(), [&](std::size_t k) { return static_cast<std::uint64_t>(mine[k]->index); },
          [&](std::size_t k, std::string& text) {
            const Block& b = *mine[k];
            const auto it = std::lower_bound(
                resting.begin(), resting.end(), b.index,
                [](const std::pair<int, Eigen::Vector3d>& x, int i) { return x.first < i; });
            const bool rests = it != resting.end() && it->first == b.index;
            block_row(rows, world, b, level, stage.name, rests ? it->second : b.contact_force);
            text += rows.take();
          },
          [&](std::string_view text) { blocks_->raw(text); });
    }
    blocks_->flush();
  }

  if (whole) {
    for (const Contact* c : contacts) contact_row(*contacts_, world, *c, level, stage.name);
  } else {
    CsvWriter rows(kContactColumns);
    world.merge_to_root(
        contacts.size(), [&](std::size_t k) { return pair_key(*contacts[k]); },
        [&](std::size_t k, std::string& text) {
          contact_row(rows, world, *contacts[k], level, stage.name);
          text += rows.take();
        },
        [&](std::string_view text) { contacts_->raw(text); });
  }
  contacts_->flush();

  write_frame(world, level);
}

void RunRecorder::write_frame(const World& world, int level) {
  if (!vtk_ || world.step_count() == last_frame_step_) return;
  last_frame_step_ = world.step_count();
  const auto& distribution = world.settings().distribution;
  const int processes = distribution ? distribution->size() : 1;
  char name[64];
  if (processes <= 1) {
    std::snprintf(name, sizeof name, "blocks_%06d.vtu", frames_);
    write_vtu_blocks(dir_ / "vtk" / name, world, level);
    blocks_pvd_->add(world.level_time(), name);
    std::snprintf(name, sizeof name, "contacts_%06d.vtu", frames_);
    write_vtu_contacts(dir_ / "vtk" / name, world);
    contacts_pvd_->add(world.level_time(), name);
    ++frames_;
    return;
  }
  // Each process its piece, of the blocks and pairs it owns.
  const int rank = distribution->rank();
  std::error_code ec;
  std::filesystem::create_directories(pieces_, ec);  // as process 0 made it (a shared folder)
  std::snprintf(name, sizeof name, "blocks_%06d_p%d.vtu", frames_, rank);
  const auto blocks = write_vtu_block_piece(pieces_ / name, world, level, rank);
  std::snprintf(name, sizeof name, "contacts_%06d_p%d.vtu", frames_, rank);
  const auto contacts = write_vtu_contact_piece(pieces_ / name, world, rank);
  // One integer sum over the processes: every piece is in place (renamed) before process 0
  // writes the index that names it, and every block is in exactly one piece.
  const std::vector<std::int64_t> total =
      distribution->sum({static_cast<std::int64_t>(blocks), static_cast<std::int64_t>(contacts)});
  if (total[0] != static_cast<std::int64_t>(world.blocks().size()))
    throw std::logic_error("VTK pieces hold " + std::to_string(total[0]) + " of " +
                           std::to_string(world.blocks().size()) + " blocks");
  for (const char* kind : {"blocks", "contacts"}) {
    std::vector<std::string> pieces;
    for (int k = 0; k < processes; ++k) {
      std::snprintf(name, sizeof name, "%s_%06d_p%d.vtu", kind, frames_, k);
      pieces.emplace_back(name);
    }
    std::snprintf(name, sizeof name, "%s_%06d.pvtu", kind, frames_);
    const bool is_blocks = kind[0] == 'b';
    PvdCollection& pvd = is_blocks ? *blocks_pvd_ : *contacts_pvd_;
    if (rank == 0) {
      if (is_blocks)
        write_pvtu_blocks(dir_ / "vtk" / name, world, pieces);
      else
        write_pvtu_contacts(dir_ / "vtk" / name, world, pieces);
      pvd.add(world.level_time(), name);
    } else {
      pvd.remember(world.level_time(), name);  // the same list, written by process 0
    }
  }
  ++frames_;
}

void RunRecorder::save_state(StateWriter& w) const {
  w.pod(static_cast<std::int32_t>(frames_));
  w.pod(last_frame_step_);
  for (const PvdCollection* pvd : {blocks_pvd_.get(), contacts_pvd_.get()}) {
    const std::size_t n = pvd ? pvd->frames().size() : 0;
    w.size(n);
    for (std::size_t i = 0; i < n; ++i) {
      w.pod(pvd->frames()[i].first);
      w.str(pvd->frames()[i].second);
    }
  }
}

void RunRecorder::load_state(StateReader& r) {
  frames_ = r.pod<std::int32_t>();
  r.pod(last_frame_step_);
  for (PvdCollection* pvd : {blocks_pvd_.get(), contacts_pvd_.get()}) {
    std::vector<std::pair<double, std::string>> frames(r.size());
    for (auto& [t, file] : frames) {
      r.pod(t);
      file = r.str();
    }
    if (frames_ < 0 || frames.size() > static_cast<std::size_t>(frames_) ||
        (!pvd && !frames.empty()))
      throw StateError("saved VTK frame list is corrupt");
    if (pvd) pvd->set_frames(std::move(frames));
  }
}

}  // namespace blockdem
