// The paper's cases and its reported numbers (Tables 2 and 3).
#include "blockdem/studies/boon2015/cases.hpp"

namespace blockdem {

const std::vector<Boon2015Case>& boon2015_cases() {
  static const std::vector<Boon2015Case> cases = {
      {"T2-1", "full", "linear 10 GPa/m", "linear 1 GPa/m", 40, "midspan -16% vs FLAC at 40 g"},
      {"T2-2", "full", "eq. 3 (4e9 + 7.4e4 sigma_n)", "eq. 2 (1e8 + 9.7e4 sigma_n)", 40,
       "midspan -12% vs FLAC at 40 g"},
      {"T2-3", "half", "linear 10 GPa/m", "linear 1 GPa/m", 90, "midspan -11% vs FLAC at 90 g"},
      {"F8", "full", "eq. 4 (half stiffness)", "eq. 2", 40,
       "deflections closer to test 180-E (Fig. 8)"},
      {"T3-full", "full", "eq. 4", "continuously yielding, eqs 6-8", 40,
       "+13.8/+40.0/+30.0% vs tests 180-C0/D/E at 40 g"},
      {"T3-half", "half", "eq. 4", "continuously yielding, eqs 6-8", 90,
       "-32% vs test 180-3 at 90 g"},
      {"T3-half-old", "half", "eq. 3", "eq. 2", 90, "-68% vs test 180-3 at 90 g"},
  };
  return cases;
}

double boon2015_ratio_full() {
  const double fresh[] = {0.138, 0.400, 0.300};
  const double old[] = {-0.467, -0.344, -0.390};
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) sum += (1 + fresh[i]) / (1 + old[i]);
  return sum / 3.0;
}

double boon2015_ratio_half() {
  return (1 - 0.32) / (1 - 0.68);
}

}  // namespace blockdem
