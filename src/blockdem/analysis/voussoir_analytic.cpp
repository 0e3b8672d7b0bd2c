// Diederichs & Kaiser (1999) voussoir beam: lever-arm iteration per n, scan and golden-section
// refinement of n, closed-form snap-through limit, safety factors and the JSON report.
#include "blockdem/analysis/voussoir_analytic.hpp"
#include "blockdem/numerics/units.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace blockdem {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

bool positive_finite(double v) {
  return v > 0.0 && std::isfinite(v);
}

// Lever arm of the undeflected arch: the stress blocks of depth n T at midspan (top) and at the
// abutments (bottom) have their resultants n T / 3 from the beam faces, so Z0 = T - 2 n T / 3.
double initial_lever_arm(double depth, double n) {
  return depth * (1.0 - 2.0 * n / 3.0);
}

// Length of the parabolic compression arch of rise Z0 on span S (D&K; shallow-arch expansion).
double arch_length(double span, double lever_arm0) {
  return span + 8.0 * lever_arm0 * lever_arm0 / (3.0 * span);
}

void check_n(double n) {
  if (!(n > 0.0 && n <= 1.0)) {
    std::ostringstream msg;
    msg << "voussoir beam: compression-zone ratio n must lie in (0, 1], got " << n;
    throw std::invalid_argument(msg.str());
  }
}

// Values of n scanned: step, 2 step, ..., and 1 itself.
std::vector<double> scan_grid(double step) {
  std::vector<double> grid;
  const auto count = static_cast<long>(std::floor(1.0 / step + 1e-9));
  grid.reserve(static_cast<std::size_t>(count) + 1);
  for (long i = 1; i <= count; ++i) grid.push_back(static_cast<double>(i) * step);
  if (grid.empty() || grid.back() < 1.0 - 1e-12) grid.push_back(1.0);
  return grid;
}

struct Minimum {
  double n = 0.0;
  double value = kInfinity;
};

// Golden-section search for the minimum of f on [lo, hi] to bracket width `tolerance`; f may
// return +inf where it is undefined (e.g. snap-through), which the search then avoids.
Minimum golden_section(const std::function<double(double)>& f, double lo, double hi,
                       double tolerance) {
  const double inv_phi = (std::sqrt(5.0) - 1.0) / 2.0;
  double a = lo;
  double b = hi;
  double c = b - inv_phi * (b - a);
  double d = a + inv_phi * (b - a);
  double fc = f(c);
  double fd = f(d);
  while (b - a > tolerance) {
    if (fc <= fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - inv_phi * (b - a);
      fc = f(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + inv_phi * (b - a);
      fd = f(d);
    }
  }
  return fc <= fd ? Minimum{c, fc} : Minimum{d, fd};
}

// Scan f over the grid, then refine the best grid point within one step either side.
Minimum minimise_over_n(const std::function<double(double)>& f,
                        const VoussoirSolverOptions& options) {
  Minimum best;
  for (const double n : scan_grid(options.n_step)) {
    const double value = f(n);
    if (value < best.value) best = {n, value};
  }
  if (!std::isfinite(best.value)) return best;
  const double lo = best.n > options.n_step ? best.n - options.n_step : 0.5 * best.n;
  const double hi = std::min(best.n + options.n_step, 1.0);
  const Minimum refined = golden_section(f, lo, hi, options.n_tolerance);
  return refined.value < best.value ? refined : best;
}

// Largest span with an equilibrium at this n: positive root in S^2 of
// S^4 + b S^2 = R, b = 8 Z0^2 / 3, R = 64 n Z0^3 E / (3 sqrt(3) gamma (2/3 + n)).
double critical_span_at(const VoussoirBeamDef& beam, double n) {
  const double z0 = initial_lever_arm(beam.depth, n);
  const double b = 8.0 * z0 * z0 / 3.0;
  const double r = 64.0 * n * z0 * z0 * z0 * beam.rock_mass_modulus /
                   (3.0 * std::numbers::sqrt3 * beam.unit_weight * (2.0 / 3.0 + n));
  // S^2 = (-b + sqrt(b^2 + 4R)) / 2, written without cancellation as 2R / (b + sqrt(b^2 + 4R)).
  const double s_squared = 2.0 * r / (b + std::sqrt(b * b + 4.0 * r));
  return std::sqrt(s_squared);
}

void append_error(std::ostringstream& errors, bool& any, const std::string& text) {
  errors << (any ? "; " : "") << text;
  any = true;
}

}  // namespace

