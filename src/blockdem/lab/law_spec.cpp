// Parsing of one-line joint-law tables ("law=linear,stiffness=1e10") into the named-parameter
// maps that the joint-law factories of contact/ take.
#include "blockdem/lab/law_spec.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <stdexcept>

namespace blockdem {
namespace {

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t");
  return s.substr(first, last - first + 1);
}

// 'text' in single quotes. (Built by appending: GCC 12 gives a false -Wrestrict for "'" + str.)
std::string in_quotes(std::string_view text) {
  std::string out(1, '\'');
  out.append(text);
  out += '\'';
  return out;
}

[[noreturn]] void fail(std::string_view kind, std::string_view text, const std::string& why) {
  throw std::invalid_argument(std::string(kind) + " law \"" + std::string(text) + "\": " + why);
}

}  // namespace

LawSpec parse_law_spec(std::string_view kind, std::string_view text) {
  LawSpec spec;
  bool has_law = false;
  bool has_preset = false;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string_view item = trim(text.substr(start, comma - start));
    start = comma + 1;
    if (item.empty()) fail(kind, text, "empty item (write key=value,key=value)");
    const std::size_t eq = item.find('=');
    if (eq == std::string_view::npos) fail(kind, text, in_quotes(item) + " is not key=value");
    const std::string key(trim(item.substr(0, eq)));
    const std::string value(trim(item.substr(eq + 1)));
    if (key.empty() || value.empty()) {
      fail(kind, text, in_quotes(item) + " needs both a key and a value");
    }
    if (key == "law" || key == "preset") {
      bool& seen = key == "law" ? has_law : has_preset;
      if (seen) fail(kind, text, "key " + in_quotes(key) + " given twice");
      seen = true;
      (key == "law" ? spec.law : spec.preset) = value;
      continue;
    }
    if (spec.params.count(key) > 0) fail(kind, text, "key " + in_quotes(key) + " given twice");
    // strtod reads "nan" and "inf" too: validate() then rejects them with the parameter's name.
    errno = 0;
    char* end = nullptr;
    const double number = std::strtod(value.c_str(), &end);
    if (end != value.c_str() + value.size()) {
      fail(kind, text,
           "parameter " + in_quotes(key) + " = " + in_quotes(value) + " is not a number");
    }
    if (errno == ERANGE) {
      fail(kind, text,
           "parameter " + in_quotes(key) + " = " + in_quotes(value) +
               " is outside the range of double");
    }
    spec.params[key] = number;
  }
  if (!has_law) fail(kind, text, "missing 'law=...' (e.g. law=linear)");
  return spec;
}

NormalLaw normal_law_from_spec(std::string_view text) {
  const LawSpec spec = parse_law_spec("normal", text);
  return normal_law_from_params(spec.law, spec.params, spec.preset);
}

ShearLaw shear_law_from_spec(std::string_view text) {
  const LawSpec spec = parse_law_spec("shear", text);
  if (!spec.preset.empty()) {
    throw std::invalid_argument("shear law '" + spec.law + "': has no presets, got preset '" +
                                spec.preset + "'");
  }
  return shear_law_from_params(spec.law, spec.params);
}

}  // namespace blockdem
