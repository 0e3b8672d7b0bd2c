// The run's files: clearing an earlier run, listing, and their record in summary.json.
#include "blockdem/run/run_files.hpp"

#include <algorithm>

#include "blockdem/io/atomic_file.hpp"

namespace blockdem {

const std::vector<std::string>& run_output_names() {
  static const std::vector<std::string> names = {"manifest.json",
                                                 "summary.json",
                                                 "history.csv",
                                                 "time_history.csv",
                                                 "blocks.csv",
                                                 "contacts.csv",
                                                 "joints.csv",
                                                 "levels.csv",
                                                 "strength_reduction.csv",
                                                 "mechanism.csv",
                                                 "collapse_search.csv",
                                                 "collapse_mechanism.csv",
                                                 "report.md",
                                                 "vtk"};
  return names;
}

void clear_earlier_run(const std::filesystem::path& out, bool keep_checkpoints) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(out, ec)) return;
  // The files the earlier run recorded (figures too), when it got that far.
  const fs::path summary = out / "summary.json";
  if (fs::exists(summary, ec)) {
    try {
      const auto j = nlohmann::json::parse(read_file_bytes(summary));
      for (const auto& f : j.at("files")) {
        const std::string rel = f.at("path").get<std::string>();
        if (rel.find("..") != std::string::npos || fs::path(rel).is_absolute()) continue;
        if (keep_checkpoints && (rel == kCheckpointName || rel == kPreviousCheckpointName))
          continue;
        fs::remove(out / rel, ec);
      }
    } catch (const std::exception&) {
      // An unreadable record: the standard names below still go.
    }
  }
  for (const std::string& name : run_output_names()) fs::remove_all(out / name, ec);
  if (!keep_checkpoints) {
    fs::remove(out / kCheckpointName, ec);
    fs::remove(out / kPreviousCheckpointName, ec);
  }
}

std::vector<std::string> list_run_folder(const std::filesystem::path& out) {
  namespace fs = std::filesystem;
  std::vector<std::string> files;
  std::error_code ec;
  if (!fs::is_directory(out, ec)) return files;
  for (auto it = fs::recursive_directory_iterator(out, ec); !ec && it != fs::end(it);
       it.increment(ec)) {
    if (!it->is_regular_file(ec)) continue;
    const std::string name = it->path().filename().string();
    if (name.size() > 4 && name.front() == '.' && name.ends_with(".tmp")) continue;
    files.push_back(fs::relative(it->path(), out, ec).generic_string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

nlohmann::json run_files_record(const std::filesystem::path& out,
                                const std::set<std::string>& foreign) {
  nlohmann::json files = nlohmann::json::array();
  for (const std::string& rel : list_run_folder(out)) {
    if (rel == "summary.json" || rel == kCheckpointName || rel == kPreviousCheckpointName ||
        foreign.count(rel))
      continue;
    const FileDigest d = file_digest(out / rel);
    files.push_back({{"path", rel}, {"bytes", d.bytes}, {"fnv1a64", hex64(d.fnv1a64)}});
  }
  return files;
}

void update_files_record(const std::filesystem::path& out, const std::set<std::string>& foreign) {
  auto summary = nlohmann::json::parse(read_file_bytes(out / "summary.json"));
  summary["files"] = run_files_record(out, foreign);
  write_file_atomically(out / "summary.json", summary.dump(2) + "\n");
}

}  // namespace blockdem