double rock_mass_modulus_rigid_blocks(double joint_normal_stiffness, double joint_spacing) {
  if (!positive_finite(joint_normal_stiffness)) {
    throw std::invalid_argument(
        "rock mass modulus: joint_normal_stiffness (Pa/m) must be positive");
  }
  if (!positive_finite(joint_spacing)) {
    throw std::invalid_argument("rock mass modulus: joint_spacing (m) must be positive");
  }
  return joint_normal_stiffness * joint_spacing;
}

double rock_mass_modulus(double intact_modulus, double joint_normal_stiffness,
                         double joint_spacing) {
  if (!positive_finite(intact_modulus)) {
    throw std::invalid_argument("rock mass modulus: intact_modulus (Pa) must be positive");
  }
  const double joint_modulus =
      rock_mass_modulus_rigid_blocks(joint_normal_stiffness, joint_spacing);
  // Block and joint in series over one spacing: compliances add.
  return 1.0 / (1.0 / intact_modulus + 1.0 / joint_modulus);
}

void VoussoirBeamDef::validate() const {
  std::ostringstream errors;
  bool any = false;
  auto require_positive = [&](const char* name, double value, const char* unit) {
    if (!positive_finite(value)) {
      std::ostringstream e;
      e << name << " must be positive and finite, got " << value << " " << unit;
      append_error(errors, any, e.str());
    }
  };
  require_positive("span", span, "m");
  require_positive("depth", depth, "m");
  require_positive("unit_weight", unit_weight, "N/m^3");
  require_positive("rock_mass_modulus", rock_mass_modulus, "Pa");
  if (width) require_positive("width", *width, "m");
  if (compressive_strength) require_positive("compressive_strength", *compressive_strength, "Pa");
  if (friction_angle && !(*friction_angle > 0.0 && *friction_angle < std::numbers::pi / 2.0)) {
    std::ostringstream e;
    e << "friction_angle must lie in (0, 90) degrees, got " << rad_to_deg(*friction_angle)
      << " degrees";
    append_error(errors, any, e.str());
  }
  if (any) throw std::invalid_argument("voussoir beam: " + errors.str());
}

void VoussoirSolverOptions::validate() const {
  if (!(n_step > 0.0 && n_step <= 0.5)) {
    throw std::invalid_argument("VoussoirSolverOptions.n_step must lie in (0, 0.5]");
  }
  if (!(n_tolerance > 0.0 && n_tolerance < n_step)) {
    throw std::invalid_argument("VoussoirSolverOptions.n_tolerance must lie in (0, n_step)");
  }
  if (!(lever_arm_tolerance > 0.0 && lever_arm_tolerance < 1e-3)) {
    throw std::invalid_argument("VoussoirSolverOptions.lever_arm_tolerance must lie in (0, 1e-3)");
  }
  if (max_iterations < 1) {
    throw std::invalid_argument("VoussoirSolverOptions.max_iterations must be >= 1");
  }
}

VoussoirTrial voussoir_trial(const VoussoirBeamDef& beam, double n,
                             const VoussoirSolverOptions& options) {
  beam.validate();
  options.validate();
  check_n(n);
  const double span = beam.span;
  VoussoirTrial trial;
  trial.n = n;
  trial.initial_lever_arm = initial_lever_arm(beam.depth, n);
  trial.arch_length = arch_length(span, trial.initial_lever_arm);
  const double z0 = trial.initial_lever_arm;

  // Stresses and shortening of the arch at lever arm z (D&K): f_m from moment equilibrium of the
  // half span, f_av the mean over the arch, dL the elastic shortening.
  auto update_stresses = [&](double z) {
    trial.lever_arm = z;
    trial.max_stress = beam.unit_weight * span * span / (4.0 * n * z);
    trial.average_stress = trial.max_stress * (2.0 / 3.0 + n) / 3.0;
    trial.arch_shortening = trial.average_stress * trial.arch_length / beam.rock_mass_modulus;
  };

  update_stresses(z0);
  for (int k = 0; k < options.max_iterations; ++k) {
    trial.iterations = k + 1;
    // Shortened arch of the same span: L - dL = S + 8 Z^2 / (3 S).
    const double argument =
        3.0 * span / 8.0 * (8.0 * z0 * z0 / (3.0 * span) - trial.arch_shortening);
    if (!(argument > 0.0)) {
      trial.status = VoussoirTrialStatus::snap_through;
      return trial;
    }
    const double z_next = std::sqrt(argument);
    const double change = std::abs(z_next - trial.lever_arm);
    update_stresses(z_next);
    if (change <= options.lever_arm_tolerance * z0) {
      trial.status = VoussoirTrialStatus::converged;
      return trial;
    }
  }
  trial.status = VoussoirTrialStatus::iteration_limit;
  return trial;
}

