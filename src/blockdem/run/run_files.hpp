// The files of one run in its output folder: clearing what an earlier run left there, listing
// what this run wrote, and the run record (manifest.json) written last.
#pragma once

#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace blockdem {

/// The restart file of a run, and the one before it (kept too).
inline constexpr const char* kCheckpointName = "checkpoint.bdck";
inline constexpr const char* kPreviousCheckpointName = "checkpoint.bdck.prev";

/// Removes what an earlier run left in `out`: the files its manifest.json lists, the files a run
/// writes (history.csv ... summary.json, manifest.json), vtk/, and, unless `keep_checkpoints`,
/// its checkpoints. Other files are left alone.
void clear_earlier_run(const std::filesystem::path& out, bool keep_checkpoints);

/// Every regular file under `out`, as paths relative to it with '/' separators, sorted;
/// temporary files of atomic writes (".NAME.tmp") are left out.
std::vector<std::string> list_run_folder(const std::filesystem::path& out);

/// Writes manifest.json atomically: the run's status and every file under `out` except those in
/// `foreign` (there before the run) and manifest.json itself, with its size and FNV-1a 64
/// checksum. Written last: a folder without it holds an unfinished or a dead run.
void write_manifest(const std::filesystem::path& out, const std::set<std::string>& foreign,
                    const std::string& status);

}  // namespace blockdem
