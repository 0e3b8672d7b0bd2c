// The error thrown for invalid shapes: the message says what is wrong in the user's terms.
#pragma once

#include <stdexcept>
#include <string>

namespace blockdem {

class GeometryError : public std::runtime_error {
 public:
  explicit GeometryError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace blockdem
