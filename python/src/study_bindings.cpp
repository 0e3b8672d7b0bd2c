// The study commands from Python, as `blockdem analytic`, `lab`, `calibrate` and `reproduce` run
// them, returning their JSON reports as dicts. Figures are left to the caller (matplotlib): the
// module starts no program.
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <chrono>
#include <fstream>
#include <optional>
#include <thread>

#include "bindings.hpp"
#include "blockdem/analysis/voussoir_analytic.hpp"
#include "blockdem/calibration/calibration_data.hpp"
#include "blockdem/calibration/calibration_report.hpp"
#include "blockdem/calibration/cy_calibration.hpp"
#include "blockdem/calibration/normal_calibration.hpp"
#include "blockdem/calibration/shear_calibration.hpp"
#include "blockdem/lab/compression_test.hpp"
#include "blockdem/lab/lab_report.hpp"
#include "blockdem/lab/law_spec.hpp"
#include "blockdem/lab/shear_test.hpp"
#include "blockdem/numerics/units.hpp"
#include "blockdem/studies/boon2015/reproduce.hpp"
#include "blockdem/world/contact_mode.hpp"

namespace py = pybind11;

namespace blockdem::python {
namespace {

template <class Json>
py::object to_python(const Json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

/// Writes a calibration's CSVs and calibration.json into `out` (created), as `blockdem calibrate
/// --out DIR --no-figures`.
template <class Report, class WriteCsv>
void write_calibration(const std::filesystem::path& out, Report report, WriteCsv write_csv) {
  std::filesystem::create_directories(out);
  report["files"] = write_csv(out);
  report["figures"] = nlohmann::ordered_json::array();
  report["plots"] = "not drawn by the Python module";
  std::ofstream f(out / "calibration.json");
  f << report.dump(2) << "\n";
  if (!f) throw std::runtime_error("cannot write " + (out / "calibration.json").string());
}

/// The words quoted and listed: "a", "b" or "c".
std::string quoted_choices(const std::vector<std::string>& words) {
  std::string list;
  for (std::size_t i = 0; i < words.size(); ++i) {
    if (i > 0) list += i + 1 == words.size() ? " or " : ", ";
    list += "\"" + words[i] + "\"";
  }
  return list;
}

TwoBlockRigDef rig_for(const std::string& mode) {
  const std::optional<ContactMode> parsed = parse_contact_mode(mode);
  if (!parsed)
    throw py::value_error("mode: must be " + quoted_choices(contact_mode_names()) + ", got \"" +
                          mode + "\"");
  TwoBlockRigDef rig;
  rig.contact_mode = *parsed;
  return rig;
}

/// The analytical voussoir beam (Diederichs & Kaiser 1999).
void bind_analytic(py::module_& m) {
  m.def(
      "analytic_voussoir",
      [](double span, double depth, double density, double gravity, double modulus,
         std::optional<double> width, std::optional<double> compressive_strength,
         std::optional<double> friction_deg) {
        for (auto [name, v] : {std::pair{"density", density}, std::pair{"gravity", gravity}}) {
          if (!(v > 0.0 && std::isfinite(v)))
            throw py::value_error(std::string("analytic voussoir: ") + name +
                                  " must be positive and finite");
        }
        VoussoirBeamDef beam;
        beam.span = span;
        beam.depth = depth;
        beam.unit_weight = density * gravity;
        beam.rock_mass_modulus = modulus;
        beam.width = width;
        beam.compressive_strength = compressive_strength;
        if (friction_deg) beam.friction_angle = deg_to_rad(*friction_deg);
        beam.validate();
        nlohmann::ordered_json report = voussoir_report_json(beam, solve_voussoir_beam(beam));
        report["inputs"]["density_kg_m3"] = density;
        report["inputs"]["gravity_m_s2"] = gravity;
        if (friction_deg) report["inputs"]["friction_deg"] = *friction_deg;
        return to_python(report);
      },
      py::kw_only(), py::arg("span"), py::arg("depth"), py::arg("density"), py::arg("gravity"),
      py::arg("modulus"), py::arg("width") = py::none(),
      py::arg("compressive_strength") = py::none(), py::arg("friction_deg") = py::none(),
      "The voussoir beam of Diederichs & Kaiser (1999), as `blockdem analytic voussoir`: span, "
      "depth (m), density (kg/m^3), gravity (m/s^2), modulus E_rm (Pa); optional width (m), "
      "compressive_strength (Pa), friction_deg. Returns the JSON report as a dict.");
}

/// The virtual laboratory: compression and shear along displacement paths.
void bind_lab(py::module_& m) {
  m.def(
      "lab_compression",
      [](const std::string& normal, std::optional<double> max_closure,
         std::optional<double> max_stress, int cycles, int steps, bool dem, const std::string& mode,
         std::optional<std::filesystem::path> out) {
        CompressionTestDef def;
        def.law = normal_law_from_spec(normal);
        if (max_closure) def.max_closure = *max_closure;
        if (max_stress) def.max_stress = *max_stress;
        def.cycles = cycles;
        def.steps_per_branch = steps;
        def.validate();
        const TwoBlockRigDef rig = rig_for(mode);
        py::gil_scoped_release free;
        const CompressionCurve kernel = run_compression_kernel(def);
        std::optional<DemCompressionRun> run;
        if (dem) run = run_compression_dem(def, kernel, rig);
        const DemCompressionRun* dem_ptr = run ? &*run : nullptr;
        nlohmann::ordered_json summary = compression_summary(def, kernel, dem_ptr);
        if (out) {
          std::filesystem::create_directories(*out);
          write_compression_csv(*out / "compression.csv", kernel, dem_ptr);
          summary["files"] = nlohmann::ordered_json::array({(*out / "compression.csv").string()});
        }
        py::gil_scoped_acquire hold;
        return to_python(summary);
      },
      py::kw_only(), py::arg("normal") = "law=exponential,preset=eq4",
      py::arg("max_closure") = py::none(), py::arg("max_stress") = py::none(),
      py::arg("cycles") = 1, py::arg("steps") = 50, py::arg("dem") = false,
      py::arg("mode") = "boon2012", py::arg("out") = py::none(),
      "A compression path of a normal law, as `blockdem lab compression` (the law as its "
      "--normal text). With out: compression.csv there. Returns the JSON summary.");

  m.def(
      "lab_shear",
      [](const std::string& shear, const std::string& normal, double normal_stress,
         double max_displacement, int steps, int cycles, bool dem, const std::string& mode,
         std::optional<std::filesystem::path> out) {
        ShearTestDef def;
        def.law = shear_law_from_spec(shear);
        const NormalLaw normal_law = normal_law_from_spec(normal);
        def.normal_stress = normal_stress;
        def.max_displacement = max_displacement;
        def.steps = steps;
        def.cycles = cycles;
        def.validate();
        const TwoBlockRigDef rig = rig_for(mode);
        py::gil_scoped_release free;
        const ShearCurve kernel = run_shear_kernel(def);
        std::optional<DemShearRun> run;
        if (dem) run = run_shear_dem(def, normal_law, kernel, rig);
        const DemShearRun* dem_ptr = run ? &*run : nullptr;
        nlohmann::ordered_json summary = shear_summary(def, normal_law, kernel, dem_ptr);
        if (out) {
          std::filesystem::create_directories(*out);
          write_shear_csv(*out / "shear.csv", kernel, dem_ptr);
          summary["files"] = nlohmann::ordered_json::array({(*out / "shear.csv").string()});
        }
        py::gil_scoped_acquire hold;
        return to_python(summary);
      },
      py::kw_only(), py::arg("shear") = "law=continuously_yielding",
      py::arg("normal") = "law=exponential,preset=eq4", py::arg("normal_stress"),
      py::arg("max_displacement"), py::arg("steps") = 2000, py::arg("cycles") = 0,
      py::arg("dem") = false, py::arg("mode") = "boon2012", py::arg("out") = py::none(),
      "A constant-normal-stress shear path, as `blockdem lab shear`: normal_stress (Pa), "
      "max_displacement (m). With out: shear.csv there. Returns the JSON summary.");
}

/// Joint-law calibration from laboratory curves.
void bind_calibration(py::module_& m) {
  m.def(
      "calibrate_normal",
      [](const std::filesystem::path& data, double modulus, double height, int joints,
         std::optional<std::filesystem::path> out) {
        ColumnTestDef test;
        test.modulus = modulus;
        test.height = height;
        test.joints = joints;
        test.validate();
        const ColumnCompressionData d = read_column_compression(data);
        const NormalCalibration cal = calibrate_normal(d, test);
        nlohmann::ordered_json report = normal_report(d, cal);
        if (out)
          write_calibration(*out, report,
                            [&](const auto& dir) { return write_normal_csv(dir, d, cal); });
        return to_python(report);
      },
      py::arg("data"), py::kw_only(), py::arg("modulus"), py::arg("height"), py::arg("joints"),
      py::arg("out") = py::none(),
      "The exponential normal law (eqs 3-4) from a column compression CSV (stress_Pa, "
      "displacement_m), as `blockdem calibrate normal`. Returns the report.");

  m.def(
      "calibrate_shear",
      [](const std::filesystem::path& data, std::optional<std::filesystem::path> out) {
        const DirectShearData d = read_direct_shear(data);
        const ShearCalibration cal = calibrate_shear(d);
        nlohmann::ordered_json report = shear_report(d, cal);
        if (out)
          write_calibration(*out, report,
                            [&](const auto& dir) { return write_shear_csv(dir, d, cal); });
        return to_python(report);
      },
      py::arg("data"), py::kw_only(), py::arg("out") = py::none(),
      "The degrading shear law (eqs 5-7) from direct shear curves, as `blockdem calibrate "
      "shear`. Returns the report.");

  m.def(
      "calibrate_continuously_yielding",
      [](const std::filesystem::path& data, double stiffness_coefficient, double stiffness_exponent,
         std::optional<std::filesystem::path> out) {
        CyStiffnessDef k;
        k.stiffness_coefficient = stiffness_coefficient;
        k.stiffness_exponent = stiffness_exponent;
        k.validate();
        const DirectShearData d = read_direct_shear(data);
        const CyCalibration cal = calibrate_continuously_yielding(d, k);
        nlohmann::ordered_json report = cy_report(d, cal);
        if (out)
          write_calibration(*out, report,
                            [&](const auto& dir) { return write_cy_csv(dir, d, cal); });
        return to_python(report);
      },
      py::arg("data"), py::kw_only(), py::arg("stiffness_coefficient") = 1.9e6,
      py::arg("stiffness_exponent") = 0.7, py::arg("out") = py::none(),
      "The continuously-yielding law (eqs 8-16) from direct shear curves, as `blockdem "
      "calibrate continuously_yielding`. Returns the report.");
}

/// The reproduction of Boon et al. (2015).
void bind_reproduce(py::module_& m) {
  m.def(
      "reproduce_boon2015",
      [](const std::filesystem::path& out, const std::filesystem::path& scenarios,
         const std::vector<std::string>& cases, const std::string& modes, int jobs,
         const std::function<void(const std::string&)>& progress) {
        Boon2015Selection sel;
        sel.scenarios = scenarios;
        sel.cases = cases;
        sel.modes = contact_modes_selected(modes);
        if (sel.modes.empty()) {
          std::vector<std::string> words = contact_mode_names();
          words.insert(words.begin(), "both");
          throw py::value_error("modes: must be " + quoted_choices(words));
        }
        std::vector<Boon2015CaseRun> runs = select_boon2015_cases(sel);
        const int threads =
            jobs > 0 ? jobs : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
        const auto wall0 = std::chrono::steady_clock::now();
        {
          py::gil_scoped_release free;
          Boon2015Callbacks callbacks;
          callbacks.case_done = [&](const Boon2015CaseRun& r) {
            if (!progress) return;
            py::gil_scoped_acquire hold;
            progress(r.spec.id + ": " + to_string(r.result.status) + " after " +
                     std::to_string(r.result.steps) + " steps");
          };
          run_boon2015_cases(runs, out, threads, callbacks);
          const double wall =
              std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
          write_boon2015_report(out, runs, {}, "figures are drawn by `blockdem reproduce`", wall);
        }
        py::list result;
        for (const auto& r : runs) {
          py::dict d;
          d["id"] = r.spec.id;
          d["status"] = to_string(r.result.status);
          d["message"] = r.result.message;
          d["exit_code"] = r.result.exit_code;
          d["steps"] = r.result.steps;
          d["wall_time"] = r.result.wall_time;
          d["summary"] = to_python(r.result.summary);
          result.append(d);
        }
        return result;
      },
      py::arg("out"), py::kw_only(), py::arg("scenarios"),
      py::arg("cases") = std::vector<std::string>{}, py::arg("modes") = "both", py::arg("jobs") = 0,
      py::arg("progress") = nullptr,
      "Runs the cases of Boon et al. (2015) from the case files in `scenarios` into out/<id> and "
      "writes out/report.md (without figures), as `blockdem reproduce boon2015 --no-figures`. "
      "Returns one dict per case (id, status, message, exit_code, steps, wall_time, summary).");
}

}  // namespace

void bind_studies(py::module_& m) {
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const CalibrationError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });

  bind_analytic(m);
  bind_lab(m);
  bind_calibration(m);
  bind_reproduce(m);
}

}  // namespace blockdem::python
