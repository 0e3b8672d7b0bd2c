// Data of the joint-law figures in the style of Boon, Houlsby & Utili (2015), Figs 1(b), 2, 3 and
// 4, computed through the kernels and written as CSV files for tools/plot_joint_laws.py.
#pragma once

#include <filesystem>
#include <vector>

namespace blockdem {

struct JointLawFiguresDef {
  /// Fig 1(b): sigma-u of eqs 3 and 4 (and Table 2's linear law) from zero to this stress (Pa).
  double max_normal_stress = 1.5e6;
  /// Figs 2 and 4: the normal stresses of the shear curves (Pa). The paper's shear tests reach
  /// 0.023 MPa; its text does not list the individual stresses.
  std::vector<double> shear_normal_stresses{5e3, 10e3, 15e3, 20e3};
  /// Fig 3: k_s,initial over this range of normal stress, log-spaced (Pa).
  double min_stiffness_stress = 1e3;
  double max_stiffness_stress = 1e6;
  /// Fig 4: shear displacement at the end of the tau-u_s curves (m).
  double max_shear_displacement = 0.1e-3;
  int steps = 400;  ///< increments (or samples) per curve (-)

  /// Throws std::invalid_argument naming the parameter ("joint-law figures: ...").
  void validate() const;
};

/// Writes into `dir` (which must exist):
///  - fig1b_normal_laws.csv: law, closure_m, normal_stress_Pa (eq 3, eq 4, Table 2 linear);
///  - fig2_shear_stiffness.csv: normal_stress_Pa, shear_displacement_m, shear_stiffness_Pa_per_m
///    (eq 5 alone: the degrading law with its cap lifted), capped_shear_stiffness_Pa_per_m (with
///    the 40 degree Mohr-Coulomb cap), initial_stiffness_Pa_per_m, peak_displacement_m (eqs 6-7);
///    stiffness = d tau / d u_s of each increment of the kernel, at the increment's middle;
///  - fig3_initial_shear_stiffness.csv: normal_stress_Pa, eq7_initial_stiffness_Pa_per_m,
///    eq2_stiffness_Pa_per_m;
///  - fig4_shear_stress.csv: normal_stress_Pa, shear_displacement_m, shear_stress_Pa,
///    mobilised_friction, plastic_slip_m (the continuously-yielding law, eq 8).
/// Returns the paths written.
std::vector<std::filesystem::path> write_joint_law_figure_data(const std::filesystem::path& dir,
                                                               const JointLawFiguresDef& def = {});

}  // namespace blockdem
