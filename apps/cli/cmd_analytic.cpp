// `blockdem analytic voussoir`: the Diederichs & Kaiser (1999) voussoir beam from the command
// line, printed as JSON on stdout.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <iostream>
#include <memory>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "blockdem/analysis/voussoir_analytic.hpp"
#include "blockdem/numerics/units.hpp"
#include "commands.hpp"

namespace blockdem::cli {
namespace {

// Values given on the command line, in the units of their option names.
struct VoussoirArgs {
  double span = 0.0;                  ///< (m)
  double depth = 0.0;                 ///< (m)
  double density = 0.0;               ///< (kg/m^3)
  double gravity = 0.0;               ///< (m/s^2)
  double modulus = 0.0;               ///< (Pa)
  double width = 0.0;                 ///< (m)
  double compressive_strength = 0.0;  ///< (Pa)
  double friction_deg = 0.0;          ///< (deg)
};

void require_positive(const char* option, double value, const char* unit) {
  if (!(value > 0.0 && std::isfinite(value))) {
    std::ostringstream msg;
    msg << "analytic voussoir: " << option << " must be positive and finite, got " << value << " "
        << unit;
    throw std::invalid_argument(msg.str());
  }
}

}  // namespace

void register_analytic(CLI::App& app) {
  CLI::App* analytic = app.add_subcommand("analytic", "Analytical solutions (JSON on stdout)")
                           ->require_subcommand(1);
  CLI::App* voussoir = analytic->add_subcommand(
      "voussoir",
      "Voussoir beam of Diederichs & Kaiser (1999): lever arm, stress, thrust, "
      "deflection, snap-through");

  auto args = std::make_shared<VoussoirArgs>();
  voussoir->add_option("--span", args->span, "Clear span S between abutments (m)")->required();
  voussoir->add_option("--depth", args->depth, "Beam depth (thickness) T (m)")->required();
  voussoir->add_option("--density", args->density, "Rock density (kg/m^3)")->required();
  voussoir->add_option("--gravity", args->gravity, "Gravitational acceleration (m/s^2)")
      ->required();
  voussoir
      ->add_option("--modulus", args->modulus,
                   "Rock-mass modulus E_rm along the beam (Pa); rigid blocks: k_n * joint spacing")
      ->required();
  CLI::Option* width =
      voussoir->add_option("--width", args->width, "Out-of-plane width, for total thrust (m)");
  CLI::Option* strength =
      voussoir->add_option("--compressive-strength", args->compressive_strength,
                           "Uniaxial compressive strength, for the crushing safety factor (Pa)");
  CLI::Option* friction = voussoir->add_option(
      "--friction-deg", args->friction_deg,
      "Friction angle of the abutment joints, for the sliding safety factor (deg)");

  voussoir->callback([args, width, strength, friction]() {
    require_positive("--density", args->density, "kg/m^3");
    require_positive("--gravity", args->gravity, "m/s^2");
    VoussoirBeamDef beam;
    beam.span = args->span;
    beam.depth = args->depth;
    beam.unit_weight = args->density * args->gravity;
    beam.rock_mass_modulus = args->modulus;
    if (width->count() > 0) beam.width = args->width;
    if (strength->count() > 0) beam.compressive_strength = args->compressive_strength;
    if (friction->count() > 0) beam.friction_angle = deg_to_rad(args->friction_deg);
    beam.validate();

    const VoussoirResult result = solve_voussoir_beam(beam);
    nlohmann::ordered_json report = voussoir_report_json(beam, result);
    // Echo the inputs as given, in the command line's units.
    report["inputs"]["density_kg_m3"] = args->density;
    report["inputs"]["gravity_m_s2"] = args->gravity;
    if (friction->count() > 0) report["inputs"]["friction_deg"] = args->friction_deg;
    std::cout << report.dump(2) << "\n";
    set_exit_code(0);
  });
}

}  // namespace blockdem::cli
