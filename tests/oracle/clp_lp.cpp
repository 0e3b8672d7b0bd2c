// CLP-based reference solver for the inscribed-ball LP: rows n_j · x + r <= d_j, free columns
// (x, y, z, r), objective minimise -r. Each answer is checked by an optimality certificate.
#include "oracle/clp_lp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <ClpSimplex.hpp>
#include <CoinMessageHandler.hpp>

namespace blockdem::oracle {
namespace {

// Loads the LP into `model` (all 4m coefficients stored, zeros included, so that they can be
// overwritten later) and silences it.
void load(ClpSimplex& model, std::span<const Halfspace> planes) {
  const int m = static_cast<int>(planes.size());
  std::vector<CoinBigIndex> starts(5);
  std::vector<int> rows(4 * planes.size());
  std::vector<double> values(4 * planes.size());
  for (int col = 0; col < 4; ++col) {
    starts[col] = col * m;
    for (int j = 0; j < m; ++j) {
      rows[col * m + j] = j;
      values[col * m + j] = col < 3 ? planes[j].normal[col] : 1.0;
    }
  }
  starts[4] = 4 * m;
  const std::vector<double> col_lower(4, -COIN_DBL_MAX);
  const std::vector<double> col_upper(4, COIN_DBL_MAX);
  const std::vector<double> objective = {0.0, 0.0, 0.0, -1.0};
  const std::vector<double> row_lower(planes.size(), -COIN_DBL_MAX);
  std::vector<double> row_upper(planes.size());
  for (int j = 0; j < m; ++j) row_upper[j] = planes[j].offset;
  model.loadProblem(4, m, starts.data(), rows.data(), values.data(), col_lower.data(),
                    col_upper.data(), objective.data(), row_lower.data(), row_upper.data());
  model.setLogLevel(0);
  model.messageHandler()->setLogLevel(0);
}

InscribedBall read_solution(const ClpSimplex& model) {
  InscribedBall out;
  out.iterations = model.numberIterations();
  const double* x = model.getColSolution();
  out.center = Eigen::Vector3d(x[0], x[1], x[2]);
  if (model.isProvenDualInfeasible()) {
    out.bounded = false;
    out.radius = std::numeric_limits<double>::infinity();
    return out;
  }
  out.radius = x[3];
  int count = 0;
  for (int j = 0; j < model.numberRows(); ++j) {
    if (model.getRowStatus(j) != ClpSimplex::basic) {
      if (count < 4) out.active[count] = j;
      ++count;
    }
  }
  out.num_active = count == 4 ? 4 : 0;
  if (count != 4) out.active = {-1, -1, -1, -1};
  return out;
}

// Optimality certificate from CLP's row duals pi_j >= 0 (pi = -CLP's row price for this
// minimisation): dual feasibility sum pi_j n_j = 0, sum pi_j = 1, and a zero duality gap
// sum pi_j d_j = min_j (d_j - n_j·x). On success, sets the radius to that primal value (the
// exact radius at CLP's centre) and returns true.
bool certify(const ClpSimplex& model, std::span<const Halfspace> planes, InscribedBall& ball) {
  if (!model.isProvenOptimal()) return false;
  const double* price = model.getRowPrice();
  Eigen::Vector3d normal_sum = Eigen::Vector3d::Zero();
  double weight = 0.0;
  double dual_value = 0.0;
  double primal_value = std::numeric_limits<double>::infinity();
  double extent = 0.0;
  for (std::size_t j = 0; j < planes.size(); ++j) {
    const double pi = -price[j];
    if (pi < -1e-9) return false;
    normal_sum += pi * planes[j].normal;
    weight += pi;
    dual_value += pi * planes[j].offset;
    const double slack = planes[j].slack(ball.center);
    primal_value = std::min(primal_value, slack);
    extent = std::max(extent, std::abs(slack));
  }
  const double tol = 1e-11 * std::max(extent, 1e-300);
  // With sum pi n = e and sum pi = 1 + w, the dual value bounds r* up to |e| |x| + |w| |r|
  // terms; require both residuals at round-off level and the gap below tol.
  if (normal_sum.norm() > 1e-10 || std::abs(weight - 1.0) > 1e-10) return false;
  if (std::abs(dual_value - normal_sum.dot(ball.center) - weight * primal_value) > tol &&
      std::abs(dual_value - primal_value) > tol) {
    return false;
  }
  ball.radius = primal_value;
  return true;
}

}  // namespace

InscribedBall clp_inscribed_ball(std::span<const Halfspace> planes) {
  if (planes.empty()) throw std::invalid_argument("clp_inscribed_ball: the plane list is empty");
  // CLP is asked in turn: dual then primal simplex, without then with CLP's scaling, with tight
  // (1e-13) then looser (1e-9) feasibility tolerances; the first certified answer is returned.
  // Tight tolerances and no scaling are needed for nearly parallel faces, where CLP's defaults
  // accept a suboptimal basis (errors ~1e-8 relative); the tight settings occasionally make CLP
  // stop on a wrong basis, which the certificate catches.
  struct Attempt {
    bool use_dual;
    bool scale;
    double tolerance;
  };
  const Attempt attempts[] = {{true, false, 1e-13}, {false, false, 1e-13}, {true, true, 1e-13},
                              {false, true, 1e-13}, {true, false, 1e-9},   {false, false, 1e-9}};
  for (const Attempt& attempt : attempts) {
    ClpSimplex model;
    load(model, planes);
    model.setPrimalTolerance(attempt.tolerance);
    model.setDualTolerance(attempt.tolerance);
    model.scaling(attempt.scale ? 1 : 0);
    if (attempt.use_dual) {
      model.dual();
    } else {
      model.primal();
    }
    InscribedBall ball = read_solution(model);
    if (!ball.bounded) return ball;
    if (certify(model, planes, ball)) return ball;
  }
  throw std::runtime_error("clp_inscribed_ball: no CLP attempt produced a certified optimum (" +
                           std::to_string(planes.size()) + " planes)");
}

ClpInscribedBallSolver::ClpInscribedBallSolver() = default;
ClpInscribedBallSolver::~ClpInscribedBallSolver() = default;

InscribedBall ClpInscribedBallSolver::solve(std::span<const Halfspace> planes) {
  if (planes.empty())
    throw std::invalid_argument("ClpInscribedBallSolver: the plane list is empty");
  const int m = static_cast<int>(planes.size());
  if (!model_ || rows_ != m) {
    model_ = std::make_unique<ClpSimplex>();
    load(*model_, planes);
    model_->setPrimalTolerance(1e-13);
    model_->setDualTolerance(1e-13);
    rows_ = m;
  } else {
    for (int j = 0; j < m; ++j) {
      for (int col = 0; col < 3; ++col) {
        model_->modifyCoefficient(j, col, planes[j].normal[col], true);
      }
      model_->setRowUpper(j, planes[j].offset);
    }
  }
  model_->dual();
  if (!model_->isProvenOptimal() && !model_->isProvenDualInfeasible()) {
    throw std::runtime_error("ClpInscribedBallSolver: CLP stopped with status " +
                             std::to_string(model_->status()));
  }
  return read_solution(*model_);
}

}  // namespace blockdem::oracle
