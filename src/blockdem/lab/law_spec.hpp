// Joint laws written on one line as on a scenario's joint-law table, e.g.
// "law=exponential,preset=eq4" or "law=continuously_yielding,friction_deg=40", for the lab CLI.
#pragma once

#include <map>
#include <string>
#include <string_view>

#include "blockdem/contact/normal_laws.hpp"
#include "blockdem/contact/shear_laws.hpp"

namespace blockdem {

/// A joint-law table parsed from "key=value,key=value": `law` and `preset` are names, every other
/// key is a numeric parameter (SI units, angles in degrees) for normal_law_from_params or
/// shear_law_from_params.
struct LawSpec {
  std::string law;                       ///< the law's key, e.g. "linear", "exponential"
  std::string preset;                    ///< e.g. "eq4"; empty when not given
  std::map<std::string, double> params;  ///< named numeric parameters
};

/// Parses "key=value,..." (spaces around keys and values are ignored). `kind` ("normal" or
/// "shear") starts the error messages. Throws std::invalid_argument for an empty item, an item
/// without '=', a repeated key, a missing `law`, or a value that is not a number (every character
/// must belong to the number; "nan" and "inf" parse, so that validate() can name them).
LawSpec parse_law_spec(std::string_view kind, std::string_view text);

/// parse_law_spec then normal_law_from_params: throws std::invalid_argument naming the law and the
/// parameter for anything the factory or validate() rejects.
NormalLaw normal_law_from_spec(std::string_view text);

/// parse_law_spec then shear_law_from_params (shear laws have no presets: a preset is an error).
ShearLaw shear_law_from_spec(std::string_view text);

}  // namespace blockdem
