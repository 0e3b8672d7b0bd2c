// Outputs of the virtual laboratory's compression and shear tests: CSV files (units in the column
// names) and JSON summaries.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "blockdem/lab/compression_test.hpp"
#include "blockdem/lab/shear_test.hpp"

namespace blockdem {

/// One row per kernel point: cycle, branch, closure_m, normal_stress_Pa,
/// tangent_stiffness_Pa_per_m; with `dem`, the engine's reading at that level (empty cells where
/// the engine ran no level): dem_closure_m, dem_normal_stress_Pa, dem_overlap_m,
/// dem_contact_area_m2, dem_steps, dem_converged.
void write_compression_csv(const std::filesystem::path& path, const CompressionCurve& kernel,
                           const DemCompressionRun* dem = nullptr);

/// One row per kernel point: cycle, shear_displacement_m, shear_stress_Pa, mobilised_friction,
/// plastic_slip_m, step_stiffness_Pa_per_m, sliding; with `dem`: dem_shear_displacement_m,
/// dem_shear_stress_Pa, dem_normal_stress_Pa, dem_mobilised_friction, dem_plastic_slip_m.
void write_shear_csv(const std::filesystem::path& path, const ShearCurve& kernel,
                     const DemShearRun* dem = nullptr);

/// Summary: the law (name, formula), the path, the extremes of the curve, and with `dem` the
/// engine's run (steps, convergence, max differences from the kernel).
nlohmann::ordered_json compression_summary(const CompressionTestDef& def,
                                           const CompressionCurve& kernel,
                                           const DemCompressionRun* dem = nullptr);
nlohmann::ordered_json shear_summary(const ShearTestDef& def, const NormalLaw& normal,
                                     const ShearCurve& kernel, const DemShearRun* dem = nullptr);

}  // namespace blockdem
