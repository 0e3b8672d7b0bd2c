// report.md: a run's results for a reader, from its summary.json and the figures beside it.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace blockdem {

/// The report's file name in a run's output folder.
inline constexpr const char* kReportName = "report.md";

/// The figures a report shows when they are in the folder, in this order, with their captions.
struct ReportFigure {
  const char* file;
  const char* caption;
};
const std::vector<ReportFigure>& report_figures();

/// The Markdown text of the report of the run whose summary is `summary` (summary.json's
/// content), showing those of `figures` (file names in the run's folder) that report_figures()
/// names, and a line for each of `warnings` (figures that could not be drawn). It holds nothing
/// that describes the machine (wall time, threads, processes: those are in summary.json), so
/// that two runs that give the same results give the same report.
std::string run_report_text(const nlohmann::json& summary, const std::vector<std::string>& figures,
                            const std::vector<std::string>& warnings);

/// Writes OUT/report.md (atomically) from OUT/summary.json and the figures present in OUT.
/// Throws std::runtime_error when summary.json cannot be read or the report cannot be written.
void write_run_report(const std::filesystem::path& out, const std::vector<std::string>& warnings);

}  // namespace blockdem
