// The reproduction report of Boon et al. (2015): report.md comparing every case with what the
// paper reports, with the statics, line-of-thrust and analytical checks beside them.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "blockdem/run/scenario_runner.hpp"
#include "blockdem/studies/boon2015/cases.hpp"

namespace blockdem {

struct Boon2015CaseRun {
  Boon2015Case spec;    ///< for a face-integrated run, spec.id carries the suffix "-fi"
  std::string base_id;  ///< the paper's case id, without suffix
  ContactMode mode = ContactMode::boon2012;
  Scenario scenario;
  RunResult result;
};

/// Writes DIR/report.md. `figures` lists the PNG files (relative to DIR) that exist, or is empty
/// with `figure_note` saying why none were drawn.
void write_boon2015_report(const std::filesystem::path& dir,
                           const std::vector<Boon2015CaseRun>& runs,
                           const std::vector<std::string>& figures, const std::string& figure_note,
                           double wall_time);

}  // namespace blockdem
