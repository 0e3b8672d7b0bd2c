// The [in_situ] table of a scenario (an in-situ stress field) and stress tensors as scenario
// files give them.
#pragma once

#include <Eigen/Core>
#include <string>

#include "blockdem/response/in_situ.hpp"
#include "blockdem/scenario/checked_table.hpp"

namespace blockdem {

/// A stress tensor (Pa, compression positive) at `key`: a table of its six components
/// { xx, yy, zz, xy, yz, xz } (a component not given is zero), or an array of three rows
/// [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]], which must be symmetric. Every value finite.
/// Throws ScenarioError naming the file, the key and the reason.
Eigen::Matrix3d read_stress_tensor(const CheckedTable& parent, const std::string& key);

/// Reads [in_situ]: either `stress` at `reference_z` (m, default 0) with an optional
/// `gradient_z` (Pa/m, a tensor as above), or the shorthand `ground_z` (m), `density` (kg/m^3)
/// or `material`, `k_x`, `k_y` (default 1) and `trend_deg` (default 0), whose vertical stress is
/// the weight of the rock above at the magnitude of `gravity` (m/s^2). `materials`: densities by
/// name. Throws ScenarioError naming the file, the key and the reason.
StressField read_in_situ(const CheckedTable& table, const Eigen::Vector3d& gravity,
                         const std::map<std::string, double>& materials);

}  // namespace blockdem
