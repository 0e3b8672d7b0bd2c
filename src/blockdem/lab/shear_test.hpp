// The virtual laboratory's direct shear test at constant normal stress: a shear displacement path
// run through the shear-law kernel and, optionally, through the engine on two blocks.
#pragma once

#include <cstdint>
#include <vector>

#include "blockdem/contact/normal_laws.hpp"
#include "blockdem/contact/shear_laws.hpp"
#include "blockdem/lab/two_block_rig.hpp"

namespace blockdem {

/// The path, at constant normal stress: monotonic shear from 0 to `max_displacement` (cycles = 0),
/// or `cycles` times 0 -> +max -> -max -> 0. Every travel of `max_displacement` takes `steps` equal
/// increments, so a cycle has 4 steps increments.
struct ShearTestDef {
  ShearLaw law = ContinuouslyYieldingShear{};  ///< default: the paper's eqs 6-8
  double normal_stress = 0.0;                  ///< sigma_n, held constant (Pa), > 0
  double max_displacement = 0.0;               ///< u_s,max (m), > 0
  int steps = 2000;                            ///< increments per max_displacement of travel (-)
  int cycles = 0;                              ///< 0: monotonic; N >= 1: N full cycles (-)

  /// Throws std::invalid_argument naming the parameter ("shear test: ...").
  void validate() const;
};

struct ShearPoint {
  int cycle = 0;                    ///< 0 for the monotonic path, else 1-based (-)
  double shear_displacement = 0.0;  ///< u_s of the top face relative to the bottom (m)
  double shear_stress = 0.0;        ///< tau, resisting the displacement: -F_x / A (Pa)
  double mobilised_friction = 0.0;  ///< tau / sigma_n (-)
  double plastic_slip = 0.0;        ///< beta, accumulated |du_p| (m)
  /// d tau / d u_s over the increment that ends here (Pa/m); NaN at the start of the path.
  double step_stiffness = 0.0;
  bool sliding = false;  ///< the increment that ends here was plastic
};

struct ShearCurve {
  std::vector<ShearPoint> points;  ///< the start (u_s = 0), then every increment
  double peak_shear_stress = 0.0;  ///< max |tau| (Pa)
};

/// The signed increments of u_s along x (m), shared by the kernel and the engine runs.
std::vector<double> shear_path_increments(const ShearTestDef& def);

/// The path through the kernel: update_shear on a joint of unit area (1 m^2) with F_n = sigma_n.
ShearCurve run_shear_kernel(const ShearTestDef& def);

/// The engine run, one entry per kernel point.
struct DemShearRun {
  std::vector<RigReading> readings;  ///< after each increment (the first: after settling)
  ContactMode contact_mode = ContactMode::boon2012;  ///< the rig's
  std::int64_t settle_steps = 0;  ///< steps to bring the top block to rest under its weight
  bool settled = false;           ///< the settling stage converged
  std::string message;            ///< why it did not, empty otherwise
  double time_step = 0.0;         ///< the fixed step of the shearing phase (s)
  double shear_speed = 0.0;       ///< |velocity| of the bottom block while shearing (m/s)
  /// max over points |tau_dem - tau_kernel| (Pa) and the same over the kernel's peak |tau| (-).
  double max_shear_stress_difference = 0.0;
  double max_relative_shear_stress_difference = 0.0;
  /// max over points |sigma_dem - sigma_n| over sigma_n (-): how constant the normal stress was.
  double max_relative_normal_stress_deviation = 0.0;
  double max_displacement_difference = 0.0;  ///< max |u_s,dem - u_s,kernel| (m)
};

/// The same path on the two-block rig: the top block, placed at half the closure that carries
/// sigma_n, is settled under a weight sigma_n A (an equilibrium stage), then the
/// bottom block is moved along -x at a prescribed velocity, one path increment per time step (the
/// top block's x is held, as in a shear box). `normal` is the joint's normal law (the kernel run
/// needs none). Throws DivergenceError if the run blows up.
DemShearRun run_shear_dem(const ShearTestDef& def, const NormalLaw& normal,
                          const ShearCurve& kernel, const TwoBlockRigDef& rig = {});

}  // namespace blockdem
