// The cases of Boon, Houlsby & Utili (2015), Tables 2 and 3, with what the
// paper reports for each, and the comparisons the reproduction report makes.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace blockdem {

struct Boon2015Case {
  std::string id;          ///< e.g. "T2-1"; the scenario is scenarios/boon2015/<id>.toml
  std::string beam;        ///< "full" or "half"
  std::string normal_law;  ///< description
  std::string shear_law;   ///< description
  double g_max = 40.0;
  std::string paper_reports;  ///< the paper's stated discrepancy for this case
};

/// The seven cases in the paper's order.
const std::vector<Boon2015Case>& boon2015_cases();

/// The paper's ratio of midspan deflections implied by Table 3: (1 + new) / (1 + old) with the
/// discrepancies against the same experiment. Full beam: the mean of the three tests
/// (180-C0/D/E: +13.8/+40.0/+30.0% new vs -46.7/-34.4/-39.0% old); half beam: +(-32%) vs -68%.
double boon2015_ratio_full();
double boon2015_ratio_half();

}  // namespace blockdem
