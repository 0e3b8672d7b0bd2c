// What a restart compares with the run that wrote its checkpoint: the scenario up to each stage.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace blockdem {

/// Hashes of a scenario file for checkpoints (docs/restart.md, "Branching").
///
/// `by_stage[k]` identifies what the state before stage k depends on: every table of the file
/// but [[stages]] (settings, materials, laws, blocks, the rock mass, outputs) and stages 1 to k,
/// with the options that change results. It is computed from the parsed TOML, so comments,
/// spacing and the order of keys do not count; a number's type and value do. A checkpoint taken
/// at the start of stage k carries by_stage[k], one taken inside stage k carries by_stage[k + 1]:
/// a scenario that agrees up to there may continue it, whatever its later stages are.
///
/// `whole` hashes the file's bytes and the options: what checkpoints of earlier versions carry,
/// what a file too large to parse twice (listed blocks over kMaxFingerprintBytes) carries, and
/// what a file without a [[stages]] list carries (its stages built by a table such as
/// [voussoir], they cannot be branched from one by one).
///
/// A dynamic stage's acceleration record (`base_motion.file`) counts with its bytes: its hash
/// is folded into that stage's entry and every later one, and into `whole`.
struct ScenarioFingerprint {
  std::uint64_t whole = 0;
  std::vector<std::uint64_t> by_stage;  ///< stages + 1 entries; empty: `whole` only
  /// The acceleration records hashed: (0-based stage index, the path as the scenario gives it).
  std::vector<std::pair<int, std::string>> records;

  /// The hash a checkpoint at stage `level` carries (`in_stage`: taken inside it).
  std::uint64_t at(int level, bool in_stage) const;
  /// Every hash a checkpoint of a run this file may continue can carry.
  std::vector<std::uint64_t> accepted() const;
  /// How many stages a checkpoint carrying `hash` shares with this file: -1 for none, INT_MAX
  /// for `whole` (the same file: every stage).
  int stages_shared(std::uint64_t hash) const;
};

/// Checks that the checkpoint `file`, carrying `hash` and taken at stage `level` (0-based;
/// `in_stage`: inside it), belongs to a run that agrees with this scenario up to there, and says
/// what was compared (one line for the user). Throws CheckpointError when it does not.
std::string check_restart_point(const ScenarioFingerprint& f, const std::filesystem::path& file,
                                std::uint64_t hash, int level, bool in_stage,
                                const std::vector<std::string>& stage_names);

/// "; the acceleration records ... count with their bytes" naming the records `f` hashed, or
/// empty without any: a note for a refused restart.
std::string records_note(const ScenarioFingerprint& f);

/// Files larger than this are fingerprinted by their bytes only (no branching): parsing a large
/// listed-block file a second time would double the reading's peak memory.
inline constexpr std::size_t kMaxFingerprintBytes = 8u << 20;

/// The fingerprint of scenario text `text` run with `options` (the command-line options that
/// change results, as text). A text that does not parse gets `whole` only. `scenario_file`, the
/// file the text was read from, places the acceleration records (relative paths are relative to
/// its folder); a record that cannot be read counts as a fixed tag.
ScenarioFingerprint scenario_fingerprint(std::string_view text, const std::string& options,
                                         const std::filesystem::path& scenario_file = {});

}  // namespace blockdem
