// Legacy-format VTK files (ParaView opens them; numbered files such as blocks_0003.vtk load
// as one time series): block polyhedra and contacts at one instant.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "blockdem/world/world.hpp"

namespace blockdem {

/// Writes the blocks' faces as polygons with cell data block_index, displacement (m) and
/// velocity (m/s).
void write_vtk_blocks(const std::filesystem::path& path, const World& world);
/// Writes contact points with point data normal, normal_force_N, shear_force_N, overlap_m, area_m2,
/// and the contact slice polygons as cells.
void write_vtk_contacts(const std::filesystem::path& path, const World& world);

}  // namespace blockdem
