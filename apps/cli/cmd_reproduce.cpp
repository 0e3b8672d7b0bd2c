// `blockdem reproduce boon2015 --out DIR`: every case of the paper's Tables 2 and 3, the report
// and its figures.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <thread>

#include "blockdem/studies/boon2015/reproduce.hpp"
#include "blockdem/world/contact_mode.hpp"
#include "commands.hpp"
#include "figures.hpp"
#include "progress.hpp"

namespace blockdem::cli {
namespace {

struct ReproduceOptions {
  std::string study;
  std::string out;
  std::string scenarios;
  std::vector<std::string> cases;
  std::string modes = "both";
  int jobs = 0;
  bool quiet = false;
  bool figures = true;
};

int reproduce(const ReproduceOptions& opt) {
  if (opt.study != "boon2015") {
    std::cerr << "blockdem: error: unknown study \"" << opt.study << "\" (available: boon2015)\n";
    return 2;
  }
  const auto wall0 = std::chrono::steady_clock::now();
  Boon2015Selection selection;
  selection.scenarios = opt.scenarios.empty() ? data_dir() / "scenarios" / "boon2015"
                                              : std::filesystem::path(opt.scenarios);
  if (!std::filesystem::is_directory(selection.scenarios)) {
    std::cerr << "blockdem: error: the case files' folder " << selection.scenarios.string()
              << " does not exist (give --scenarios, or set BLOCKDEM_DATA_DIR)\n";
    return 2;
  }
  selection.cases = opt.cases;
  selection.modes = contact_modes_selected(opt.modes);  // --modes checks the word
  // Select and read every case before running any.
  std::vector<Boon2015CaseRun> runs;
  try {
    runs = select_boon2015_cases(selection);
  } catch (const std::exception& e) {
    std::cerr << "blockdem: error: " << e.what() << "\n";
    return 2;
  }

  // Run the cases on a few threads; each writes its own folder.
  const std::filesystem::path out(opt.out);
  const int jobs =
      opt.jobs > 0 ? opt.jobs : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  Progress progress(!opt.quiet);
  // A line as each case starts and ends (with the time since the start and the case's own), and
  // the status line of the running stages (rewritten on a terminal, every few seconds otherwise).
  const std::size_t total = runs.size();
  std::size_t started = 0, finished = 0;
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  };
  Boon2015Callbacks callbacks;
  if (!opt.quiet) {
    callbacks.case_started = [&](const Boon2015CaseRun& r) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "[%zu/%zu] %-12s started   at %8.1f s", ++started, total,
                    r.spec.id.c_str(), elapsed());
      progress.message(buf);
    };
    callbacks.case_done = [&](const Boon2015CaseRun& r) {
      char buf[200];
      std::snprintf(buf, sizeof buf,
                    "[%zu/%zu] %-12s finished  at %8.1f s: %s, %lld steps in %.2f s", ++finished,
                    total, r.spec.id.c_str(), elapsed(), to_string(r.result.status),
                    static_cast<long long>(r.result.steps), r.result.wall_time);
      progress.message(buf);
      if (r.result.status != RunStatus::completed) progress.message("  " + r.result.message);
    };
    callbacks.stage_done = [&](const std::string& id, const std::string& line) {
      progress.update(id + ": " + line);
    };
    callbacks.progress = [&](const std::string& id, const std::string& line) {
      progress.update(id + ": " + line);
    };
  }
  run_boon2015_cases(runs, out, jobs, callbacks);
  for (const auto& r : runs) {
    if (r.result.status == RunStatus::failed) {
      std::cerr << "blockdem: error: case " << r.spec.id << ": " << r.result.message << "\n";
      return 1;
    }
  }
  const double run_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();

  // Figures, then the report that shows them.
  std::vector<std::string> figures;
  std::string note = "disabled with --no-figures";
  if (opt.figures) {
    std::vector<std::string> args = {"report", out.string()};
    for (const auto& r : runs) args.push_back(r.spec.id);
    if (run_plot_script("plot_voussoir.py", args, note)) {
      for (const auto& entry : std::filesystem::directory_iterator(out / "figures")) {
        if (entry.path().extension() == ".png")
          figures.push_back("figures/" + entry.path().filename().string());
      }
      std::sort(figures.begin(), figures.end());
    } else {
      std::cerr << "blockdem: warning: " << note << "\n";
    }
  }
  write_boon2015_report(out, runs, figures, note, run_time);
  if (!opt.quiet) {
    std::fprintf(stderr, "blockdem: %zu cases in %.2f s (%d threads); report: %s\n", runs.size(),
                 run_time, jobs, (out / "report.md").string().c_str());
  }
  const bool all_ok = std::all_of(runs.begin(), runs.end(),
                                  [](const Boon2015CaseRun& r) { return r.result.exit_code == 0; });
  return all_ok ? 0 : 3;
}

}  // namespace

void register_reproduce(CLI::App& app) {
  auto opt = std::make_shared<ReproduceOptions>();
  CLI::App* cmd = app.add_subcommand(
      "reproduce", "Reproduce a published study (boon2015: Boon, Houlsby & Utili 2015)");
  cmd->add_option("study", opt->study, "Study id: boon2015")->required();
  cmd->add_option("--out", opt->out, "Output folder")->required();
  cmd->add_option("--case", opt->cases,
                  "Run only these cases (repeatable), e.g. --case T2-1 or --case T2-1-fi");
  cmd->add_option(
         "--mode", opt->modes,
         "Contact modes: both (default), boon2012 (the paper's) or face_integrated (cases -fi)")
      ->check(CLI::IsMember([] {
        std::vector<std::string> words = contact_mode_names();
        words.insert(words.begin(), "both");
        return words;
      }()));
  cmd->add_option(
         "--jobs", opt->jobs,
         "Cases run in parallel (default: number of cores); each case gets cores / jobs threads")
      ->check(positive_number("jobs"));
  cmd->add_option("--scenarios", opt->scenarios,
                  "Folder of the case files (default: the installed scenarios/boon2015)");
  cmd->add_flag("--quiet", opt->quiet, "No progress output");
  cmd->add_flag("!--no-figures", opt->figures, "Do not draw figures (no Python needed)");
  cmd->callback([opt] { set_exit_code(reproduce(*opt)); });
}

}  // namespace blockdem::cli
