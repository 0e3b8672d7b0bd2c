// Case selection and the parallel case loop of the Boon et al. (2015) reproduction.
#include "blockdem/studies/boon2015/reproduce.hpp"

#include <algorithm>
#include <atomic>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "blockdem/run/scene_builders.hpp"

namespace blockdem {

std::vector<Boon2015CaseRun> select_boon2015_cases(const Boon2015Selection& sel) {
  for (const auto& id : sel.cases) {
    const bool known =
        std::any_of(boon2015_cases().begin(), boon2015_cases().end(),
                    [&](const Boon2015Case& c) { return c.id == id || c.id + "-fi" == id; });
    if (!known) {
      std::string list;
      for (const auto& c : boon2015_cases()) list += (list.empty() ? "" : ", ") + c.id;
      throw std::invalid_argument("no case \"" + id + "\" in boon2015 (cases: " + list + ")");
    }
  }
  auto wanted = [&](const std::string& id) {
    return sel.cases.empty() ||
           std::find(sel.cases.begin(), sel.cases.end(), id) != sel.cases.end();
  };
  std::vector<Boon2015CaseRun> runs;
  for (const ContactMode mode : sel.modes) {
    for (const auto& c : boon2015_cases()) {
      const std::string id = c.id + (mode == ContactMode::face_integrated ? "-fi" : "");
      if (!wanted(id) && !wanted(c.id)) continue;
      Boon2015CaseRun r;
      r.spec = c;
      r.spec.id = id;
      r.base_id = c.id;
      r.mode = mode;
      r.scenario = load_scenario((sel.scenarios / (c.id + ".toml")).string());
      r.scenario.settings.contact_mode = mode;
      // A level that fails by a mechanism is bisected for the collapse load (not the preload).
      for (std::size_t k = 1; k < r.scenario.stages.size(); ++k) {
        Stage& st = r.scenario.stages[k];
        if (st.gravity && st.kind == Stage::Kind::equilibrium) st.find_collapse = true;
      }
      runs.push_back(std::move(r));
    }
  }
  // Longest first, so that the threads finish together.
  std::stable_sort(runs.begin(), runs.end(),
                   [](const Boon2015CaseRun& x, const Boon2015CaseRun& y) {
                     auto cost = [](const Boon2015CaseRun& r) {
                       return (r.spec.beam == "half" ? 3.0 : 1.0) *
                              (r.mode == ContactMode::face_integrated ? 3.0 : 1.0);
                     };
                     return cost(x) > cost(y);
                   });
  return runs;
}

void run_boon2015_cases(std::vector<Boon2015CaseRun>& runs, const std::filesystem::path& out,
                        int jobs, const Boon2015Callbacks& callbacks) {
  std::filesystem::create_directories(out);
  // Cores (OMP_NUM_THREADS, else every core) are shared: cases run side by side, and each case
  // gets the cores left over (one thread each when there are at least as many cases as cores).
  // Results do not depend on the split: a step is bit-identical for any thread count.
  const int cores = World().thread_count();
  if (jobs <= 0) jobs = cores;
  jobs = std::max(1, std::min(jobs, static_cast<int>(runs.size())));
  for (auto& r : runs) r.scenario.settings.threads = std::max(1, cores / jobs);
  std::atomic<std::size_t> next{0};
  std::mutex io;
  auto worker = [&] {
    for (std::size_t i = next++; i < runs.size(); i = next++) {
      auto& r = runs[i];
      {
        std::lock_guard<std::mutex> lock(io);
        if (callbacks.case_started) callbacks.case_started(r);
      }
      RunCallbacks cb;
      cb.stage_done = [&](const std::string& line) {
        std::lock_guard<std::mutex> lock(io);
        if (callbacks.stage_done) callbacks.stage_done(r.spec.id, line);
      };
      if (callbacks.progress) {
        cb.progress = [&](const std::string& line) {
          std::lock_guard<std::mutex> lock(io);
          callbacks.progress(r.spec.id, line);
        };
      }
      try {
        r.result = run_scenario(r.scenario, out / r.spec.id, cb);
      } catch (const std::exception& e) {
        r.result.status = RunStatus::failed;
        r.result.message = e.what();
        r.result.exit_code = 1;
      }
      std::lock_guard<std::mutex> lock(io);
      if (callbacks.case_done) callbacks.case_done(r);
    }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < std::min<int>(jobs, static_cast<int>(runs.size())); ++t)
    pool.emplace_back(worker);
  for (auto& t : pool) t.join();
}

}  // namespace blockdem
