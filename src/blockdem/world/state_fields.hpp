// One function for both directions of a saved state: a StateWriter takes each field, a
// StateReader fills it. A record written with these (world/bolt_state.cpp, the voussoir
// recorder) is read back by the same function, so the two directions cannot drift apart.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "blockdem/world/state_stream.hpp"

namespace blockdem::state_fields {

template <class Stream>
inline constexpr bool kWriting = std::is_same_v<Stream, StateWriter>;

/// A plain value as its bytes.
template <class Stream, class T>
void field(Stream& s, T& value) {
  s.pod(value);
}

template <class Stream>
void vector3(Stream& s, Eigen::Vector3d& v) {
  for (int i = 0; i < 3; ++i) s.pod(v[i]);
}

template <class Stream>
void text(Stream& s, std::string& value) {
  if constexpr (kWriting<Stream>)
    s.str(value);
  else
    value = s.str();
}

/// A bool as one byte, 0 or 1; `what` names the state in the error a corrupt byte raises
/// ("saved bolt": "saved bolt is corrupt (a flag is not 0 or 1)").
template <class Stream>
void flag(Stream& s, bool& value, const char* what) {
  std::uint8_t byte = value ? 1 : 0;
  s.pod(byte);
  if (byte > 1) throw StateError(std::string(what) + " is corrupt (a flag is not 0 or 1)");
  value = byte == 1;
}

/// A list: its length, then each item through `each(s, item)`.
template <class Stream, class T, class Each>
void list(Stream& s, std::vector<T>& items, Each each) {
  if constexpr (kWriting<Stream>)
    s.size(items.size());
  else
    items.resize(s.size());
  for (T& item : items) each(s, item);
}

}  // namespace blockdem::state_fields
