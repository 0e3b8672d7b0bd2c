// `blockdem lab compression|shear|figures`: the virtual laboratory. Drives the joint-law kernels
// along compression and direct-shear paths (optionally also on a two-block engine run), and draws
// the joint-law figures of Boon, Houlsby & Utili (2015), Figs 1(b), 2, 3, 4. See docs/lab.md.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <iostream>
#include <memory>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>

#include "blockdem/contact/law_params.hpp"
#include "blockdem/io/output_error.hpp"
#include "blockdem/lab/compression_test.hpp"
#include "blockdem/lab/joint_law_figures.hpp"
#include "blockdem/lab/lab_report.hpp"
#include "blockdem/lab/law_spec.hpp"
#include "blockdem/lab/shear_test.hpp"
#include "blockdem/world/contact_mode.hpp"
#include "commands.hpp"
#include "figures.hpp"

namespace blockdem::cli {
namespace {

constexpr const char* kDefaultNormal = "law=exponential,preset=eq4";
constexpr const char* kDefaultShear = "law=continuously_yielding";
constexpr const char* kPlotScript = "plot_joint_laws.py";

// Exit codes: 0 success, 1 a run or figure failed, 2 invalid input.
constexpr int kFailed = 1;
constexpr int kInvalidInput = 2;
constexpr int kSystem = 4;  ///< a file the system would not let it write, or memory

struct CompressionArgs {
  std::string normal = kDefaultNormal;
  double max_closure = 0.0;  ///< (m)
  double max_stress = 0.0;   ///< (Pa)
  int cycles = 1;
  int steps = 50;
  bool dem = false;
  std::string mode = "boon2012";
  std::string out;
  bool plot = true;
};

struct ShearArgs {
  std::string shear = kDefaultShear;
  std::string normal = kDefaultNormal;
  double normal_stress = 0.0;     ///< (Pa)
  double max_displacement = 0.0;  ///< (m)
  int steps = 2000;
  int cycles = 0;
  bool dem = false;
  std::string mode = "boon2012";
  std::string out;
  bool plot = true;
};

struct FiguresArgs {
  std::string out;
  bool plot = true;
};

/// The two-block rig of --dem, in the contact mode given by --mode.
TwoBlockRigDef rig_for(const std::string& mode) {
  TwoBlockRigDef rig;
  rig.contact_mode = *parse_contact_mode(mode);  // --mode checks the name
  return rig;
}

/// Creates the output folder; the files and an optional figure go in it.
std::filesystem::path prepare_out(const std::string& out) {
  const std::filesystem::path dir(out);
  std::filesystem::create_directories(dir);
  return dir;
}

/// Draws one figure with the plotting script; records the outcome in `summary`.
bool plot(const std::vector<std::string>& args, const std::filesystem::path& png,
          nlohmann::ordered_json& summary) {
  std::string why;
  if (run_plot_script(kPlotScript, args, why)) {
    summary["files"].push_back(png.string());
    return true;
  }
  summary["figure_error"] = why;
  std::cerr << "blockdem: error: lab: no figure: " << why << "\n";
  return false;
}

int run_compression(const CompressionArgs& a, bool max_closure_given, bool max_stress_given) {
  CompressionTestDef def;
  def.law = normal_law_from_spec(a.normal);
  if (max_closure_given) def.max_closure = a.max_closure;
  if (max_stress_given) def.max_stress = a.max_stress;
  def.cycles = a.cycles;
  def.steps_per_branch = a.steps;
  def.validate();

  const CompressionCurve kernel = run_compression_kernel(def);
  std::optional<DemCompressionRun> dem;
  if (a.dem) dem = run_compression_dem(def, kernel, rig_for(a.mode));
  const DemCompressionRun* dem_ptr = dem ? &*dem : nullptr;

  nlohmann::ordered_json summary = compression_summary(def, kernel, dem_ptr);
  int code = 0;
  if (dem && !dem->converged) {
    std::cerr << "blockdem: error: lab compression: the DEM run did not converge: " << dem->message
              << "\n";
    code = kFailed;
  }
  if (!a.out.empty()) {
    const std::filesystem::path dir = prepare_out(a.out);
    const std::filesystem::path csv = dir / "compression.csv";
    write_compression_csv(csv, kernel, dem_ptr);
    summary["files"] = nlohmann::ordered_json::array({csv.string()});
    if (a.plot) {
      const std::filesystem::path png = dir / "compression.png";
      if (!plot({"compression", csv.string(), png.string(), "normal law: " + a.normal}, png,
                summary))
        code = kFailed;
    }
  }
  std::cout << summary.dump(2) << "\n";
  return code;
}

int run_shear(const ShearArgs& a) {
  ShearTestDef def;
  def.law = shear_law_from_spec(a.shear);
  const NormalLaw normal = normal_law_from_spec(a.normal);
  def.normal_stress = a.normal_stress;
  def.max_displacement = a.max_displacement;
  def.steps = a.steps;
  def.cycles = a.cycles;
  def.validate();

  const ShearCurve kernel = run_shear_kernel(def);
  std::optional<DemShearRun> dem;
  if (a.dem) dem = run_shear_dem(def, normal, kernel, rig_for(a.mode));
  const DemShearRun* dem_ptr = dem ? &*dem : nullptr;

  nlohmann::ordered_json summary = shear_summary(def, normal, kernel, dem_ptr);
  int code = 0;
  if (dem && !dem->settled) {
    std::cerr << "blockdem: error: lab shear: the DEM run did not settle: " << dem->message << "\n";
    code = kFailed;
  }
  if (!a.out.empty()) {
    const std::filesystem::path dir = prepare_out(a.out);
    const std::filesystem::path csv = dir / "shear.csv";
    write_shear_csv(csv, kernel, dem_ptr);
    summary["files"] = nlohmann::ordered_json::array({csv.string()});
    if (a.plot) {
      const std::filesystem::path png = dir / "shear.png";
      const std::string label =
          "shear law: " + a.shear + ";  sigma_n = " + format_value(a.normal_stress) + " Pa";
      if (!plot({"shear", csv.string(), png.string(), label}, png, summary)) code = kFailed;
    }
  }
  std::cout << summary.dump(2) << "\n";
  return code;
}

int run_figures(const FiguresArgs& a) {
  const JointLawFiguresDef def;
  const std::filesystem::path dir = prepare_out(a.out);
  nlohmann::ordered_json summary;
  summary["figures"] = "Boon, Houlsby & Utili (2015), Figs 1(b), 2, 3, 4";
  summary["files"] = nlohmann::ordered_json::array();
  for (const auto& path : write_joint_law_figure_data(dir, def)) {
    summary["files"].push_back(path.string());
  }
  int code = 0;
  if (a.plot) {
    std::string why;
    if (run_plot_script(kPlotScript, {"figures", dir.string()}, why)) {
      for (const char* png : {"fig1b_normal_laws.png", "fig2_shear_stiffness.png",
                              "fig3_initial_shear_stiffness.png", "fig4_shear_stress.png"}) {
        summary["files"].push_back((dir / png).string());
      }
    } else {
      summary["figure_error"] = why;
      std::cerr << "blockdem: error: lab figures: no figures: " << why << "\n";
      code = kFailed;
    }
  }
  std::cout << summary.dump(2) << "\n";
  return code;
}

/// Runs a subcommand body: invalid input (a message naming the law and the parameter) exits with
/// kInvalidInput, a file or memory the system refused with kSystem, any other failure with
/// kFailed.
template <class Body>
void guarded(const char* name, Body&& body) {
  try {
    set_exit_code(body());
  } catch (const std::invalid_argument& e) {
    std::cerr << "blockdem: error: lab " << name << ": " << e.what() << "\n";
    set_exit_code(kInvalidInput);
  } catch (const std::bad_alloc&) {
    std::cerr << "blockdem: error: lab " << name << ": out of memory\n";
    set_exit_code(kSystem);
  } catch (const OutputError& e) {
    std::cerr << "blockdem: error: lab " << name << ": " << e.what() << "\n";
    set_exit_code(kSystem);
  } catch (const std::filesystem::filesystem_error& e) {
    std::cerr << "blockdem: error: lab " << name << ": " << e.what() << "\n";
    set_exit_code(kSystem);
  } catch (const std::exception& e) {
    std::cerr << "blockdem: error: lab " << name << ": " << e.what() << "\n";
    set_exit_code(kFailed);
  }
}

}  // namespace

void register_lab(CLI::App& app) {
  CLI::App* lab =
      app.add_subcommand("lab",
                         "Virtual laboratory: joint compression and shear tests, joint-law "
                         "figures (docs/lab.md)")
          ->require_subcommand(1);
  const std::string normal_help =
      "Normal law as on a scenario's joint-law table, e.g. \"law=linear,stiffness=10e9\" or "
      "\"law=exponential,preset=eq3\" (SI units; default: " +
      std::string(kDefaultNormal) + ")";

  // lab compression
  {
    auto a = std::make_shared<CompressionArgs>();
    CLI::App* cmd = lab->add_subcommand(
        "compression", "Closure path with loading and unloading through the normal law: sigma-u");
    cmd->add_option("--normal", a->normal, normal_help);
    CLI::Option* closure =
        cmd->add_option("--max-closure", a->max_closure, "Largest closure of the path (m)");
    CLI::Option* stress =
        cmd->add_option("--max-stress", a->max_stress, "Normal stress at the largest closure (Pa)");
    closure->excludes(stress);
    cmd->add_option("--cycles", a->cycles, "Load-unload cycles (default 1)");
    cmd->add_option("--steps", a->steps,
                    "Closure increments per loading or unloading branch (default 50)");
    cmd->add_flag("--dem", a->dem,
                  "Also run the path on two blocks in the engine (load levels to equilibrium)");
    cmd->add_option("--mode", a->mode, "Contact mode of --dem (default boon2012, the paper's)")
        ->check(CLI::IsMember(contact_mode_names()));
    cmd->add_option("--out", a->out, "Folder for compression.csv and compression.png");
    cmd->add_flag("!--no-figures", a->plot, "With --out: write the CSV only");
    cmd->callback([a, closure, stress] {
      guarded("compression", [&] {
        if (closure->count() + stress->count() != 1) {
          throw std::invalid_argument("give one of --max-closure (m) and --max-stress (Pa)");
        }
        return run_compression(*a, closure->count() > 0, stress->count() > 0);
      });
    });
  }

  // lab shear
  {
    auto a = std::make_shared<ShearArgs>();
    CLI::App* cmd = lab->add_subcommand(
        "shear", "Direct shear at constant normal stress: tau, tau/sigma_n, plastic slip vs u_s");
    cmd->add_option("--shear", a->shear,
                    "Shear law as on a scenario's joint-law table, e.g. "
                    "\"law=continuously_yielding,friction_deg=40\" (SI units, degrees; default: " +
                        std::string(kDefaultShear) + ")");
    cmd->add_option("--normal", a->normal, normal_help + "; used by --dem only");
    cmd->add_option("--normal-stress", a->normal_stress, "Constant normal stress sigma_n (Pa)")
        ->required();
    cmd->add_option("--max-shear-displacement", a->max_displacement,
                    "Largest shear displacement u_s of the path (m)")
        ->required();
    cmd->add_option("--steps", a->steps,
                    "Increments per max-shear-displacement of travel (default 2000)");
    cmd->add_option("--cycles", a->cycles,
                    "0: monotonic (default); N: N cycles 0 -> +max -> -max -> 0");
    cmd->add_flag("--dem", a->dem,
                  "Also run the path on two blocks in the engine (prescribed shear velocity)");
    cmd->add_option("--mode", a->mode, "Contact mode of --dem (default boon2012, the paper's)")
        ->check(CLI::IsMember(contact_mode_names()));
    cmd->add_option("--out", a->out, "Folder for shear.csv and shear.png");
    cmd->add_flag("!--no-figures", a->plot, "With --out: write the CSV only");
    cmd->callback([a] { guarded("shear", [&] { return run_shear(*a); }); });
  }

  // lab figures
  {
    auto a = std::make_shared<FiguresArgs>();
    CLI::App* cmd = lab->add_subcommand(
        "figures",
        "Joint-law figures in the style of the paper's Figs 1(b), 2, 3, 4 (CSV and PNG)");
    cmd->add_option("--out", a->out, "Output folder")->required();
    cmd->add_flag("!--no-figures", a->plot, "Write the CSV files only");
    cmd->callback([a] { guarded("figures", [&] { return run_figures(*a); }); });
  }
}

}  // namespace blockdem::cli
