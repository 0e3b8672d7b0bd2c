// Hashes of a scenario up to each stage, for restarts that branch (docs/restart.md).
#include "blockdem/run/scenario_fingerprint.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <optional>
#include <sstream>

#include "blockdem/io/atomic_file.hpp"
#include "blockdem/io/checkpoint_file.hpp"

namespace blockdem {
namespace {

/// Folds a parsed TOML node into `h`: its type, then its value (tables key by key in key order,
/// arrays element by element). Two files that parse to the same tree hash alike.
std::uint64_t hash_node(const toml::node& node, std::uint64_t h) {
  const auto fold_bytes = [&h](const void* p, std::size_t n) {
    h = fnv1a64(std::string_view(static_cast<const char*>(p), n), h);
  };
  const auto fold_text = [&](std::string_view s) {
    const std::uint64_t n = s.size();
    fold_bytes(&n, sizeof n);
    h = fnv1a64(s, h);
  };
  const auto type = static_cast<std::uint8_t>(node.type());
  fold_bytes(&type, 1);
  if (const auto* t = node.as_table()) {
    std::vector<std::pair<std::string_view, const toml::node*>> items;
    for (auto&& [key, value] : *t) items.emplace_back(key.str(), &value);
    std::sort(items.begin(), items.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [key, value] : items) {
      fold_text(key);
      h = hash_node(*value, h);
    }
    const std::uint64_t n = items.size();
    fold_bytes(&n, sizeof n);
  } else if (const auto* a = node.as_array()) {
    for (const auto& element : *a) h = hash_node(element, h);
    const std::uint64_t n = a->size();
    fold_bytes(&n, sizeof n);
  } else if (const auto* s = node.as_string()) {
    fold_text(s->get());
  } else if (const auto* i = node.as_integer()) {
    const std::int64_t v = i->get();
    fold_bytes(&v, sizeof v);
  } else if (const auto* f = node.as_floating_point()) {
    const double v = f->get();
    fold_bytes(&v, sizeof v);
  } else if (const auto* b = node.as_boolean()) {
    const std::uint8_t v = b->get() ? 1 : 0;
    fold_bytes(&v, 1);
  } else {
    // Dates and times: their TOML text.
    std::ostringstream text;
    if (const auto* d = node.as_date()) text << d->get();
    if (const auto* tm = node.as_time()) text << tm->get();
    if (const auto* dt = node.as_date_time()) text << dt->get();
    fold_text(text.str());
  }
  return h;
}

// The bytes' hash of a stage's acceleration record (base_motion.file), if it has one: the record
// is data the stage's results depend on as much as on the text.
std::optional<std::uint64_t> record_hash(const toml::node& stage,
                                         const std::filesystem::path& scenario_file,
                                         std::string* name) {
  const auto* table = stage.as_table();
  const auto* motion = table != nullptr ? table->get_as<toml::table>("base_motion") : nullptr;
  const auto* file = motion != nullptr ? motion->get_as<std::string>("file") : nullptr;
  if (file == nullptr) return std::nullopt;
  *name = file->get();
  std::filesystem::path path = file->get();
  if (path.is_relative()) path = scenario_file.parent_path() / path;
  try {
    return fnv1a64(read_file_bytes(path), fnv1a64("blockdem acceleration record"));
  } catch (const std::exception&) {
    return fnv1a64("blockdem acceleration record: unreadable");
  }
}

}  // namespace

std::uint64_t ScenarioFingerprint::at(int level, bool in_stage) const {
  if (by_stage.empty()) return whole;
  const std::size_t k = static_cast<std::size_t>(level) + (in_stage ? 1 : 0);
  return by_stage[std::min(k, by_stage.size() - 1)];
}

std::vector<std::uint64_t> ScenarioFingerprint::accepted() const {
  std::vector<std::uint64_t> all = by_stage;
  all.push_back(whole);
  return all;
}

int ScenarioFingerprint::stages_shared(std::uint64_t hash) const {
  if (hash == whole) return std::numeric_limits<int>::max();
  for (std::size_t k = 0; k < by_stage.size(); ++k)
    if (by_stage[k] == hash) return static_cast<int>(k);
  return -1;
}

namespace {

// ", or the acceleration records they read: a.csv, b.csv" for the records of the first `stages`
// stages, if any.
std::string records_read(const ScenarioFingerprint& f, int stages) {
  std::string list;
  for (const auto& [stage, name] : f.records) {
    if (stage >= stages) continue;
    list += (list.empty() ? "" : ", ") + name;
  }
  return list.empty() ? list : ", or the acceleration records they read: " + list;
}

}  // namespace

std::string records_note(const ScenarioFingerprint& f) {
  if (f.records.empty()) return {};
  std::string list;
  for (const auto& [stage, name] : f.records) list += (list.empty() ? "" : ", ") + name;
  return "; the acceleration records of its dynamic stages count with their bytes (" + list +
         "): an edited record is another scenario";
}

std::string check_restart_point(const ScenarioFingerprint& f, const std::filesystem::path& file,
                                std::uint64_t hash, int level, bool in_stage,
                                const std::vector<std::string>& stage_names) {
  const int shared = f.stages_shared(hash);
  const int needed = level + (in_stage ? 1 : 0);
  const auto stage = [&](int k) {
    return "stage " + std::to_string(k + 1) + " '" +
           (k < static_cast<int>(stage_names.size()) ? stage_names[k] : std::string("?")) + "'";
  };
  if (shared == std::numeric_limits<int>::max())
    return "restarting from " + file.string() + " (written for this scenario file, byte for byte)";
  if (shared != needed || needed > static_cast<int>(stage_names.size()))
    throw CheckpointError(file, "taken " + std::string(in_stage ? "inside" : "at the start of") +
                                    " stage " + std::to_string(level + 1) +
                                    " of a run whose scenario differs from this one before "
                                    "there (in its settings, blocks, laws, outputs or first " +
                                    std::to_string(needed) + " stages" + records_read(f, needed) +
                                    "); a restart may change only later stages");
  std::string line = "restarting from " + file.string() + ", taken " +
                     (in_stage ? "inside " : "at the start of ") + stage(level) +
                     ": compared with this file, its settings, blocks, laws" +
                     (needed == 0   ? std::string(" and outputs")
                      : needed == 1 ? ", outputs and " + stage(0)
                                    : ", outputs and stages 1 to " + std::to_string(needed)) +
                     " are the same";
  if (needed < static_cast<int>(stage_names.size()))
    line += "; from " + stage(needed) + " on, the stages are this file's";
  return line;
}

ScenarioFingerprint scenario_fingerprint(std::string_view text, const std::string& options,
                                         const std::filesystem::path& scenario_file) {
  ScenarioFingerprint f;
  const std::uint64_t opts = fnv1a64(options);
  f.whole = fnv1a64(options, fnv1a64(text));  // the hash of every earlier version's files
  if (text.size() > kMaxFingerprintBytes) return f;
  toml::table root;
  try {
    root = toml::parse(text);
  } catch (const toml::parse_error&) {
    return f;
  }
  // A file whose stages a table builds (e.g. [voussoir]) has no [[stages]] list to branch from:
  // its checkpoints carry `whole` and restart only the same file.
  auto* listed = root.get_as<toml::array>("stages");
  if (listed == nullptr) return f;
  toml::array stages = std::move(*listed);
  root.erase("stages");
  // Distinct from any `whole`: a leading tag.
  std::uint64_t h = hash_node(root, fnv1a64("blockdem scenario prefix", opts));
  f.by_stage.push_back(h);
  for (const auto& stage : stages) {
    h = hash_node(stage, h);
    std::string name;
    if (const auto record = record_hash(stage, scenario_file, &name)) {
      // The record's bytes count in this stage's entry (and so every later one's) and in whole.
      h = fnv1a64(std::string_view(reinterpret_cast<const char*>(&*record), sizeof *record), h);
      f.whole = fnv1a64(std::string_view(reinterpret_cast<const char*>(&*record), sizeof *record),
                        f.whole);
      f.records.emplace_back(static_cast<int>(f.by_stage.size()) - 1, name);
    }
    f.by_stage.push_back(h);
  }
  return f;
}

}  // namespace blockdem
