// The analytical voussoir beam of Diederichs & Kaiser (1999), "Stability of large excavations in
// laminated hard rock masses: the voussoir analogue revisited", IJRMMS 36:97-117 (D&K below):
// compression arch, iterated lever arm, snap-through, safety factors.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <optional>
#include <string>

namespace blockdem {

/// Rock-mass modulus of rigid blocks with joints of normal stiffness k_n at spacing s, loaded
/// across the joints: strain = sigma / (k_n s), so E_rm = k_n s (Pa). Throws
/// std::invalid_argument naming a non-positive or non-finite argument.
double rock_mass_modulus_rigid_blocks(double joint_normal_stiffness,  ///< k_n (Pa/m)
                                      double joint_spacing);          ///< s (m)

/// Rock-mass modulus of elastic blocks (modulus E_i) in series with joints: 1/E_rm = 1/E_i +
/// 1/(k_n s) (Pa). Throws std::invalid_argument naming a bad argument.
double rock_mass_modulus(double intact_modulus,          ///< E_i (Pa)
                         double joint_normal_stiffness,  ///< k_n (Pa/m)
                         double joint_spacing);          ///< s (m)

/// A single-layer beam (plane strain, per unit width unless `width` is given) clamped between
/// rigid abutments and loaded by its own weight.
struct VoussoirBeamDef {
  double span = 0.0;                           ///< S, clear span between abutments (m)
  double depth = 0.0;                          ///< T, beam thickness (m)
  double unit_weight = 0.0;                    ///< gamma = density * gravity (N/m^3)
  double rock_mass_modulus = 0.0;              ///< E_rm along the beam axis (Pa)
  std::optional<double> width;                 ///< b, out-of-plane width for total thrust (m)
  std::optional<double> compressive_strength;  ///< sigma_c, for the crushing factor (Pa)
  std::optional<double> friction_angle;        ///< phi of the abutment joints, sliding (rad)

  /// Throws std::invalid_argument listing every parameter that is missing, non-finite or out of
  /// range, by name, with its value and unit.
  void validate() const;
};

/// Numerical settings of the D&K solution. Defaults give n to ~1e-9.
struct VoussoirSolverOptions {
  double n_step = 1e-3;                ///< step of the scan over n in (0, 1] (-)
  double n_tolerance = 1e-10;          ///< golden-section bracket width that ends refinement (-)
  double lever_arm_tolerance = 1e-13;  ///< |Z_k+1 - Z_k| / Z0 that ends the iteration (-)
  int max_iterations = 100000;         ///< lever-arm iterations per n (-)

