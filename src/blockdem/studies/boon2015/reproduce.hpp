// The reproduction of Boon et al. (2015): selects the paper's cases (Tables 2 and 3) in the
// chosen contact modes, reads their scenario files and runs them in parallel, one folder each.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "blockdem/studies/boon2015/report.hpp"

namespace blockdem {

struct Boon2015Selection {
  std::filesystem::path scenarios;  ///< folder holding the case files <id>.toml
  /// Case ids to run, with or without the suffix "-fi"; empty: every case.
  std::vector<std::string> cases;
  /// Contact modes; a face-integrated run carries the suffix "-fi".
  std::vector<ContactMode> modes = {ContactMode::boon2012, ContactMode::face_integrated};
};

/// Reads and checks every selected case before any runs, longest first. Throws
/// std::invalid_argument for an unknown case id and ScenarioError for a bad case file.
std::vector<Boon2015CaseRun> select_boon2015_cases(const Boon2015Selection& selection);

/// What run_boon2015_cases reports while it runs; each may be empty. None is ever called from two
/// threads at once.
struct Boon2015Callbacks {
  std::function<void(const Boon2015CaseRun&)> case_started;  ///< as a case starts
  std::function<void(const Boon2015CaseRun&)> case_done;     ///< as a case ends
  /// (case id, line) as each stage of a case ends.
  std::function<void(const std::string&, const std::string&)> stage_done;
  /// (case id, status line) while a stage runs, at most every 0.25 s per case (RunCallbacks).
  std::function<void(const std::string&, const std::string&)> progress;
};

/// Runs the cases on `jobs` threads (0: one per core), each writing out/<id>; each case's step
/// gets cores / jobs threads. A case that throws is marked status "failed" with the message.
void run_boon2015_cases(std::vector<Boon2015CaseRun>& runs, const std::filesystem::path& out,
                        int jobs, const Boon2015Callbacks& callbacks);

}  // namespace blockdem
