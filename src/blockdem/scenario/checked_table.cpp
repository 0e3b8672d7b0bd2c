// Checked access to TOML values for scenario files.
#include "blockdem/scenario/checked_table.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace blockdem {
namespace {

std::string type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a number";
    case toml::node_type::boolean:
      return "a boolean";
    default:
      return "a date/time";
  }
}

// The most entries one array of a scenario file may hold: far more than any hand-written list
// needs, and small enough that a runaway array is refused before it costs time and memory.
constexpr std::size_t kMaxArrayEntries = 1000000;

std::optional<double> as_number(const toml::node& n) {
  if (auto v = n.value_exact<double>()) return *v;
  if (auto v = n.value_exact<std::int64_t>()) return static_cast<double>(*v);
  return std::nullopt;
}

// Reads `want` finite numbers from `row` into `out`; errors name `key` and `where` in the row.
void read_row(const CheckedTable& t, const std::string& key, const toml::array& row,
              std::size_t want, const std::string& where, double* out) {
  if (row.size() != want) {
    t.fail(key, where + "must have " + std::to_string(want) + " numbers, got " +
                    std::to_string(row.size()));
  }
  for (std::size_t i = 0; i < row.size(); ++i) {
    const auto v = as_number(*row.get(i));
    if (!v)
      t.fail(key, where + "entry " + std::to_string(i + 1) + " must be a number, got " +
                      type_name(*row.get(i)));
    if (!std::isfinite(*v))
      t.fail(key, where + "entry " + std::to_string(i + 1) + " must be finite");
    out[i] = *v;
  }
}

}  // namespace

CheckedTable::CheckedTable(const toml::table& table, std::string file, std::string path)
    : table_(&table), file_(std::move(file)), path_(std::move(path)) {}

bool CheckedTable::has(const std::string& key) const {
  asked_.push_back(key);
  return table_->contains(key);
}

bool CheckedTable::is_string(const std::string& key) const {
  asked_.push_back(key);
  const toml::node* n = table_->get(key);
  return n != nullptr && n->is_string();
}

bool CheckedTable::is_table(const std::string& key) const {
  asked_.push_back(key);
  const toml::node* n = table_->get(key);
  return n != nullptr && n->is_table();
}

std::string nearest_name(const std::string& key, const std::vector<std::string>& names) {
  // Levenshtein distance, one row at a time.
  auto distance = [](const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
      std::size_t diagonal = row[0];
      row[0] = i;
      for (std::size_t j = 1; j <= b.size(); ++j) {
        const std::size_t above = row[j];
        row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
        diagonal = above;
      }
    }
    return row[b.size()];
  };
  auto starts = [](const std::string& a, const std::string& b) {
    return a.size() >= 4 && b.size() > a.size() && b.compare(0, a.size(), a) == 0;
  };
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(2, key.size() / 3) + 1;
  for (const auto& name : names) {
    if (name == key) continue;
    const std::size_t d = starts(key, name) || starts(name, key) ? 1 : distance(key, name);
    if (d < best_distance) {
      best = name;
      best_distance = d;
    }
  }
  return best;
}

void CheckedTable::missing(const std::string& key, const std::string& what) const {
  std::vector<std::string> unread;
  for (const auto& [k, v] : *table_) {
    if (std::find(used_.begin(), used_.end(), &v) == used_.end()) unread.emplace_back(k.str());
  }
  const std::string near = nearest_name(key, unread);
  fail(key,
       "is required" + (what.empty() ? std::string() : " (" + what + ")") +
           (near.empty() ? "" : "; the table has \"" + near + "\": did you mean \"" + key + "\"?"));
}

void CheckedTable::fail(const std::string& key, const std::string& reason) const {
  throw ScenarioError(file_, key_path(key), reason);
}

void CheckedTable::check_length(const std::string& key, std::size_t entries) const {
  if (entries > kMaxArrayEntries)
    fail(key, "has " + std::to_string(entries) + " entries, more than the limit of " +
                  std::to_string(kMaxArrayEntries));
}

const toml::node* CheckedTable::get(const std::string& key) const {
  asked_.push_back(key);
  const toml::node* n = table_->get(key);
  if (n != nullptr) used_.push_back(n);
  return n;
}

double CheckedTable::number(const std::string& key) const {
  const toml::node* n = get(key);
  if (n == nullptr) missing(key, "a number");
  const auto v = as_number(*n);
  if (!v) fail(key, "must be a number, got " + type_name(*n));
  if (!std::isfinite(*v)) fail(key, "must be finite");
  return *v;
}

double CheckedTable::number(const std::string& key, double fallback) const {
  return has(key) ? number(key) : fallback;
}

double CheckedTable::positive(const std::string& key, double fallback, bool allow_zero) const {
  const double v = number(key, fallback);
  if (allow_zero ? !(v >= 0.0) : !(v > 0.0)) {
    std::ostringstream s;
    s << "must be " << (allow_zero ? "zero or positive" : "positive") << ", got " << v;
    fail(key, s.str());
  }
  return v;
}

std::int64_t CheckedTable::integer(const std::string& key, std::int64_t fallback) const {
  const toml::node* n = get(key);
  if (n == nullptr) return fallback;
  if (auto v = n->value_exact<std::int64_t>()) return *v;
  fail(key, "must be an integer, got " + type_name(*n));
}

bool CheckedTable::boolean(const std::string& key, bool fallback) const {
  const toml::node* n = get(key);
  if (n == nullptr) return fallback;
  if (auto v = n->value_exact<bool>()) return *v;
  fail(key, "must be true or false, got " + type_name(*n));
}

