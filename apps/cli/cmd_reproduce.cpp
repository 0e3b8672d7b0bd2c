// `blockdem reproduce boon2015 --out DIR`: every case of the paper's Tables 2 and 3, the report
// and its figures.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <thread>

#include "blockdem/io/boon2015_report.hpp"
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
  const std::filesystem::path scen_dir =
      opt.scenarios.empty() ? std::filesystem::path(BLOCKDEM_SOURCE_DIR) / "scenarios" / "boon2015"
                            : std::filesystem::path(opt.scenarios);
  // Select and read every case before running any.
  // Each case in mode boon2012 (the paper's) and, with the suffix -fi, face_integrated.
  std::vector<ContactMode> modes;
  if (opt.modes != "face_integrated") modes.push_back(ContactMode::boon2012);
  if (opt.modes != "boon2012") modes.push_back(ContactMode::face_integrated);
  auto wanted = [&](const std::string& id) {
    return opt.cases.empty() ||
           std::find(opt.cases.begin(), opt.cases.end(), id) != opt.cases.end();
  };
  std::vector<Boon2015CaseRun> runs;
  for (const ContactMode mode : modes) {
    for (const auto& c : boon2015_cases()) {
      const std::string id = c.id + (mode == ContactMode::face_integrated ? "-fi" : "");
      if (!wanted(id) && !wanted(c.id)) continue;
      Boon2015CaseRun r;
      r.spec = c;
      r.spec.id = id;
      r.base_id = c.id;
      r.mode = mode;
      try {
        r.scenario = load_scenario((scen_dir / (c.id + ".toml")).string());
      } catch (const ScenarioError& e) {
        std::cerr << "blockdem: error: " << e.what() << "\n";
        return 2;
      }
      r.scenario.settings.contact_mode = mode;
      runs.push_back(std::move(r));
    }
  }
  // Longest first, so that two threads finish together.
  std::stable_sort(runs.begin(), runs.end(),
                   [](const Boon2015CaseRun& x, const Boon2015CaseRun& y) {
                     auto cost = [](const Boon2015CaseRun& r) {
                       return (r.spec.beam == "half" ? 3.0 : 1.0) *
                              (r.mode == ContactMode::face_integrated ? 3.0 : 1.0);
                     };
                     return cost(x) > cost(y);
                   });
  for (const auto& id : opt.cases) {
    const bool known =
        std::any_of(boon2015_cases().begin(), boon2015_cases().end(),
                    [&](const Boon2015Case& c) { return c.id == id || c.id + "-fi" == id; });
    if (!known) {
      std::string list;
      for (const auto& c : boon2015_cases()) list += (list.empty() ? "" : ", ") + c.id;
      std::cerr << "blockdem: error: no case \"" << id << "\" in boon2015 (cases: " << list
                << ")\n";
      return 2;
    }
  }

  // Run the cases on a few threads; each writes its own folder.
  const std::filesystem::path out(opt.out);
  std::filesystem::create_directories(out);
  // Cores (OMP_NUM_THREADS, else every core) are shared: cases run side by side, and each case
  // gets the cores left over (one thread each when there are at least as many cases as cores).
  // Results do not depend on the split: the step is bit-identical for any thread count.
  const int cores = World().thread_count();
  const int jobs =
      std::min(opt.jobs > 0 ? opt.jobs : cores, std::max(1, static_cast<int>(runs.size())));
  for (auto& r : runs) r.scenario.settings.threads = std::max(1, cores / jobs);
  std::atomic<std::size_t> next{0};
  std::mutex io;
  Progress progress(!opt.quiet);
  std::vector<std::string> errors(runs.size());
  auto worker = [&] {
    for (std::size_t i = next++; i < runs.size(); i = next++) {
      auto& r = runs[i];
      RunCallbacks cb;
      cb.stage_done = [&](const std::string& line) {
        std::lock_guard<std::mutex> lock(io);
        if (!opt.quiet) progress.update(r.spec.id + ": " + line);
      };
      try {
        r.result = run_scenario(r.scenario, out / r.spec.id, cb);
      } catch (const std::exception& e) {
        errors[i] = e.what();
        r.result.status = "failed";
        r.result.message = e.what();
      }
      std::lock_guard<std::mutex> lock(io);
      if (!opt.quiet) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "%-12s %-13s %8lld steps  %6.2f s", r.spec.id.c_str(),
                      r.result.status.c_str(), static_cast<long long>(r.result.steps),
                      r.result.wall_time);
        progress.message(buf);
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < std::min<int>(jobs, static_cast<int>(runs.size())); ++t)
    pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (!errors[i].empty()) {
      std::cerr << "blockdem: error: case " << runs[i].spec.id << ": " << errors[i] << "\n";
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
      ->check(CLI::IsMember({"both", "boon2012", "face_integrated"}));
  cmd->add_option(
         "--jobs", opt->jobs,
         "Cases run in parallel (default: number of cores); each case gets cores / jobs threads")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--scenarios", opt->scenarios,
                  "Folder of the case files (default: the source tree's scenarios/boon2015)");
  cmd->add_flag("--quiet", opt->quiet, "No progress output");
  cmd->add_flag("!--no-figures", opt->figures, "Do not draw figures (no Python needed)");
  cmd->callback([opt] { set_exit_code(reproduce(*opt)); });
}

}  // namespace blockdem::cli
