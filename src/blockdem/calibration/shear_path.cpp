// Monotonic direct shear through update_shear at constant normal stress (see the header).
#include "blockdem/calibration/shear_path.hpp"

#include <cmath>
#include <stdexcept>

#include "blockdem/contact/law_params.hpp"

namespace blockdem {

std::vector<double> simulate_monotonic_shear(const ShearLaw& law, double normal_stress,
                                             const std::vector<double>& displacements,
                                             int substeps) {
  if (!(normal_stress > 0.0 && std::isfinite(normal_stress))) {
    throw std::invalid_argument("simulate_monotonic_shear: normal stress must be positive, got " +
                                format_value(normal_stress));
  }
  if (substeps < 1) {
    throw std::invalid_argument("simulate_monotonic_shear: substeps must be >= 1, got " +
                                std::to_string(substeps));
  }
  // Unit area: F_n (N) equals sigma_n (Pa), |F| (N) equals tau (Pa).
  ShearIncrement increment;
  increment.normal = Eigen::Vector3d::UnitZ();
  increment.normal_force = normal_stress;
  increment.normal_stress = normal_stress;
  increment.contact_area = 1.0;
  ShearState state;
  std::vector<double> tau;
  tau.reserve(displacements.size());
  double previous = 0.0;
  for (double u : displacements) {
    if (!(u >= previous && std::isfinite(u))) {
      throw std::invalid_argument(
          "simulate_monotonic_shear: displacements must be finite, >= 0 and non-decreasing; " +
          format_value(u) + " follows " + format_value(previous));
    }
    const double step = (u - previous) / substeps;
    for (int s = 0; s < substeps; ++s) {
      increment.displacement = Eigen::Vector3d(step, 0.0, 0.0);
      update_shear(law, state, increment);
    }
    previous = u;
    tau.push_back(state.force.norm());
  }
  return tau;
}

}  // namespace blockdem