std::string CheckedTable::string(const std::string& key) const {
  const toml::node* n = get(key);
  if (n == nullptr) missing(key, "a string");
  if (auto v = n->value_exact<std::string>()) return *v;
  fail(key, "must be a string, got " + type_name(*n));
}

std::string CheckedTable::string(const std::string& key, const std::string& fallback) const {
  return has(key) ? string(key) : fallback;
}

std::string CheckedTable::choice(const std::string& key, const std::string& fallback,
                                 const std::vector<std::string>& choices) const {
  const std::string v = string(key, fallback);
  for (const auto& c : choices) {
    if (c == v) return v;
  }
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "" : ", ") + ("\"" + c + "\"");
  fail(key, "must be one of " + list + ", got \"" + v + "\"");
}

Eigen::Vector3d CheckedTable::vec3(const std::string& key) const {
  const toml::node* n = get(key);
  if (n == nullptr) missing(key, "");
  const toml::array* a = n->as_array();
  if (a == nullptr) fail(key, "must be an array, got " + type_name(*n));
  check_length(key, a->size());
  Eigen::Vector3d v;
  read_row(*this, key, *a, 3, "", v.data());
  return v;
}

Eigen::Vector3d CheckedTable::vec3(const std::string& key, const Eigen::Vector3d& fallback) const {
  return has(key) ? vec3(key) : fallback;
}

std::vector<std::vector<double>> CheckedTable::rows(const std::string& key,
                                                    std::size_t width) const {
  const toml::node* n = get(key);
  if (n == nullptr) missing(key, "");
  const toml::array* a = n->as_array();
  if (a == nullptr) fail(key, "must be an array, got " + type_name(*n));
  check_length(key, a->size());
  // width 0: the value itself is one row of three numbers (as vec3 reads it).
  std::vector<std::vector<double>> out;
  if (width == 0) {
    out.emplace_back(3);
    read_row(*this, key, *a, 3, "", out.back().data());
    return out;
  }
  for (std::size_t r = 0; r < a->size(); ++r) {
    const toml::array* row = a->get(r)->as_array();
    const std::string where = "row " + std::to_string(r + 1) + " ";
    if (row == nullptr)
      fail(key, where + "must be an array of " + std::to_string(width) + " numbers");
    out.emplace_back(width);
    read_row(*this, key, *row, width, where, out.back().data());
  }
  return out;
}

std::vector<double> CheckedTable::numbers(const std::string& key) const {
  const toml::node* n = get(key);
  if (n == nullptr) missing(key, "an array of numbers");
  const toml::array* a = n->as_array();
  if (a == nullptr) fail(key, "must be an array of numbers, got " + type_name(*n));
  check_length(key, a->size());
  std::vector<double> out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const auto v = as_number(*a->get(i));
    if (!v)
      fail(key,
           "entry " + std::to_string(i + 1) + " must be a number, got " + type_name(*a->get(i)));
    if (!std::isfinite(*v)) fail(key, "entry " + std::to_string(i + 1) + " must be finite");
    out.push_back(*v);
  }
  return out;
}

std::vector<std::string> CheckedTable::strings(const std::string& key) const {
  const toml::node* n = get(key);
  if (n == nullptr) return {};
  const toml::array* a = n->as_array();
  if (a == nullptr) fail(key, "must be an array of strings, got " + type_name(*n));
  check_length(key, a->size());
  std::vector<std::string> out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    auto v = a->get(i)->value_exact<std::string>();
    if (!v) fail(key, "entry " + std::to_string(i + 1) + " must be a string");
    out.push_back(*v);
  }
  return out;
}

CheckedTable CheckedTable::table(const std::string& key) const {
  const toml::node* n = get(key);
  if (n == nullptr) missing(key, "a table");
  const toml::table* t = n->as_table();
  if (t == nullptr) fail(key, "must be a table, got " + type_name(*n));
  return CheckedTable(*t, file_, key_path(key));
}

std::size_t CheckedTable::for_each_table(
    const std::string& key, const std::function<void(const CheckedTable&)>& read) const {
  const toml::node* n = get(key);
  if (n == nullptr) return 0;
  const toml::array* a = n->as_array();
  if (a == nullptr) fail(key, "must be an array of tables ([[" + key + "]]), got " + type_name(*n));
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::table* t = a->get(i)->as_table();
    if (t == nullptr) fail(key, "entry " + std::to_string(i + 1) + " must be a table");
    read(CheckedTable(*t, file_, key_path(key) + "[" + std::to_string(i + 1) + "]"));
  }
  return a->size();
}

std::size_t CheckedTable::table_count(const std::string& key) const {
  asked_.push_back(key);
  const toml::node* n = table_->get(key);
  if (n == nullptr) return 0;
  const toml::array* a = n->as_array();
  if (a == nullptr) fail(key, "must be an array of tables ([[" + key + "]]), got " + type_name(*n));
  return a->size();
}

std::vector<CheckedTable> CheckedTable::tables(const std::string& key) const {
  std::vector<CheckedTable> out;
  for_each_table(key, [&](const CheckedTable& t) { out.push_back(t); });
  return out;
}

std::map<std::string, double> CheckedTable::numbers_except(
    const std::set<std::string>& except) const {
  std::map<std::string, double> out;
  for (const auto& [k, v] : *table_) {
    const std::string key(k.str());
    if (except.count(key)) continue;
    out[key] = number(key);
  }
  return out;
}

void CheckedTable::finish() const {
  for (const auto& [k, v] : *table_) {
    if (std::find(used_.begin(), used_.end(), &v) != used_.end()) continue;
    const std::string key(k.str());
    const std::string near = nearest_name(key, asked_);
    fail(key, "unknown key (misspelt, or not a setting of this table)" +
                  (near.empty() ? "" : "; did you mean \"" + near + "\"?"));
  }
}

}  // namespace blockdem
