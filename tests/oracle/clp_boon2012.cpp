// Boon et al. (2012) narrow phase with the overlap LP by CLP (see clp_boon2012.hpp).
#include "oracle/clp_boon2012.hpp"

#include <vector>

namespace blockdem::oracle {

ContactGeometry clp_boon2012_contact(std::span<const Halfspace> planes_a,
                                     std::span<const Halfspace> planes_b, double extent,
                                     const Boon2012Settings& settings, Boon2012Cache* cache,
                                     ClpInscribedBallSolver* solver) {
  // The LP's plane list: A's planes then B's, as the fast path orders them.
  std::vector<Halfspace> both(planes_a.begin(), planes_a.end());
  both.insert(both.end(), planes_b.begin(), planes_b.end());
  const InscribedBall ball = solver != nullptr ? solver->solve(both) : clp_inscribed_ball(both);
  return boon2012_contact_from_ball(planes_a, planes_b, ball, extent, settings, cache);
}

}  // namespace blockdem::oracle