  /// Throws std::invalid_argument naming the first option out of range.
  void validate() const;
};

/// Outcome of the lever-arm iteration at one compression-zone ratio n.
enum class VoussoirTrialStatus {
  converged,        ///< Z converged to a positive value
  snap_through,     ///< the root's argument turned non-positive: no equilibrium at this n
  iteration_limit,  ///< neither after max_iterations (only right at the snap-through fold)
};

/// The D&K iteration at a fixed n (D&K's iterative procedure):
///   Z0 = T (1 - 2n/3),  L = S + 8 Z0^2 / (3 S),  Z := Z0, then repeat
///   f_m = gamma S^2 / (4 n Z),  f_av = f_m (2/3 + n) / 3,  dL = f_av L / E_rm,
///   Z = sqrt(3S/8 (8 Z0^2 / (3S) - dL))
/// until Z stops changing. The fields other than n, Z0 and L hold the last iterate.
struct VoussoirTrial {
  double n = 0.0;                  ///< compression-zone ratio, depth of the stress block / T (-)
  double initial_lever_arm = 0.0;  ///< Z0, lever arm of the undeflected arch (m)
  double arch_length = 0.0;        ///< L, length of the parabolic compression arch (m)
  double lever_arm = 0.0;          ///< Z, lever arm after arch shortening (m)
  double max_stress = 0.0;         ///< f_m, peak of the triangular stress block (Pa)
  double average_stress = 0.0;     ///< f_av, mean longitudinal stress of the arch (Pa)
  double arch_shortening = 0.0;    ///< dL, elastic shortening of the arch (m)
  int iterations = 0;              ///< lever-arm iterations done (-)
  VoussoirTrialStatus status = VoussoirTrialStatus::iteration_limit;
};

/// Runs the iteration at one n in (0, 1]. Validates its inputs (throws std::invalid_argument).
VoussoirTrial voussoir_trial(const VoussoirBeamDef& beam, double n,
                             const VoussoirSolverOptions& options = {});

/// The equilibrium chosen: the n with the smallest converged f_m.
struct VoussoirEquilibrium {
  double n = 0.0;                   ///< compression-zone ratio (-)
  double initial_lever_arm = 0.0;   ///< Z0 (m)
  double lever_arm = 0.0;           ///< Z (m)
  double arch_length = 0.0;         ///< L (m)
  double arch_shortening = 0.0;     ///< dL (m)
  double midspan_deflection = 0.0;  ///< Z0 - Z (m)
  double max_stress = 0.0;          ///< f_m (Pa)
  double average_stress = 0.0;      ///< f_av (Pa)
  double thrust_per_width = 0.0;    ///< H = f_m n T / 2, resultant of the stress block (N/m)
  std::optional<double> thrust;     ///< H b, if a width b was given (N)
  /// sigma_c / f_m, if sigma_c was given (-).
  std::optional<double> crushing_safety_factor;
  /// Abutment sliding: H tan(phi) / V with V = gamma T S / 2 the vertical abutment reaction per
  /// width, i.e. f_m n tan(phi) / (gamma S), if phi was given (-).
  std::optional<double> sliding_safety_factor;
  int iterations = 0;  ///< lever-arm iterations at the chosen n (-)
};

/// The snap-through (buckling) limit of the D&K model. Eliminating f_m, f_av and dL, the iteration
/// is the fixed point of Z^2 = Z0^2 - K / Z with K = gamma S^3 (2/3 + n) L / (32 n E_rm): the
/// cubic Z^3 - Z0^2 Z + K = 0. It has a positive root (equilibrium) iff K <= 2 Z0^3 / (3 sqrt 3);
/// at equality the stable and unstable roots merge at Z = Z0 / sqrt 3 (snap-through fold).
struct VoussoirBucklingLimit {
  /// Smallest E_rm with an equilibrium at some n: min over n of
  /// E_crit(n) = 3 sqrt(3) gamma S^3 (2/3 + n) L / (64 n Z0^3) (Pa).
  double critical_modulus = 0.0;
  double critical_modulus_n = 0.0;  ///< the n of that minimum (-)
  /// Largest span with an equilibrium at this E_rm, T and gamma: max over n of the root of
  /// S^4 + (8 Z0^2 / 3) S^2 = 64 n Z0^3 E_rm / (3 sqrt(3) gamma (2/3 + n)) (m).
  double critical_span = 0.0;
  double modulus_safety_factor = 0.0;  ///< E_rm / critical_modulus (-); < 1 means snap-through
  double span_safety_factor = 0.0;     ///< critical_span / S (-); < 1 means snap-through
};

/// Whether the beam has an equilibrium.
enum class VoussoirStatus { stable, snap_through };

/// "stable" or "snap_through".
std::string to_string(VoussoirStatus status);

/// Full D&K solution of a beam.
struct VoussoirResult {
  VoussoirStatus status = VoussoirStatus::snap_through;
  std::optional<VoussoirEquilibrium> equilibrium;  ///< present iff status == stable
  VoussoirBucklingLimit buckling;
  int scanned_n_count = 0;     ///< values of n tried in the scan (-)
  int feasible_n_count = 0;    ///< of those, with a converged lever arm (-)
  int unresolved_n_count = 0;  ///< of those, stopped by the iteration limit (-)
};

/// Solves the beam: scans n over (0, 1] in steps of options.n_step, refines the best n by golden
/// section within one step either side, and keeps the converged n with the smallest f_m (D&K).
/// No feasible n: status snap_through, no equilibrium. Throws std::invalid_argument for invalid
/// input (see VoussoirBeamDef::validate).
VoussoirResult solve_voussoir_beam(const VoussoirBeamDef& beam,
                                   const VoussoirSolverOptions& options = {});

/// E_crit(n) of VoussoirBucklingLimit at one n in (0, 1] (Pa). The beam must validate; its
/// rock_mass_modulus does not enter.
double voussoir_critical_modulus(const VoussoirBeamDef& beam, double n);

/// JSON report of a solution: status, the equilibrium in SI units with the unit in every key
/// (n, lever_arm_m, midspan_deflection_m, max_stress_Pa, thrust_N_per_m, thrust_N, ...; null when
/// snap-through), the buckling limit, scan counts, the inputs and the reference.
nlohmann::ordered_json voussoir_report_json(const VoussoirBeamDef& beam,
                                            const VoussoirResult& result);

}  // namespace blockdem