double voussoir_critical_modulus(const VoussoirBeamDef& beam, double n) {
  beam.validate();
  check_n(n);
  const double z0 = initial_lever_arm(beam.depth, n);
  const double length = arch_length(beam.span, z0);
  const double s = beam.span;
  return 3.0 * std::numbers::sqrt3 * beam.unit_weight * s * s * s * (2.0 / 3.0 + n) * length /
         (64.0 * n * z0 * z0 * z0);
}

std::string to_string(VoussoirStatus status) {
  switch (status) {
    case VoussoirStatus::stable:
      return "stable";
    case VoussoirStatus::snap_through:
      return "snap_through";
  }
  throw std::logic_error("unknown VoussoirStatus value");
}

VoussoirResult solve_voussoir_beam(const VoussoirBeamDef& beam,
                                   const VoussoirSolverOptions& options) {
  beam.validate();
  options.validate();
  VoussoirResult result;

  // Scan n, counting outcomes; f_m is the objective, +inf where there is no equilibrium.
  Minimum best;
  for (const double n : scan_grid(options.n_step)) {
    const VoussoirTrial trial = voussoir_trial(beam, n, options);
    ++result.scanned_n_count;
    if (trial.status == VoussoirTrialStatus::converged) {
      ++result.feasible_n_count;
      if (trial.max_stress < best.value) best = {n, trial.max_stress};
    } else if (trial.status == VoussoirTrialStatus::iteration_limit) {
      ++result.unresolved_n_count;
    }
  }
  auto max_stress_of = [&](double n) {
    const VoussoirTrial trial = voussoir_trial(beam, n, options);
    return trial.status == VoussoirTrialStatus::converged ? trial.max_stress : kInfinity;
  };
  if (std::isfinite(best.value)) {
    const double lo = best.n > options.n_step ? best.n - options.n_step : 0.5 * best.n;
    const double hi = std::min(best.n + options.n_step, 1.0);
    const Minimum refined = golden_section(max_stress_of, lo, hi, options.n_tolerance);
    if (refined.value < best.value) best = refined;

    const VoussoirTrial trial = voussoir_trial(beam, best.n, options);
    VoussoirEquilibrium eq;
    eq.n = trial.n;
    eq.initial_lever_arm = trial.initial_lever_arm;
    eq.lever_arm = trial.lever_arm;
    eq.arch_length = trial.arch_length;
    eq.arch_shortening = trial.arch_shortening;
    eq.midspan_deflection = trial.initial_lever_arm - trial.lever_arm;
    eq.max_stress = trial.max_stress;
    eq.average_stress = trial.average_stress;
    // Resultant of the triangular stress block of depth n T and peak f_m; by moment equilibrium
    // of the half span it equals gamma T S^2 / (8 Z).
    eq.thrust_per_width = trial.max_stress * trial.n * beam.depth / 2.0;
    if (beam.width) eq.thrust = eq.thrust_per_width * *beam.width;
    if (beam.compressive_strength)
      eq.crushing_safety_factor = *beam.compressive_strength / eq.max_stress;
    if (beam.friction_angle) {
      // D&K / Brady & Brown abutment check: frictional resistance of the thrust, H tan(phi),
      // against the vertical shear at each abutment, half the beam weight gamma T S / 2.
      const double abutment_shear = beam.unit_weight * beam.depth * beam.span / 2.0;
      eq.sliding_safety_factor =
          eq.thrust_per_width * std::tan(*beam.friction_angle) / abutment_shear;
    }
    eq.iterations = trial.iterations;
    result.equilibrium = eq;
    result.status = VoussoirStatus::stable;
  } else {
    result.status = VoussoirStatus::snap_through;
  }

  // Buckling limit from the closed-form fold of the lever-arm cubic.
  const Minimum modulus =
      minimise_over_n([&](double n) { return voussoir_critical_modulus(beam, n); }, options);
  const Minimum span =
      minimise_over_n([&](double n) { return -critical_span_at(beam, n); }, options);
  result.buckling.critical_modulus = modulus.value;
  result.buckling.critical_modulus_n = modulus.n;
  result.buckling.critical_span = -span.value;
  result.buckling.modulus_safety_factor = beam.rock_mass_modulus / modulus.value;
  result.buckling.span_safety_factor = -span.value / beam.span;
  return result;
}

