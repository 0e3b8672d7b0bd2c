// report.md: a run's results for a reader, from its summary.json and the figures beside it.
#include "blockdem/run/run_report.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "blockdem/io/atomic_file.hpp"
#include "blockdem/numerics/number_text.hpp"

namespace blockdem {
namespace {

using nlohmann::json;

/// `j[key]` printed with `format`, or "-" where it is missing or not a number.
std::string num(const json& j, const char* key, const char* format = "%.4g") {
  if (!j.is_object() || !j.contains(key) || !j[key].is_number()) return "-";
  return number_text(j[key].get<double>(), format);
}

std::string text(const json& j, const char* key) {
  if (!j.is_object() || !j.contains(key) || !j[key].is_string()) return "";
  return j[key].get<std::string>();
}

/// A table cell: '|' and line breaks would end the cell or the row.
std::string cell(std::string s) {
  for (char& c : s)
    if (c == '|' || c == '\n') c = ' ';
  return s;
}

std::string yes_no(const json& j, const char* key) {
  if (!j.is_object() || !j.contains(key) || !j[key].is_boolean()) return "-";
  return j[key].get<bool>() ? "yes" : "no";
}

/// How stage entry `s` ended, in a few words.
std::string stage_end(const json& s) {
  if (s.contains("factor_of_safety") && s["factor_of_safety"].is_number())
    return "factor of safety " + num(s, "factor_of_safety");
  const std::string status = text(s, "status");
  if (!status.empty() && status != "completed") return status;
  if (s.contains("converged") && s["converged"].is_boolean())
    return s["converged"].get<bool>() ? "done" : "not converged";
  return "-";
}

void stages_section(std::ostringstream& o, const json& summary) {
  const json& stages = summary.value("stages", json::array());
  if (stages.empty()) return;
  o << "## Stages\n\n"
    << "| # | stage | steps | ended | in equilibrium | unbalanced-force ratio | "
       "kinetic-energy ratio | contacts | broken bonds |\n"
    << "|---|---|---|---|---|---|---|---|---|\n";
  int k = 0;
  for (const json& s : stages) {
    o << "| " << ++k << " | " << cell(text(s, "name")) << " | " << num(s, "steps", "%.0f") << " | "
      << stage_end(s) << " | " << yes_no(s, "in_equilibrium") << " | "
      << num(s, "unbalanced_force_ratio", "%.3g") << " | " << num(s, "kinetic_energy_ratio", "%.3g")
      << " | " << num(s, "contacts", "%.0f") << " | " << num(s, "broken_bonds", "%.0f") << " |\n";
  }
  o << "\n\"in equilibrium\": the stage's unbalanced-force and kinetic-energy ratios at its end "
       "meet its tolerances, whatever its kind.\n";
  for (const json& s : stages) {
    const std::string message = text(s, "message");
    if (!message.empty()) o << "\n- " << text(s, "name") << ": " << message << "\n";
  }
  o << "\n";
}

/// The trials of a search (factor of safety or collapse load) as a table.
void trials_table(std::ostringstream& o, const json& search, const std::string& what) {
  const json& trials = search.value("trials", json::array());
  if (trials.empty()) return;
  o << "| trial | " << what << " | outcome | steps | largest displacement (m) |\n"
    << "|---|---|---|---|---|\n";
  int k = 0;
  for (const json& t : trials)
    o << "| " << ++k << " | " << num(t, "value", "%.6g") << " | " << cell(text(t, "outcome"))
      << " | " << num(t, "steps", "%.0f") << " | " << num(t, "max_displacement_m", "%.3g")
      << " |\n";
  o << "\n";
}

void stability_sections(std::ostringstream& o, const json& summary) {
  if (summary.contains("factor_of_safety") && summary["factor_of_safety"].is_object()) {
    const json& f = summary["factor_of_safety"];
    o << "## Factor of safety\n\n"
      << "Stage '" << text(f, "stage") << "': **F = " << num(f, "value") << "**, between "
      << num(f, "last_stable", "%.6g") << " (the last stable trial) and "
      << num(f, "first_failed", "%.6g") << " (the first that failed), bisected to "
      << num(f, "tolerance", "%.3g")
      << ". Each trial divides the joints' tan(phi), cohesion and tensile strength by its "
         "factor.\n\n";
    trials_table(o, f, "factor");
  }
  if (summary.contains("collapse") && summary["collapse"].is_object()) {
    const json& c = summary["collapse"];
    const std::string unit = text(c, "unit");
    o << "## Collapse\n\n"
      << "Stage '" << text(c, "stage") << "': collapse between " << num(c, "last_stable", "%.6g")
      << " (stable) and " << num(c, "first_failed", "%.6g") << " (failed)"
      << (unit == "g" ? " g" : " of " + unit) << (c.value("interrupted", false) ? ", stopped" : "")
      << ".\n\n";
    trials_table(o, c, unit == "g" ? "gravity (g)" : unit);
  }
}

void key_block_sections(std::ostringstream& o, const json& summary) {
  const json& stages = summary.value("stages", json::array());
  bool moved = false, removable = false;
  for (const json& s : stages) {
    moved = moved || !s.value("key_blocks", json::array()).empty();
    removable = removable || !s.value("removable_blocks", json::array()).empty();
  }
  if (!moved && !removable) return;
  o << "## Key blocks\n\n";
  if (moved) {
    o << "Blocks that moved in an excavation stage (summary.json `key_blocks`):\n\n"
      << "| stage | block | volume (m³) | displacement (m) | speed (m/s) |\n"
      << "|---|---|---|---|---|\n";
    for (const json& s : stages)
      for (const json& b : s.value("key_blocks", json::array()))
        o << "| " << cell(text(s, "name")) << " | " << cell(text(b, "block")) << " | "
          << num(b, "volume_m3") << " | " << num(b, "displacement_m") << " | "
          << num(b, "speed_m_s") << " |\n";
    o << "\n";
  }
  if (removable) {
    o << "Blocks that block theory finds free to move into the opening (summary.json "
         "`removable_blocks`; limit equilibrium with the joints' friction and cohesion):\n\n"
      << "| stage | block | mode | volume (m³) | weight (N) | F | support force (N) |\n"
      << "|---|---|---|---|---|---|---|\n";
    for (const json& s : stages)
      for (const json& b : s.value("removable_blocks", json::array()))
        o << "| " << cell(text(s, "name")) << " | " << cell(text(b, "block")) << " | "
          << cell(text(b, "mode")) << " | " << num(b, "volume_m3") << " | " << num(b, "weight_N")
          << " | " << num(b, "factor_of_safety") << " | " << num(b, "support_force_N") << " |\n";
    o << "\nThe support force is the bolt force that brings a block to the required factor "
         "of safety.\n\n";
  }
}

void dynamic_and_bolt_sections(std::ostringstream& o, const json& summary) {
  for (const json& s : summary.value("stages", json::array())) {
    if (!s.contains("permanent_displacements")) continue;
    const json& p = s["permanent_displacements"];
    o << "## Permanent displacements, stage '" << text(s, "name") << "'\n\n"
      << "Relative to the base (group '" << text(p, "base_group") << "'), the largest ten:\n\n"
      << "| block | relative displacement (m) |\n|---|---|\n";
    std::vector<std::pair<double, std::string>> moved;
    for (const json& b : p.value("blocks", json::array())) {
      const json& u = b.value("relative_displacement_m", json::array());
      double n2 = 0.0;
      for (const json& c : u)
        if (c.is_number()) n2 += c.get<double>() * c.get<double>();
      moved.emplace_back(std::sqrt(n2), text(b, "block"));
    }
    std::stable_sort(moved.begin(), moved.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    for (std::size_t i = 0; i < moved.size() && i < 10; ++i)
      o << "| " << cell(moved[i].second) << " | " << number_text(moved[i].first, "%.4g") << " |\n";
    o << "\n";
  }
  if (summary.contains("bolts") && summary["bolts"].is_object()) {
    const json& b = summary["bolts"];
    o << "## Bolts\n\n"
      << num(b, "installed", "%.0f") << " installed: " << num(b, "intact", "%.0f") << " intact, "
      << num(b, "yielded", "%.0f") << " yielded, " << num(b, "ruptured", "%.0f") << " ruptured, "
      << num(b, "removed", "%.0f") << " removed with their blocks (bolts.csv).\n\n";
  }
}

void energy_section(std::ostringstream& o, const json& summary) {
  if (!summary.contains("energy_J") || !summary["energy_J"].is_object()) return;
  const json& e = summary["energy_J"];
  static const std::vector<std::pair<const char*, const char*>> terms = {
      {"kinetic", "kinetic energy"},
      {"elastic", "elastic energy in the joints"},
      {"gravity_work", "work of gravity"},
      {"load_work", "work of the loads"},
      {"water_work", "of which the ground water's"},
      {"seismic_work", "of which the earthquake's"},
      {"boundary_work", "work of the boundaries"},
      {"friction_dissipation", "dissipated by friction"},
      {"damping_dissipation", "dissipated by damping"},
      {"contact_damping", "dissipated by the contacts' dashpots"},
      {"residual", "residual"}};
  o << "## Energy budget at the end\n\n| term | J |\n|---|---|\n";
  double largest = 0.0;
  for (const auto& [key, label] : terms) {
    if (!e.contains(key)) continue;  // a term the run has not (the dashpots' without them)
    const double v = e.contains(key) && e[key].is_number() ? e[key].get<double>() : 0.0;
    largest = std::max(largest, std::abs(v));
    // The parts of the loads' work that a run without water or earthquake does not have.
    if (v == 0.0 && std::string(label).rfind("of which", 0) == 0) continue;
    o << "| " << label << " | " << num(e, key, "%.6g") << " |\n";
  }
  if (largest > 0.0 && e.contains("residual") && e["residual"].is_number())
    o << "\nThe residual is "
      << number_text(std::abs(e["residual"].get<double>()) / largest, "%.2g")
      << " of the largest term (docs/outputs.md, \"Energy budget\").\n";
  o << "\n";
}

}  // namespace

const std::vector<ReportFigure>& report_figures() {
  static const std::vector<ReportFigure> figures = {
      {"blocks_final.png", "The blocks at the end, coloured by their displacement"},
      {"time_history.png", "The energy budget and the convergence measures in time"},
      {"mechanism.png", "The failure mechanism of the strength reduction and its bisection"},
      {"thrust_vs_g.png", "The beam's thrust against the gravity level"},
      {"midspan_deflection_vs_g.png", "The beam's midspan deflection against the gravity level"},
      {"deflection_profiles.png", "The beam's deflection along its span at each gravity level"},
      {"thrust_line.png", "The beam's line of thrust"}};
  return figures;
}

std::string run_report_text(const json& summary, const std::vector<std::string>& figures,
                            const std::vector<std::string>& warnings) {
  std::ostringstream o;
  const std::string title = text(summary, "title");
  o << "# " << (title.empty() ? "blockdem run" : title) << "\n\n";
  o << "Scenario `" << text(summary, "scenario") << "`. Status **" << text(summary, "status")
    << "**";
  const std::string message = text(summary, "message");
  o << (message.empty() ? "." : ": " + message) << "\n\n";
  o << num(summary, "blocks", "%.0f") << " blocks, contact mode `" << text(summary, "contact_mode")
    << "`, " << num(summary, "steps", "%.0f") << " steps to a model time of "
    << num(summary, "time_s") << " s; contacts at the end: " << num(summary, "contacts", "%.0f")
    << ". The wall time, threads and processes are in summary.json.\n\n";
  stages_section(o, summary);
  stability_sections(o, summary);
  key_block_sections(o, summary);
  dynamic_and_bolt_sections(o, summary);
  energy_section(o, summary);
  bool any = false;
  for (const ReportFigure& f : report_figures()) {
    if (std::find(figures.begin(), figures.end(), f.file) == figures.end()) continue;
    if (!any) o << "## Figures\n\n";
    any = true;
    o << "![" << f.file << "](" << f.file << ")\n\n*" << f.caption << ".*\n\n";
  }
  if (!warnings.empty()) {
    o << (any ? "" : "## Figures\n\n");
    for (const std::string& w : warnings) o << "- Not drawn: " << w << "\n";
    o << "\n";
  }
  o << "## Files\n\nEvery file of the run, with its size and hash, is listed in summary.json "
       "(`files`); docs/outputs.md describes them.\n";
  const json& citations = summary.value("citations", json::array());
  if (!citations.empty()) {
    o << "\n## References\n\n";
    for (const json& c : citations)
      if (c.is_string()) o << "- " << c.get<std::string>() << "\n";
  }
  return o.str();
}

void write_run_report(const std::filesystem::path& out, const std::vector<std::string>& warnings) {
  const json summary = json::parse(read_file_bytes(out / "summary.json"));
  std::vector<std::string> figures;
  std::error_code ec;
  for (const ReportFigure& f : report_figures())
    if (std::filesystem::is_regular_file(out / f.file, ec)) figures.emplace_back(f.file);
  write_file_atomically(out / kReportName, run_report_text(summary, figures, warnings));
}

}  // namespace blockdem
