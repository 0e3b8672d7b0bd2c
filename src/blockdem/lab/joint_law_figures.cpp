// The curves of the joint-law figures (the paper's Figs 1(b), 2, 3, 4), each computed by driving
// the kernels of contact/ along the paths of the virtual laboratory.
#include "blockdem/lab/joint_law_figures.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "blockdem/contact/law_params.hpp"
#include "blockdem/io/csv.hpp"
#include "blockdem/lab/compression_test.hpp"
#include "blockdem/lab/shear_test.hpp"

namespace blockdem {
namespace {

[[noreturn]] void fail_figures(const std::string& what) {
  throw std::invalid_argument("joint-law figures: " + what);
}

void require_positive(const char* name, double value, const char* unit) {
  if (!(value > 0.0 && std::isfinite(value))) {
    fail_figures(std::string(name) + " must be positive and finite, got " + format_value(value) +
                 " " + unit);
  }
}

}  // namespace

void JointLawFiguresDef::validate() const {
  require_positive("max_normal_stress", max_normal_stress, "Pa");
  if (shear_normal_stresses.empty()) fail_figures("shear_normal_stresses is empty");
  for (double s : shear_normal_stresses) require_positive("shear_normal_stresses", s, "Pa");
  require_positive("min_stiffness_stress", min_stiffness_stress, "Pa");
  require_positive("max_stiffness_stress", max_stiffness_stress, "Pa");
  if (!(max_stiffness_stress > min_stiffness_stress)) {
    fail_figures("max_stiffness_stress must exceed min_stiffness_stress");
  }
  require_positive("max_shear_displacement", max_shear_displacement, "m");
  if (steps < 2) fail_figures("steps must be at least 2, got " + std::to_string(steps));
}

std::vector<std::filesystem::path> write_joint_law_figure_data(const std::filesystem::path& dir,
                                                               const JointLawFiguresDef& def) {
  def.validate();
  std::vector<std::filesystem::path> written;

  // Fig 1(b): the loading branch of a compression path for each normal law.
  {
    const std::filesystem::path path = dir / "fig1b_normal_laws.csv";
    CsvWriter csv(path, {"law", "closure_m", "normal_stress_Pa"});
    const std::pair<const char*, NormalLaw> laws[] = {{"eq3", ExponentialNormal::eq3()},
                                                      {"eq4", ExponentialNormal::eq4()},
                                                      {"linear_table2", LinearNormal{10e9}}};
    for (const auto& [name, law] : laws) {
      CompressionTestDef test;
      test.law = law;
      test.max_stress = def.max_normal_stress;
      test.steps_per_branch = def.steps;
      const CompressionCurve curve = run_compression_kernel(test);
      for (const auto& p : curve.points) {
        if (p.branch != PathBranch::loading) break;
        csv.cell(std::string(name)).cell(p.closure).cell(p.normal_stress).end_row();
      }
    }
    written.push_back(path);
  }

  // Fig 2: tangent shear stiffness of the degrading law (eq 5) along monotonic shear, up to 1.2
  // times the largest u_peak (eq 6): with its 40 degree Mohr-Coulomb cap, and with the cap lifted
  // (friction angle 89.9 degrees, tan = 573, far above the peak tau/sigma_n of eq 5, about 0.9),
  // which leaves eq 5 alone as in the paper's figure.
  {
    const std::filesystem::path path = dir / "fig2_shear_stiffness.csv";
    CsvWriter csv(path, {"normal_stress_Pa", "shear_displacement_m", "shear_stiffness_Pa_per_m",
                         "capped_shear_stiffness_Pa_per_m", "initial_stiffness_Pa_per_m",
                         "peak_displacement_m"});
    const DegradingShear law;
    DegradingShear uncapped;
    uncapped.strength = JointStrength::from_friction_deg(89.9);
    double max_peak = 0.0;
    for (double s : def.shear_normal_stresses) {
      max_peak = std::max(max_peak, law.power_laws.peak_displacement(s));
    }
    for (double s : def.shear_normal_stresses) {
      ShearTestDef test;
      test.law = uncapped;
      test.normal_stress = s;
      test.max_displacement = 1.2 * max_peak;
      test.steps = def.steps;
      const ShearCurve curve = run_shear_kernel(test);
      test.law = law;
      const ShearCurve capped = run_shear_kernel(test);
      for (std::size_t k = 1; k < curve.points.size(); ++k) {
        const double mid =
            0.5 * (curve.points[k - 1].shear_displacement + curve.points[k].shear_displacement);
        csv.cell(s).cell(mid).cell(curve.points[k].step_stiffness);
        csv.cell(capped.points[k].step_stiffness);
        csv.cell(law.power_laws.initial_stiffness(s)).cell(law.power_laws.peak_displacement(s));
        csv.end_row();
      }
    }
    written.push_back(path);
  }

  // Fig 3: initial shear stiffness against normal stress, eq 7 and eq 2.
  {
    const std::filesystem::path path = dir / "fig3_initial_shear_stiffness.csv";
    CsvWriter csv(path,
                  {"normal_stress_Pa", "eq7_initial_stiffness_Pa_per_m", "eq2_stiffness_Pa_per_m"});
    const ShearLaw eq7 = ContinuouslyYieldingShear{};
    const ShearLaw eq2 = StressLinearShear{};
    const double ratio = def.max_stiffness_stress / def.min_stiffness_stress;
    for (int i = 0; i <= def.steps; ++i) {
      const double s = def.min_stiffness_stress *
                       std::pow(ratio, static_cast<double>(i) / static_cast<double>(def.steps));
      csv.cell(s).cell(shear_stiffness_estimate(eq7, s)).cell(shear_stiffness_estimate(eq2, s));
      csv.end_row();
    }
    written.push_back(path);
  }

  // Fig 4: tau against u_s for the continuously-yielding law (eq 8) at each normal stress.
  {
    const std::filesystem::path path = dir / "fig4_shear_stress.csv";
    CsvWriter csv(path, {"normal_stress_Pa", "shear_displacement_m", "shear_stress_Pa",
                         "mobilised_friction", "plastic_slip_m"});
    for (double s : def.shear_normal_stresses) {
      ShearTestDef test;
      test.law = ContinuouslyYieldingShear{};
      test.normal_stress = s;
      test.max_displacement = def.max_shear_displacement;
      test.steps = def.steps;
      for (const auto& p : run_shear_kernel(test).points) {
        csv.cell(s).cell(p.shear_displacement).cell(p.shear_stress).cell(p.mobilised_friction);
        csv.cell(p.plastic_slip).end_row();
      }
    }
    written.push_back(path);
  }
  return written;
}

}  // namespace blockdem
