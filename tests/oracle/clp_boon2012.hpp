// The Boon et al. (2012) narrow phase with its overlap LP solved by COIN-OR CLP instead of the fast
// solver: the "general LP solver" path the paper's code took, for benchmarks and cross-checks.
#pragma once

#include <span>

#include "blockdem/collision/boon2012.hpp"
#include "oracle/clp_lp.hpp"

namespace blockdem::oracle {

/// boon2012_contact with step 1 done by CLP: a cold CLP solve (a new model per call) when
/// `solver` is null, else `solver`'s re-solve from its previous basis. Steps 2-5 are the
/// library's (boon2012_contact_from_ball), with the cache's contact point as their warm start.
ContactGeometry clp_boon2012_contact(std::span<const Halfspace> planes_a,
                                     std::span<const Halfspace> planes_b, double extent,
                                     const Boon2012Settings& settings,
                                     Boon2012Cache* cache = nullptr,
                                     ClpInscribedBallSolver* solver = nullptr);

}  // namespace blockdem::oracle
