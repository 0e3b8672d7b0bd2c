// The files of one run in its output folder: clearing what an earlier run left there, listing
// what this run wrote, and the record of them in summary.json (written last).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

namespace blockdem {

/// The restart file of a run, and the one before it (kept too).
inline constexpr const char* kCheckpointName = "checkpoint.bdck";
inline constexpr const char* kPreviousCheckpointName = "checkpoint.bdck.prev";

/// The files and folders directly under the output folder that a run of any scene may write
/// (history.csv ... summary.json, vtk), the checkpoints aside.
const std::vector<std::string>& run_output_names();

/// Removes what an earlier run left in `out`: the files its summary.json lists, run_output_names()
/// and, unless `keep_checkpoints`, its checkpoints.
/// Other files are left alone.
void clear_earlier_run(const std::filesystem::path& out, bool keep_checkpoints);

/// Every regular file under `out`, as paths relative to it with '/' separators, sorted;
/// temporary files of atomic writes (".NAME.tmp") are left out.
std::vector<std::string> list_run_folder(const std::filesystem::path& out);

/// summary.json's "files": every file under `out` but summary.json, the checkpoints (they carry
/// their own checksum) and those in `foreign` (there before the run), with its size and FNV-1a
/// 64 checksum.
nlohmann::json run_files_record(const std::filesystem::path& out,
                                const std::set<std::string>& foreign);

/// Rewrites OUT/summary.json (atomically) with "files" brought up to date, after the run wrote
/// more (figures).
void update_files_record(const std::filesystem::path& out, const std::set<std::string>& foreign);

}  // namespace blockdem
