// Voussoir outputs.
#include "blockdem/voussoir/recorder.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <type_traits>

#include "blockdem/numerics/units.hpp"
#include "blockdem/world/state_fields.hpp"

namespace blockdem {

VoussoirRecorder::VoussoirRecorder(const std::filesystem::path& dir, VoussoirSpec spec,
                                   VoussoirLayout layout, bool resumed)
    : spec_(std::move(spec)), layout_(std::move(layout)) {
  history_ = std::make_unique<CsvWriter>(
      dir / "history.csv",
      std::vector<std::string>{
          "level", "stage", "converged", "steps", "g_level", "thrust_N", "thrust_other_abutment_N",
          "midspan_deflection_mm", "abutment_slip_mm", "max_normal_stress_MPa",
          "equilibrium_residual", "lever_arm_mm", "beam_weight_N", "parabola_rms_mm",
          "parabola_thrust_N", "catenary_rms_mm", "catenary_thrust_N", "time_s"},
      resumed);
  blocks_ = std::make_unique<CsvWriter>(
      dir / "blocks.csv",
      std::vector<std::string>{"level", "g_level", "block", "x_m", "z_m", "ux_mm", "uz_mm",
                               "deflection_mm", "rotation_deg"},
      resumed);
  joints_ = std::make_unique<CsvWriter>(
      dir / "joints.csv",
      std::vector<std::string>{"level", "g_level", "joint", "left_block", "right_block",
                               "in_contact", "x_mm", "z_mm", "normal_force_N", "horizontal_force_N",
                               "shear_force_N", "normal_stress_MPa", "peak_stress_MPa",
                               "closure_mm", "area_mm2", "compressed_depth_mm", "plastic_slip_mm",
                               "sliding"},
      resumed);
}

void VoussoirRecorder::record(const World& world, const VoussoirLevel& lv, const std::string& stage,
                              bool converged, std::int64_t steps, int index) {
  const auto& blocks = world.blocks();
  const double nan = std::nan("");
  const bool fit = lv.fit.has_value();
  history_->cell(index)
      .cell(stage)
      .cell(converged ? 1 : 0)
      .cell(static_cast<long long>(steps))
      .cell(lv.g_level)
      .cell(lv.thrust)
      .cell(lv.thrust_left)
      .cell(1e3 * lv.midspan_deflection)
      .cell(1e3 * lv.abutment_slip)
      .cell(1e-6 * lv.max_normal_stress)
      .cell(lv.equilibrium_residual)
      .cell(1e3 * lv.lever_arm)
      .cell(lv.beam_weight)
      .cell(fit ? 1e3 * lv.fit->parabola.rms_residual : nan)
      .cell(fit ? lv.fit->parabola_thrust : nan)
      .cell(fit ? 1e3 * lv.fit->catenary.rms_residual : nan)
      .cell(fit ? lv.fit->catenary_thrust : nan)
      .cell(world.time());
  history_->end_row();
  history_->flush();
  for (const auto& b : lv.blocks) {
    const Block& bl = blocks[b.index];
    blocks_->cell(index)
        .cell(lv.g_level)
        .cell(bl.name)
        .cell(bl.position.x())
        .cell(bl.position.z())
        .cell(1e3 * b.ux)
        .cell(1e3 * b.uz)
        .cell(1e3 * b.deflection)
        .cell(rad_to_deg(b.rotation));
    blocks_->end_row();
  }
  blocks_->flush();
  for (std::size_t k = 0; k < lv.joints.size(); ++k) {
    const auto& j = lv.joints[k];
    joints_->cell(index)
        .cell(lv.g_level)
        .cell(static_cast<int>(k))
        .cell(blocks[j.left].name)
        .cell(blocks[j.right].name)
        .cell(j.in_contact ? 1 : 0)
        .cell(1e3 * j.x)
        .cell(1e3 * j.z)
        .cell(j.normal_force)
        .cell(j.horizontal_force)
        .cell(j.shear_force)
        .cell(1e-6 * j.normal_stress)
        .cell(1e-6 * j.peak_stress)
        .cell(1e3 * j.closure)
        .cell(1e6 * j.area)
        .cell(1e3 * j.compressed_depth)
        .cell(1e3 * j.plastic_slip)
        .cell(j.sliding ? 1 : 0);
    joints_->end_row();
  }
  joints_->flush();
  levels_.push_back(lv);
}

void VoussoirRecorder::on_stage_end(const World& world, const StageEnd& end) {
  if (end.diverged) return;
  const double g_level = world.settings().gravity.norm() / kOneG;
  if (end.level == 0) reference_ = capture_reference(world);
  const VoussoirLevel lv = measure_voussoir(world, spec_, layout_, reference_, g_level);
  record(world, lv, end.stage.name, end.result.converged, end.result.steps, end.level);
  if (end.result.converged) stable_.push_back(lv);
}

void VoussoirRecorder::on_run_end() {
  history_.reset();
  blocks_.reset();
  joints_.reset();
}

namespace {

using namespace state_fields;

// A flag of the recorder's state (state_fields::flag, its error naming the levels).
template <class Stream>
void flag(Stream& s, bool& value) {
  state_fields::flag(s, value, "saved voussoir levels");
}

template <class Stream>
void level_fields(Stream& s, VoussoirLevel& lv) {
  for (double* v :
       {&lv.g_level, &lv.thrust, &lv.thrust_left, &lv.midspan_deflection, &lv.abutment_slip,
        &lv.max_normal_stress, &lv.beam_weight, &lv.equilibrium_residual, &lv.lever_arm})
    field(s, *v);
  list(s, lv.joints, [](Stream& st, VoussoirJoint& j) {
    field(st, j.left);
    field(st, j.right);
    flag(st, j.in_contact);
    for (double* v :
         {&j.x, &j.z, &j.normal_force, &j.horizontal_force, &j.shear_force, &j.normal_stress,
          &j.closure, &j.area, &j.peak_stress, &j.compressed_depth, &j.plastic_slip})
      field(st, *v);
    flag(st, j.sliding);
  });
  list(s, lv.blocks, [](Stream& st, VoussoirBlockState& b) {
    field(st, b.index);
    for (double* v : {&b.ux, &b.uz, &b.deflection, &b.rotation}) field(st, *v);
  });
  bool fitted = lv.fit.has_value();
  flag(s, fitted);
  if (fitted) {
    if (!lv.fit) lv.fit.emplace();
    ThrustLineFit& f = *lv.fit;
    for (double* v : {&f.parabola.c0, &f.parabola.c1, &f.parabola.c2, &f.parabola.rms_residual})
      field(s, *v);
    flag(s, f.parabola.curvature_resolved);
    for (double* v : {&f.catenary.y0, &f.catenary.x0, &f.catenary.a, &f.catenary.rms_residual})
      field(s, *v);
    field(s, f.catenary.iterations);
    for (double* v : {&f.load_per_unit_span, &f.parabola_thrust, &f.catenary_thrust}) field(s, *v);
  } else {
    lv.fit.reset();
  }
  text(s, lv.fit_error);
}

}  // namespace

void VoussoirRecorder::save_state(StateWriter& w) const {
  w.size(reference_.positions.size());
  for (std::size_t i = 0; i < reference_.positions.size(); ++i) {
    w.vec(reference_.positions[i]);
    w.quat(reference_.orientations[i]);
  }
  // The shared function takes its lists by reference (a few levels of a few joints: copies).
  std::vector<VoussoirLevel> levels = levels_, stable = stable_;
  list(w, levels, level_fields<StateWriter>);
  list(w, stable, level_fields<StateWriter>);
}

void VoussoirRecorder::load_state(StateReader& r) {
  const std::size_t n = r.size();
  reference_.positions.resize(n);
  reference_.orientations.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    reference_.positions[i] = r.vec();
    reference_.orientations[i] = r.quat();
  }
  list(r, levels_, level_fields<StateReader>);
  list(r, stable_, level_fields<StateReader>);
}

