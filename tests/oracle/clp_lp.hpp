// Reference solver for the inscribed-ball LP (Boon et al. 2012 overlap test) with COIN-OR CLP:
// the slow, general oracle that the fast solver in collision/inscribed_ball is tested against.
#pragma once

#include <memory>
#include <span>

#include "blockdem/collision/inscribed_ball.hpp"
#include "blockdem/geometry/halfspace.hpp"

class ClpSimplex;

namespace blockdem::oracle {

/// Solves  maximise r  s.t.  n_j · x + r <= d_j  with CLP's dual simplex, building a new model on
/// every call (a cold solve), tolerances tightened to 1e-13 and all output silenced. Fills radius
/// (CLP's optimal objective; +infinity if unbounded), center, bounded, iterations (CLP's) and,
/// when exactly four rows are non-basic, `active` with those rows. Throws std::runtime_error if
/// CLP stops without proving optimality or unboundedness.
InscribedBall clp_inscribed_ball(std::span<const Halfspace> planes);

/// A CLP model kept across calls: a call with as many planes as the previous one overwrites the
/// coefficients and re-solves from the previous basis (CLP's own warm start); any other call
/// rebuilds the model. For benchmarks against the fast solver's warm start.
class ClpInscribedBallSolver {
 public:
  ClpInscribedBallSolver();
  ~ClpInscribedBallSolver();
  ClpInscribedBallSolver(const ClpInscribedBallSolver&) = delete;
  ClpInscribedBallSolver& operator=(const ClpInscribedBallSolver&) = delete;

  InscribedBall solve(std::span<const Halfspace> planes);

 private:
  std::unique_ptr<ClpSimplex> model_;
  int rows_ = 0;
};

}  // namespace blockdem::oracle
