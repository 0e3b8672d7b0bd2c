// The contact modes by name, as scenario files, the command line and Python spell them: the list
// of modes, and the name read back (to_string(ContactMode) holds the names).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "blockdem/world/world.hpp"

namespace blockdem {

/// Every contact mode, in the order they are offered (the paper's first).
inline constexpr std::array<ContactMode, 2> kContactModes{ContactMode::boon2012,
                                                          ContactMode::face_integrated};

/// The mode named `name`; empty for any other name.
inline std::optional<ContactMode> parse_contact_mode(std::string_view name) {
  for (ContactMode mode : kContactModes) {
    if (name == to_string(mode)) return mode;
  }
  return std::nullopt;
}

/// Every mode's name, in kContactModes' order.
inline std::vector<std::string> contact_mode_names() {
  std::vector<std::string> names;
  for (ContactMode mode : kContactModes) names.emplace_back(to_string(mode));
  return names;
}

/// The modes a selection of modes names: "both" (every mode, in kContactModes' order) or one
/// mode's name; empty for any other word.
inline std::vector<ContactMode> contact_modes_selected(std::string_view selection) {
  std::vector<ContactMode> modes;
  for (ContactMode mode : kContactModes) {
    if (selection == "both" || selection == to_string(mode)) modes.push_back(mode);
  }
  return modes;
}

}  // namespace blockdem
