// A direct shear test run through the engine's shear kernel (update_shear): monotonic shear
// displacement at constant normal stress on a unit joint area, as the calibration fits and the
// round-trip checks need it ("what the engine will do" with the calibrated law).
#pragma once

#include <vector>

#include "blockdem/contact/shear_laws.hpp"

namespace blockdem {

/// Drives `law` from a fresh ShearState (no force, no slip) along the shear displacements
/// `displacements` (m, non-decreasing, >= 0, starting from u = 0) at constant normal stress
/// sigma_n (Pa) on a joint of area 1 m^2 (so F_n = sigma_n and |F| = tau), in a fixed direction.
/// Each interval [u_{i-1}, u_i] (u_{-1} = 0) is covered by `substeps` equal calls of
/// update_shear. Returns tau = |F| (Pa) after each displacement. The continuously-yielding
/// kernel's implicit update is exact for this path at any step size (see shear_update.cpp), so
/// substeps = 1 gives the engine's curve; the degrading kernel integrates eq 5 exactly along it.
/// Throws std::invalid_argument for a non-positive or non-finite sigma_n, substeps < 1, or
/// displacements that are negative, non-finite or decreasing.
std::vector<double> simulate_monotonic_shear(const ShearLaw& law, double normal_stress,
                                             const std::vector<double>& displacements,
                                             int substeps = 1);

}  // namespace blockdem