std::string VoussoirRecorder::failure_note() const {
  if (stable_.empty()) return {};
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g g", stable_.back().g_level);
  return std::string("; last stable level ") + buf;
}

void VoussoirRecorder::add_to_summary(nlohmann::json& summary, RunStatus status) const {
  summary["voussoir"] = voussoir_summary(spec_, stable_);
  // The headline numbers at the top level too, as the contract asks.
  for (const char* key :
       {"g_max", "thrust_N", "midspan_deflection_mm", "equilibrium_residual", "fits"}) {
    if (summary["voussoir"].contains(key)) summary[key] = summary["voussoir"][key];
  }
  summary["lost_equilibrium"] = status != RunStatus::completed;
}

nlohmann::json fit_json(const VoussoirLevel& lv) {
  if (!lv.fit) return {{"error", lv.fit_error}};
  const auto& f = *lv.fit;
  return {{"parabola",
           {{"c0_m", f.parabola.c0},
            {"c1", f.parabola.c1},
            {"c2_per_m", f.parabola.c2},
            {"rms_mm", 1e3 * f.parabola.rms_residual},
            {"thrust_N", f.parabola_thrust}}},
          {"catenary",
           {{"y0_m", f.catenary.y0},
            {"x0_m", f.catenary.x0},
            {"a_m", f.catenary.a},
            {"rms_mm", 1e3 * f.catenary.rms_residual},
            {"thrust_N", f.catenary_thrust}}},
          {"load_per_unit_span_N_per_m", f.load_per_unit_span}};
}

nlohmann::json voussoir_summary(const VoussoirSpec& spec,
                                const std::vector<VoussoirLevel>& levels) {
  nlohmann::json j;
  j["beam"] = {
      {"blocks", spec.blocks},
      {"block_length_m", spec.block_length},
      {"block_width_m", spec.block_width},
      {"block_depth_m", spec.block_depth},
      {"span_m", spec.span()},
      {"abutment_length_m", spec.abutment_length},
      {"abutment_height_m", spec.abutment_height},
      {"abutment_note", "fixed blocks, tops flush with the beam top, covering the end faces"},
      {"density_kg_m3", spec.density},
      {"preload_force_N", spec.preload_force},
      {"servo_side", spec.servo_side}};
  if (levels.empty()) return j;
  const VoussoirLevel& last = levels.back();
  double worst = 0.0;
  for (const auto& lv : levels) {
    if (std::isfinite(lv.equilibrium_residual)) worst = std::max(worst, lv.equilibrium_residual);
  }
  j["g_max"] = last.g_level;
  j["thrust_N"] = last.thrust;
  j["midspan_deflection_mm"] = 1e3 * last.midspan_deflection;
  j["abutment_slip_mm"] = 1e3 * last.abutment_slip;
  j["max_normal_stress_MPa"] = 1e-6 * last.max_normal_stress;
  j["equilibrium_residual"] = worst;
  j["fits"] = fit_json(last);
  nlohmann::json per = nlohmann::json::array();
  for (const auto& lv : levels) {
    per.push_back({{"g_level", lv.g_level},
                   {"thrust_N", lv.thrust},
                   {"midspan_deflection_mm", 1e3 * lv.midspan_deflection},
                   {"equilibrium_residual", lv.equilibrium_residual},
                   {"fits", fit_json(lv)}});
  }
  j["levels"] = per;
  return j;
}

}  // namespace blockdem
