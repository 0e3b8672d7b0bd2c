// A joint set's constitutive model: one normal law and one shear law (Boon, Houlsby & Utili 2015,
// eqs 1-16), the pair a world assigns to the contacts of that joint set.
#pragma once

#include "blockdem/contact/normal_laws.hpp"
#include "blockdem/contact/shear_laws.hpp"

namespace blockdem {

/// Normal and shear law of one joint set. Defaults: the paper's Table 2 case 1 (k_n = 10 GPa/m,
/// k_s = 1 GPa/m, phi = 40 deg).
struct JointLaw {
  NormalLaw normal = LinearNormal{};
  ShearLaw shear = LinearShear{};

  /// Throws std::invalid_argument naming the law and the parameter if either law is unusable.
  void validate() const {
    blockdem::validate(normal);
    blockdem::validate(shear);
  }
};

}  // namespace blockdem
