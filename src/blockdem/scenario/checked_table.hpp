// A TOML table reader that records which keys were read, so that unknown keys, wrong types and
// impossible values become errors naming the file, the key and the reason.
#pragma once

#include <toml++/toml.h>
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "blockdem/numerics/number_text.hpp"

namespace blockdem {

/// An error in a scenario file. what() reads "FILE: KEY: REASON".
class ScenarioError : public std::runtime_error {
 public:
  ScenarioError(const std::string& file, const std::string& key, const std::string& reason)
      : std::runtime_error(file + ": " + (key.empty() ? std::string() : key + ": ") + reason),
        file_(file),
        key_(key),
        reason_(reason) {}
  const std::string& file() const { return file_; }
  const std::string& key() const { return key_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string file_, key_, reason_;
};

class CheckedTable {
 public:
  /// `path` is the dotted key of this table in the file ("" for the root), for messages.
  CheckedTable(const toml::table& table, std::string file, std::string path);

  const std::string& file() const { return file_; }
  std::string key_path(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }
  bool has(const std::string& key) const;
  bool is_string(const std::string& key) const;
  bool is_table(const std::string& key) const;

  /// Throws ScenarioError naming this key.
  [[noreturn]] void fail(const std::string& key, const std::string& reason) const;

  double number(const std::string& key) const;
  double number(const std::string& key, double fallback) const;
  /// A number that must be > 0 (or >= 0 when allow_zero).
  double positive(const std::string& key, double fallback, bool allow_zero = false) const;
  std::int64_t integer(const std::string& key, std::int64_t fallback) const;
  bool boolean(const std::string& key, bool fallback) const;
  std::string string(const std::string& key) const;
  std::string string(const std::string& key, const std::string& fallback) const;
  /// A string that must be one of `choices`.
  std::string choice(const std::string& key, const std::string& fallback,
                     const std::vector<std::string>& choices) const;
  Eigen::Vector3d vec3(const std::string& key) const;
  Eigen::Vector3d vec3(const std::string& key, const Eigen::Vector3d& fallback) const;
  /// An array of arrays of numbers, each of length `width`.
  std::vector<std::vector<double>> rows(const std::string& key, std::size_t width) const;
  std::vector<std::string> strings(const std::string& key) const;
  /// A flat array of numbers.
  std::vector<double> numbers(const std::string& key) const;
  /// A sub-table (inline or not).
  CheckedTable table(const std::string& key) const;
  /// An array of tables ([[key]]); empty when absent.
  std::vector<CheckedTable> tables(const std::string& key) const;
  /// The entries of an array of tables ([[key]]), each checked as by tables() and passed to
  /// `read` in turn, its reader (and the keys it recorded) dropped before the next: a list of
  /// 1e5 blocks does not hold 1e5 readers at once. Returns the number of entries.
  std::size_t for_each_table(const std::string& key,
                             const std::function<void(const CheckedTable&)>& read) const;
  /// The number of entries of an array of tables ([[key]]) (0 when absent); fails as tables().
  std::size_t table_count(const std::string& key) const;
  /// Every key of the table with a numeric value, as a map (for joint-law parameters), skipping
  /// the keys in `except`.
  std::map<std::string, double> numbers_except(const std::set<std::string>& except) const;

  /// Throws for any key that was never read: an unknown key (typo or unsupported setting).
  void finish() const;

 private:
  const toml::node* get(const std::string& key) const;
  /// Fails for a required key that is absent: "is required (WHAT)", and the table's unread key
  /// nearest to it when there is one (a misspelling).
  [[noreturn]] void missing(const std::string& key, const std::string& what) const;
  /// Fails for an array longer than the limit.
  void check_length(const std::string& key, std::size_t entries) const;
  const toml::table* table_;
  std::string file_, path_;
  /// The values read (a key read with a fallback but absent from the table is not one): finish()
  /// fails for the table's other keys.
  mutable std::vector<const toml::node*> used_;
  /// Every key the reader asked for, present or not: the names finish() suggests for an
  /// unknown key.
  mutable std::vector<std::string> asked_;
};

/// The name in `names` nearest to `key` (by edit distance, at most 2 or a third of the key's
/// length, or one of them the other's start), or "" when none is near.
std::string nearest_name(const std::string& key, const std::vector<std::string>& names);

}  // namespace blockdem