nlohmann::ordered_json voussoir_report_json(const VoussoirBeamDef& beam,
                                            const VoussoirResult& result) {
  auto optional_value = [](const std::optional<double>& v) {
    return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);
  };
  nlohmann::ordered_json out;
  out["method"] = "voussoir beam, Diederichs & Kaiser (1999) IJRMMS 36:97-117";
  out["status"] = to_string(result.status);
  const std::optional<VoussoirEquilibrium>& eq = result.equilibrium;
  if (eq) {
    out["n"] = eq->n;
    out["initial_lever_arm_m"] = eq->initial_lever_arm;
    out["lever_arm_m"] = eq->lever_arm;
    out["arch_length_m"] = eq->arch_length;
    out["arch_shortening_m"] = eq->arch_shortening;
    out["midspan_deflection_m"] = eq->midspan_deflection;
    out["max_stress_Pa"] = eq->max_stress;
    out["average_stress_Pa"] = eq->average_stress;
    out["thrust_N_per_m"] = eq->thrust_per_width;
    out["thrust_N"] = optional_value(eq->thrust);
    out["crushing_safety_factor"] = optional_value(eq->crushing_safety_factor);
    out["sliding_safety_factor"] = optional_value(eq->sliding_safety_factor);
    out["iterations"] = eq->iterations;
  } else {
    const char* keys[] = {"n",
                          "initial_lever_arm_m",
                          "lever_arm_m",
                          "arch_length_m",
                          "arch_shortening_m",
                          "midspan_deflection_m",
                          "max_stress_Pa",
                          "average_stress_Pa",
                          "thrust_N_per_m",
                          "thrust_N",
                          "crushing_safety_factor",
                          "sliding_safety_factor",
                          "iterations"};
    for (const char* key : keys) out[key] = nullptr;
    out["message"] =
        "snap-through: no compression-zone ratio n in (0, 1] gives an equilibrium lever arm; the "
        "rock-mass modulus is below the critical modulus (see buckling)";
  }
  out["buckling"] = {
      {"critical_modulus_Pa", result.buckling.critical_modulus},
      {"critical_modulus_n", result.buckling.critical_modulus_n},
      {"critical_span_m", result.buckling.critical_span},
      {"modulus_safety_factor", result.buckling.modulus_safety_factor},
      {"span_safety_factor", result.buckling.span_safety_factor},
  };
  out["scan"] = {{"scanned_n", result.scanned_n_count},
                 {"feasible_n", result.feasible_n_count},
                 {"unresolved_n", result.unresolved_n_count}};
  out["inputs"] = {
      {"span_m", beam.span},
      {"depth_m", beam.depth},
      {"unit_weight_N_m3", beam.unit_weight},
      {"rock_mass_modulus_Pa", beam.rock_mass_modulus},
      {"width_m", optional_value(beam.width)},
      {"compressive_strength_Pa", optional_value(beam.compressive_strength)},
      {"friction_deg", beam.friction_angle
                           ? nlohmann::ordered_json(rad_to_deg(*beam.friction_angle))
                           : nlohmann::ordered_json(nullptr)},
  };
  return out;
}

}  // namespace blockdem
