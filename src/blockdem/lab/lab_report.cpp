// CSV files and JSON summaries of the virtual laboratory's tests.
#include "blockdem/lab/lab_report.hpp"

#include <cmath>
#include <limits>

#include "blockdem/io/csv.hpp"

namespace blockdem {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

void write_compression_csv(const std::filesystem::path& path, const CompressionCurve& kernel,
                           const DemCompressionRun* dem) {
  std::vector<std::string> columns = {"cycle", "branch", "closure_m", "normal_stress_Pa",
                                      "tangent_stiffness_Pa_per_m"};
  if (dem) {
    columns.insert(columns.end(), {"dem_closure_m", "dem_normal_stress_Pa", "dem_overlap_m",
                                   "dem_contact_area_m2", "dem_steps", "dem_converged"});
  }
  // The engine's level for each kernel point, if any.
  std::vector<const DemCompressionPoint*> level(kernel.points.size(), nullptr);
  if (dem) {
    for (const auto& p : dem->points) level.at(p.kernel_index) = &p;
  }
  CsvWriter csv(path, columns);
  for (std::size_t i = 0; i < kernel.points.size(); ++i) {
    const CompressionPoint& p = kernel.points[i];
    csv.cell(p.cycle).cell(std::string(branch_name(p.branch)));
    csv.cell(p.closure).cell(p.normal_stress).cell(p.tangent_stiffness);
    if (dem) {
      if (const DemCompressionPoint* d = level[i]) {
        csv.cell(d->reading.closure).cell(d->reading.normal_stress).cell(d->reading.overlap);
        csv.cell(d->reading.contact_area).cell(static_cast<long long>(d->steps));
        csv.cell(d->converged ? 1 : 0);
      } else {
        for (int k = 0; k < 6; ++k) csv.cell(std::string());
      }
    }
    csv.end_row();
  }
}

void write_shear_csv(const std::filesystem::path& path, const ShearCurve& kernel,
                     const DemShearRun* dem) {
  std::vector<std::string> columns = {
      "cycle",          "shear_displacement_m",    "shear_stress_Pa", "mobilised_friction",
      "plastic_slip_m", "step_stiffness_Pa_per_m", "sliding"};
  if (dem) {
    columns.insert(columns.end(),
                   {"dem_shear_displacement_m", "dem_shear_stress_Pa", "dem_normal_stress_Pa",
                    "dem_mobilised_friction", "dem_plastic_slip_m"});
  }
  CsvWriter csv(path, columns);
  for (std::size_t i = 0; i < kernel.points.size(); ++i) {
    const ShearPoint& p = kernel.points[i];
    csv.cell(p.cycle).cell(p.shear_displacement).cell(p.shear_stress).cell(p.mobilised_friction);
    csv.cell(p.plastic_slip).cell(p.step_stiffness).cell(p.sliding ? 1 : 0);
    if (dem) {
      const RigReading& r = dem->readings.at(i);
      csv.cell(r.shear_displacement).cell(r.shear_stress).cell(r.normal_stress);
      csv.cell(r.normal_stress > 0.0 ? r.shear_stress / r.normal_stress : kNaN);
      csv.cell(r.plastic_slip);
    }
    csv.end_row();
  }
}

nlohmann::ordered_json compression_summary(const CompressionTestDef& def,
                                           const CompressionCurve& kernel,
                                           const DemCompressionRun* dem) {
  nlohmann::ordered_json j;
  j["test"] = "compression";
  j["normal_law"] = {{"law", law_name(def.law)}, {"description", describe(def.law)}};
  j["path"] = {{"cycles", def.cycles},
               {"steps_per_branch", def.steps_per_branch},
               {"max_closure_m", kernel.max_closure},
               {"max_stress_Pa", kernel.max_stress},
               {"points", kernel.points.size()}};
  const CompressionPoint& top = kernel.points.at(static_cast<std::size_t>(def.steps_per_branch));
  j["kernel"] = {{"max_stress_Pa", kernel.max_stress},
                 {"tangent_stiffness_at_zero_Pa_per_m", kernel.points.front().tangent_stiffness},
                 {"tangent_stiffness_at_max_Pa_per_m", top.tangent_stiffness},
                 {"secant_stiffness_Pa_per_m", kernel.max_stress / kernel.max_closure}};
  if (dem) {
    j["dem"] = {{"contact_mode", to_string(dem->contact_mode)},
                {"levels", dem->points.size()},
                {"total_steps", dem->total_steps},
                {"converged", dem->converged},
                {"message", dem->message},
                {"max_closure_difference_m", dem->max_closure_difference},
                {"max_relative_closure_difference", dem->max_relative_closure_difference},
                {"max_stress_difference_Pa", dem->max_stress_difference},
                {"max_relative_stress_difference", dem->max_relative_stress_difference}};
  }
  return j;
}

nlohmann::ordered_json shear_summary(const ShearTestDef& def, const NormalLaw& normal,
                                     const ShearCurve& kernel, const DemShearRun* dem) {
  nlohmann::ordered_json j;
  j["test"] = "shear";
  j["shear_law"] = {{"law", law_name(def.law)}, {"description", describe(def.law)}};
  j["normal_law"] = {{"law", law_name(normal)}, {"description", describe(normal)}};
  j["path"] = {{"normal_stress_Pa", def.normal_stress},
               {"max_shear_displacement_m", def.max_displacement},
               {"steps", def.steps},
               {"cycles", def.cycles},
               {"points", kernel.points.size()}};
  const ShearPoint& last = kernel.points.back();
  j["kernel"] = {
      {"peak_shear_stress_Pa", kernel.peak_shear_stress},
      {"peak_mobilised_friction", kernel.peak_shear_stress / def.normal_stress},
      {"final_shear_displacement_m", last.shear_displacement},
      {"final_shear_stress_Pa", last.shear_stress},
      {"final_mobilised_friction", last.mobilised_friction},
      {"final_plastic_slip_m", last.plastic_slip},
      {"initial_stiffness_Pa_per_m", shear_stiffness_estimate(def.law, def.normal_stress)}};
  if (dem) {
    j["dem"] = {{"contact_mode", to_string(dem->contact_mode)},
                {"settle_steps", dem->settle_steps},
                {"settled", dem->settled},
                {"message", dem->message},
                {"shear_steps", dem->readings.size() - 1},
                {"time_step_s", dem->time_step},
                {"shear_speed_m_per_s", dem->shear_speed},
                {"max_shear_stress_difference_Pa", dem->max_shear_stress_difference},
                {"max_relative_shear_stress_difference", dem->max_relative_shear_stress_difference},
                {"max_relative_normal_stress_deviation", dem->max_relative_normal_stress_deviation},
                {"max_shear_displacement_difference_m", dem->max_displacement_difference}};
  }
  return j;
}

}  // namespace blockdem
