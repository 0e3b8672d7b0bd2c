// `blockdem calibrate normal|shear|cy`: joint laws from laboratory data
// (docs/calibration.md). Prints a summary and the joint-law block (JSON and TOML); with --out DIR
// writes calibration.json, fit CSVs and PNG plots. Everything is checked before anything is
// written.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "blockdem/calibration/calibration_report.hpp"
#include "commands.hpp"
#include "figures.hpp"

namespace blockdem::cli {
namespace {

// Options shared by the three subcommands.
struct CommonArgs {
  std::string data;  ///< CSV file
  std::string out;   ///< output directory, empty: print only
  bool no_plots = false;
  std::string python;  ///< interpreter for the plots, empty: default_python()
};

std::string g(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

std::string quality_line(const FitQuality& q, const std::string& unit) {
  return "R^2 = " + g(q.r_squared) + ", RMS residual " + g(q.rms_residual) + " " + unit + " (" +
         g(100.0 * q.rms_relative_residual) + " % relative), max |residual| " +
         g(q.max_abs_residual) + " " + unit;
}

void add_common_options(CLI::App* sub, CommonArgs& args, const std::string& columns) {
  sub->add_option("--data", args.data, "CSV file with columns " + columns + "; '#' lines skipped")
      ->required();
  sub->add_option("--out", args.out,
                  "Directory for calibration.json, fit CSVs and PNG plots (created if needed)");
  sub->add_flag("--no-figures", args.no_plots, "With --out: write JSON and CSVs but no PNG plots");
  sub->add_option("--python", args.python,
                  "Python interpreter for the plots (default: /usr/bin/python3 if it exists, "
                  "else python3)");
}

void print_block(const nlohmann::ordered_json& report) {
  std::cout << "joint law (JSON): " << report["joint_law"]["json"].dump() << "\n";
  std::cout << "joint law (TOML): " << report["joint_law"]["toml"].get<std::string>() << "\n";
}

void write_json(const std::filesystem::path& path, const nlohmann::ordered_json& report) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path.string());
  out << report.dump(2) << "\n";
  if (!out) throw std::runtime_error("error while writing " + path.string());
}

// Writes the outputs of a finished calibration into args.out: CSVs, calibration.json, then the
// plots, and calibration.json again with the figures listed.
void write_outputs(
    const CommonArgs& args, nlohmann::ordered_json report,
    const std::function<std::vector<std::string>(const std::filesystem::path&)>& write_csv) {
  const std::filesystem::path dir(args.out);
  std::filesystem::create_directories(dir);
  report["files"] = write_csv(dir);
  report["figures"] = nlohmann::ordered_json::array();
  report["plots"] = args.no_plots ? "not requested (--no-figures)" : "pending";
  write_json(dir / "calibration.json", report);
  if (!args.no_plots) {
    const std::string python = args.python.empty() ? default_python() : args.python;
    const PlotOutcome plots = run_calibration_plots(dir, python);
    report["figures"] = plots.files;
    report["plots"] = plots.written ? "written" : "not written: " + plots.message;
    write_json(dir / "calibration.json", report);
    if (!plots.written) {
      std::cerr << "blockdem: warning: no PNG plots written: " << plots.message
                << "; calibration.json and the CSV files are written\n";
    }
  }
  std::cout << "outputs written to " << dir.string() << "/: calibration.json";
  for (const auto& f : report["files"]) std::cout << ", " << f.get<std::string>();
  for (const auto& f : report["figures"]) std::cout << ", " << f.get<std::string>();
  std::cout << "\n";
}

// Runs `body`, turning unusable input into a message and exit code 2.
void run_checked(const std::function<void()>& body) {
  try {
    body();
    set_exit_code(0);
  } catch (const CalibrationError& e) {
    std::cerr << "blockdem: error: " << e.what() << "\n";
    set_exit_code(2);
  }
}

std::string data_line(const std::string& source, const std::vector<std::string>& comments,
                      std::size_t rows) {
  std::string text = source + ", " + std::to_string(rows) + " rows";
  for (const auto& c : comments) {
    if (c.find("SYNTHETIC") != std::string::npos) text += " (SYNTHETIC data)";
  }
  return text;
}

void register_normal(CLI::App* calibrate) {
  CLI::App* sub = calibrate->add_subcommand(
      "normal", "Exponential normal law (eqs 3-4) from a column compression test (Fig 1)");
  auto args = std::make_shared<CommonArgs>();
  auto test = std::make_shared<ColumnTestDef>();
  add_common_options(sub, *args, "stress_Pa,displacement_m");
  sub->add_option("--modulus", test->modulus, "Young's modulus E of the intact blocks (Pa)")
      ->required();
  sub->add_option("--height", test->height, "Total height H of the column's intact blocks (m)")
      ->required();
  sub->add_option("--joints", test->joints,
                  "Number of equivalent joints N (3 for a three-block column: two joints and "
                  "the two end interfaces)")
      ->required();
  sub->callback([args, test]() {
    run_checked([&]() {
      test->validate();
      const ColumnCompressionData data = read_column_compression(args->data);
      const NormalCalibration cal = calibrate_normal(data, *test);
      nlohmann::ordered_json report = normal_report(data, cal);
      report["program"] = std::string("blockdem ") + version();
      std::cout << "calibrate normal: " << data_line(data.source, data.comments, data.stress.size())
                << "\n  joint closure u = (d - sigma H / E) / N with E = " << g(test->modulus)
                << " Pa, H = " << g(test->height) << " m, N = " << test->joints
                << "\n  exponential sigma = a [exp(b u) - 1]: a = " << g(cal.exponential.a)
                << " Pa, b = " << g(cal.exponential.b) << " 1/m"
                << "\n    standard errors a " << g(cal.a_standard_error) << " Pa, b "
                << g(cal.b_standard_error) << " 1/m; 95% intervals a [" << g(cal.a_lower95) << ", "
                << g(cal.a_upper95) << "] Pa, b [" << g(cal.b_lower95) << ", " << g(cal.b_upper95)
                << "] 1/m"
                << "\n    tangent form k_n = k0 + c sigma: k0 = a b = "
                << g(cal.exponential.a * cal.exponential.b)
                << " Pa/m, c = b = " << g(cal.exponential.b) << " 1/m"
                << "\n    " << quality_line(cal.exponential_quality, "m")
                << "\n  linear sigma = k u (comparison): k = " << g(cal.linear.stiffness)
                << " Pa/m\n    " << quality_line(cal.linear_quality, "m") << "\n";
      print_block(report);
      if (!args->out.empty()) {
        write_outputs(*args, report, [&](const std::filesystem::path& dir) {
          return write_normal_csv(dir, data, cal);
        });
      }
    });
  });
}

void register_shear(CLI::App* calibrate) {
  CLI::App* sub = calibrate->add_subcommand(
      "shear",
      "Shear power laws u_peak = C sigma_n^D (eq 6), k_s,initial = A sigma_n^B (eq 7) from direct "
      "shear curves through eq 5 (Figs 2-3)");
  auto args = std::make_shared<CommonArgs>();
  add_common_options(sub, *args, "normal_stress_Pa,shear_displacement_m,shear_stress_Pa");
  sub->callback([args]() {
    run_checked([&]() {
      const DirectShearData data = read_direct_shear(args->data);
      const ShearCalibration cal = calibrate_shear(data);
      nlohmann::ordered_json report = shear_report(data, cal);
      report["program"] = std::string("blockdem ") + version();
      std::size_t rows = 0;
      for (const auto& c : data.curves) rows += c.displacement.size();
      std::cout << "calibrate shear: " << data_line(data.source, data.comments, rows) << "\n";
      for (const PeakCurveFit& fit : cal.curves) {
        std::cout << "  sigma_n = " << g(fit.normal_stress)
                  << " Pa: k_s,initial = " << g(fit.initial_stiffness)
                  << " Pa/m, u_peak = " << g(fit.peak_displacement) << " m"
                  << (fit.peak_within_data ? "" : " (beyond the data: extrapolated)")
                  << ", tau_peak = " << g(fit.peak_shear_stress) << " Pa, " << fit.points_used
                  << " rows, " << quality_line(fit.quality, "Pa") << "\n";
      }
      std::cout << "  eq 7: k_s,initial = A sigma_n^B, A = " << g(cal.stiffness.coefficient)
                << ", B = " << g(cal.stiffness.exponent)
                << " (R^2 of log = " << g(cal.stiffness.r_squared) << ")\n"
                << "  eq 6: u_peak = C sigma_n^D, C = " << g(cal.peak.coefficient)
                << ", D = " << g(cal.peak.exponent) << " (R^2 of log = " << g(cal.peak.r_squared)
                << ")\n  Mohr-Coulomb cap of the degrading law: friction_deg = "
                << g(cal.law.strength.friction_deg()) << "\n";
      print_block(report);
      std::cout << "next: " << report["next_step"].get<std::string>() << "\n";
      if (!args->out.empty()) {
        write_outputs(*args, report, [&](const std::filesystem::path& dir) {
          return write_shear_csv(dir, data, cal);
        });
      }
    });
  });
}

void register_cy(CLI::App* calibrate) {
  CLI::App* sub = calibrate->add_subcommand(
      "cy",
      "Continuously-yielding shear law (eq 8: mu0 and u_peak = C sigma_n^D) fitted through the "
      "engine's kernel (Fig 4)");
  auto args = std::make_shared<CommonArgs>();
  auto stiffness = std::make_shared<CyStiffnessDef>();
  add_common_options(sub, *args, "normal_stress_Pa,shear_displacement_m,shear_stress_Pa");
  sub->add_option("--stiffness-coefficient", stiffness->stiffness_coefficient,
                  "A of eq 7, k_s,initial = A sigma_n^B (from `blockdem calibrate shear`)")
      ->required();
  sub->add_option("--stiffness-exponent", stiffness->stiffness_exponent,
                  "B of eq 7 (from `blockdem calibrate shear`)")
      ->required();
  sub->callback([args, stiffness]() {
    run_checked([&]() {
      stiffness->validate();
      const DirectShearData data = read_direct_shear(args->data);
      const CyCalibration cal = calibrate_continuously_yielding(data, *stiffness);
      nlohmann::ordered_json report = cy_report(data, cal);
      report["program"] = std::string("blockdem ") + version();
      std::size_t rows = 0;
      for (const auto& c : data.curves) rows += c.displacement.size();
      std::cout << "calibrate cy: " << data_line(data.source, data.comments, rows) << "\n"
                << "  k_s,initial = A sigma_n^B held at A = " << g(stiffness->stiffness_coefficient)
                << ", B = " << g(stiffness->stiffness_exponent) << "\n"
                << "  eq 8: mu0 = tan(phi) = " << g(cal.friction_coefficient)
                << ", friction_deg = " << g(cal.law.strength.friction_deg()) << "\n"
                << "  eq 6: u_peak = C sigma_n^D, C = " << g(cal.law.power_laws.peak_coefficient)
                << ", D = " << g(cal.law.power_laws.peak_exponent) << "\n"
                << "  all rows, in tau / sigma_n: " << quality_line(cal.quality, "(-)") << "\n";
      for (const CyCurveFit& fit : cal.curves) {
        std::cout << "  sigma_n = " << g(fit.normal_stress)
                  << " Pa: " << quality_line(fit.quality, "Pa") << "\n";
      }
      print_block(report);
      if (!args->out.empty()) {
        write_outputs(*args, report, [&](const std::filesystem::path& dir) {
          return write_cy_csv(dir, data, cal);
        });
      }
    });
  });
}

}  // namespace

void register_calibrate(CLI::App& app) {
  CLI::App* calibrate =
      app.add_subcommand("calibrate", "Joint laws from laboratory data (docs/calibration.md)")
          ->require_subcommand(1);
  register_normal(calibrate);
  register_shear(calibrate);
  register_cy(calibrate);
}

}  // namespace blockdem::cli
