// Largest ball inside an intersection of half-spaces (the overlap LP of Boon et al. 2012): a dense
// primal active-set method for cold starts and a dual simplex for warm starts, both on 4 x m.
//
// The LP, in the variables y = (x, r) in R^4 with rows a_j = (n_j, 1) and right-hand sides d_j:
//     maximise c·y = r   subject to   a_j · y <= d_j,   j = 1..m.
// It is always feasible (take any x and r = min_j (d_j - n_j·x)), so the primal method never needs
// a phase 1. Its optimality conditions (KKT) are: c = sum_{j in W} mu_j a_j with mu_j >= 0 over
// the working set W of tight planes; in words, sum mu_j n_j = 0 and sum mu_j = 1: the tight
// normals hold the origin in their convex hull.
//
// Primal active-set method (Nocedal & Wright, Numerical Optimization, 2nd ed., Alg. 16.3,
// specialised to a linear objective): W holds at most 4 linearly independent tight rows. If the
// projection z of c onto the null space of W is non-zero, step along p = z/|z| (c·p > 0) until the
// first plane blocks and add it to W; if z = 0, compute the multipliers and either stop (all
// mu >= 0) or drop the most negative one. The method needs no vertex to start from and handles
// optima that are not vertices. Ratio test after Harris (1973): among planes that block within a
// small feasibility tolerance take the one with the largest a_j·p, which keeps W well conditioned
// in the highly degenerate face-to-face contacts. After a run of degenerate (zero-length) steps
// the choices switch to Bland's smallest-index rule, which cannot cycle.
//
// Warm starts. (a) Dual simplex (e.g. Chvatal, Linear Programming, ch. 10): at the previous
// step's vertex (4 planes, basis matrix B), the multipliers mu = B^-T c are usually still >= 0
// after the blocks moved slightly; planes violated at the vertex then enter one by one, the
// leaving plane being chosen by the ratio test on mu, until the vertex is feasible.
// (b) An optimum with fewer than 4 tight planes (face-to-face contact: a segment or polygon of
// optimal centres) is re-entered at the nearest point where those planes are tight again; if it
// is feasible, the primal method continues from there, usually only confirming optimality.
// A vertex whose multipliers are no longer all non-negative (a zero multiplier of a degenerate
// vertex, as in face contact, that turned slightly negative) is re-entered the same way, and the
// primal method drops the planes with negative multipliers.
// Anything else restarts the primal method from the previous centre.
#include "blockdem/collision/inscribed_ball.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/LU>

namespace blockdem {
namespace {

using Vec4 = Eigen::Vector4d;
using Mat4 = Eigen::Matrix4d;

// Tolerances. Rows a_j = (n_j, 1) have norm sqrt(2), search directions p are unit vectors and
// c = (0, 0, 0, 1), so the first four are dimensionless and scale-free.
constexpr double kDirectionTol = 1e-12;    // |z| below this: c lies in the span of the W rows
constexpr double kMultiplierTol = 1e-12;   // multipliers above -this count as non-negative
constexpr double kPivotTol = 1e-11;        // plane j blocks a step along p only if a_j·p > this
constexpr double kDependentTol = 1e-13;    // Gram-Schmidt residual below this: row dependent
constexpr double kConditionLimit = 1e12;   // warm-start basis B rejected above this cond_inf(B)
constexpr double kFeasibilityRel = 1e-13;  // slack tolerance, relative to the problem's extent
constexpr int kBlandAfter = 8;             // consecutive degenerate steps before Bland's rule

// The planes and the per-plane workspace shared by both methods.
struct Problem {
  // The planes' columns n_x, n_y, n_z and d.
  const double* nx = nullptr;
  const double* ny = nullptr;
  const double* nz = nullptr;
  const double* offsets = nullptr;
  int m = 0;
  double* gap = nullptr;          ///< d_j - n_j·x at the current x; the slack is gap_j - r (m)
  double* alpha = nullptr;        ///< a_j·p for the current step direction p (-)
  double feasibility_tol = -1.0;  ///< slack tolerance (m); negative until set by the first pass
  double min_gap = 0.0;           ///< min_j gap_j, if min_gap_valid (m)
  bool min_gap_valid = false;     ///< set by the passes that compute the gaps from scratch
  int max_iterations = 0;

  Vec4 row(int j) const { return Vec4(nx[j], ny[j], nz[j], 1.0); }
  double d(int j) const { return offsets[j]; }
  /// n_j·v (m or -).
  double normal_dot(int j, double vx, double vy, double vz) const {
    return nx[j] * vx + ny[j] * vy + nz[j] * vz;
  }
};

// A point y = (x, r) with its working set in insertion order.
struct State {
  Vec4 y = Vec4::Zero();
  std::array<int, 4> working = {-1, -1, -1, -1};
  int size = 0;
  int iterations = 0;
};

[[noreturn]] void throw_iteration_limit(const Problem& pb) {
  throw std::runtime_error("largest_inscribed_ball: no convergence within " +
                           std::to_string(pb.max_iterations) + " iterations for " +
                           std::to_string(pb.m) + " planes (non-unit or non-finite normals?)");
}

[[noreturn]] void throw_non_finite() {
  throw std::invalid_argument(
      "largest_inscribed_ball: a plane has a non-finite normal or offset (NaN or infinity)");
}

// Removes entry i of the working set, keeping insertion order (Gram-Schmidt relies on it: each
// row then has a residual against the rows before it at least as large as when it entered).
void remove_working(State& st, int i) {
  for (int l = i; l + 1 < st.size; ++l) st.working[l] = st.working[l + 1];
  --st.size;
  st.working[st.size] = -1;
}

// Sets y = (x, min_j slack) with the minimising plane as the only working row and fills the
// gaps. If the tolerance is not yet set, sets it from the planes' extent seen from x.
void start_at(Problem& pb, const Eigen::Vector3d& x, State& st) {
  double rmin = std::numeric_limits<double>::infinity();
  double extent = 0.0;
  double probe = 0.0;  // becomes NaN if any gap is NaN or infinite
  int argmin = 0;
  for (int j = 0; j < pb.m; ++j) {
    const double g = pb.d(j) - pb.normal_dot(j, x.x(), x.y(), x.z());
    pb.gap[j] = g;
    extent = std::max(extent, std::abs(g));
    probe += 0.0 * g;
    if (g < rmin) {
      rmin = g;
      argmin = j;
    }
  }
  if (probe != 0.0) throw_non_finite();
  if (pb.feasibility_tol < 0.0) pb.feasibility_tol = kFeasibilityRel * extent;
  pb.min_gap = rmin;
  pb.min_gap_valid = true;
  st.y << x, rmin;
  st.working = {argmin, -1, -1, -1};
  st.size = 1;
}

// Orthonormal basis of the working rows, kept up to date as rows enter: A_W^T = Q R with
// Q = [q_0 .. q_{k-1}] and R upper triangular. Classical Gram-Schmidt with one
// re-orthogonalisation when the first pass cancelled more than half the norm ("twice is
// enough", Giraud et al. 2005).
struct WorkingBasis {
  std::array<Vec4, 4> q;
  double rr[4][4];     ///< R above the diagonal
  double inv_diag[4];  ///< 1 / R_ii

  // Orthogonalises working row i against rows 0..i-1; false if it is dependent on them.
  // (Squared norms are compared, to keep square roots off the critical path.)
  bool orthogonalize(const Problem& pb, const State& st, int i) {
    Vec4 v = pb.row(st.working[i]);
    double norm2_before = v.squaredNorm();
    for (int l = 0; l < i; ++l) rr[l][i] = 0.0;
    for (int pass = 0; pass < 2; ++pass) {
      for (int l = 0; l < i; ++l) {
        const double c = q[l].dot(v);
        v -= c * q[l];
        rr[l][i] += c;
      }
      const double norm2_after = v.squaredNorm();
      if (i == 0 || norm2_after > 0.25 * norm2_before) break;
      norm2_before = norm2_after;
    }
    const double norm2 = v.squaredNorm();
    if (!(norm2 > kDependentTol * kDependentTol)) return false;
    inv_diag[i] = 1.0 / std::sqrt(norm2);
    q[i] = v * inv_diag[i];
    return true;
  }

  // Rebuilds the basis, removing rows dependent on earlier ones (they are implied by them; only
  // possible for a warm-start set, as a row enters only with a residual above kPivotTol).
  void rebuild(const Problem& pb, State& st) {
    for (int i = 0; i < st.size;) {
      if (orthogonalize(pb, st, i)) {
        ++i;
      } else {
        remove_working(st, i);
      }
    }
  }
};

// Primal active-set iterations from a feasible state whose working rows have the orthonormal
// basis `basis`. Returns false if r is unbounded.
bool solve_primal(Problem& pb, State& st, WorkingBasis& basis) {
  const int m = pb.m;
  int last_dropped = -1;
  int degenerate_run = 0;
  bool bland = false;
  for (;; ++st.iterations) {
    if (st.iterations > pb.max_iterations) throw_iteration_limit(pb);

    // Projection of c = e_r onto the null space of the working rows, re-orthogonalised when
    // short so that the step keeps the working planes tight to round-off however short z is.
    Vec4 z = Vec4::UnitW();
    for (int l = 0; l < st.size; ++l) z -= basis.q[l][3] * basis.q[l];
    double z_norm2 = z.squaredNorm();
    if (z_norm2 < 0.25) {
      for (int l = 0; l < st.size; ++l) z -= basis.q[l].dot(z) * basis.q[l];
      z_norm2 = z.squaredNorm();
    }

    if (z_norm2 <= kDirectionTol * kDirectionTol) {
      // c = A_W^T mu: solve R mu = Q^T c by back substitution.
      double mu[4] = {};
      for (int i = st.size - 1; i >= 0; --i) {
        double sum = basis.q[i][3];
        for (int l = i + 1; l < st.size; ++l) sum -= basis.rr[i][l] * mu[l];
        mu[i] = sum * basis.inv_diag[i];
      }
      int drop = -1;
      for (int i = 0; i < st.size; ++i) {
        if (mu[i] >= -kMultiplierTol) continue;
        if (drop < 0 || (bland ? st.working[i] < st.working[drop] : mu[i] < mu[drop])) drop = i;
      }
      if (drop < 0) return true;  // KKT holds: optimal
      last_dropped = st.working[drop];
      remove_working(st, drop);
      basis.rebuild(pb, st);
      continue;
    }
    const Vec4 p = z / std::sqrt(z_norm2);

    // Harris (1973) ratio test. Pass 1: the longest step t_max that violates no plane by more
    // than the feasibility tolerance; the slack of plane j is gap_j - r. Working planes
    // (a_j·p = 0 to round-off) and the plane just dropped (a_j·p < 0) cannot block.
    // t_max is kept as the fraction t_num / t_den (both positive), so that the loops compare
    // cross products instead of dividing.
    const double r = st.y[3];
    const double tol = pb.feasibility_tol;
    double t_num = 1.0;
    double t_den = 0.0;  // t_max = +infinity
    for (int j = 0; j < m; ++j) {
      const double a = pb.normal_dot(j, p[0], p[1], p[2]) + p[3];
      pb.alpha[j] = a;
      const double bound = std::max(pb.gap[j] - r, 0.0) + tol;
      if (a > kPivotTol && j != last_dropped && bound * t_den < t_num * a) {
        t_num = bound;
        t_den = a;
      }
    }
    if (t_den == 0.0) {
      return false;  // c·p > 0 and nothing blocks: r is unbounded
    }
    // Pass 2: among the planes blocking within t_max, the largest pivot a_j·p, which keeps the
    // working rows well conditioned (Bland: the lowest index).
    int enter = -1;
    double best_alpha = kPivotTol;
    for (int j = 0; j < m; ++j) {
      const double a = pb.alpha[j];
      if (a > best_alpha && j != last_dropped &&
          std::max(pb.gap[j] - r, 0.0) * t_den <= t_num * a) {
        enter = j;
        best_alpha = a;
        if (bland) break;
      }
    }
    const double t = std::max(pb.gap[enter] - r, 0.0) / pb.alpha[enter];

    // Step (x moves by t p_x, so gap_j by -t n_j·p_x = -t (a_j - p_r)); add the blocking plane.
    st.y += t * p;
    const double dr = t * p[3];
    for (int j = 0; j < m; ++j) pb.gap[j] -= t * pb.alpha[j] - dr;
    pb.gap[enter] = st.y[3];
    pb.min_gap_valid = false;
    st.working[st.size++] = enter;
    if (!basis.orthogonalize(pb, st, st.size - 1)) remove_working(st, st.size - 1);
    last_dropped = -1;
    degenerate_run = (t <= tol) ? degenerate_run + 1 : 0;
    if (degenerate_run > kBlandAfter) bland = true;
  }
}

// Infinity-norm condition number of a 4x4 matrix, given its inverse.
double condition_inf(const Mat4& b, const Mat4& b_inv) {
  return b.cwiseAbs().rowwise().sum().maxCoeff() * b_inv.cwiseAbs().rowwise().sum().maxCoeff();
}

// Dual simplex from a dual-feasible vertex basis. Returns true on success (st holds a vertex
// feasible within the tolerance); false if the basis is unusable or the pivots stall, in which
// case st.y holds the last vertex reached, if any (else it is left unchanged).
bool solve_dual(Problem& pb, State& st) {
  const int m = pb.m;
  Mat4 b;
  Vec4 rhs;
  for (int i = 0; i < 4; ++i) {
    b.row(i) = pb.row(st.working[i]).transpose();
    rhs[i] = pb.d(st.working[i]);
  }
  Mat4 b_inv = b.inverse();
  if (!b_inv.allFinite() || !(condition_inf(b, b_inv) < kConditionLimit)) return false;
  // Multipliers mu = B^-T c, i.e. the last row of B^-1.
  Vec4 mu = b_inv.row(3).transpose();
  if (mu.minCoeff() < -kMultiplierTol) return false;

  const int budget = st.iterations + pb.max_iterations / 2;
  for (;; ++st.iterations) {
    st.y = b_inv * rhs;
    // The most violated plane enters. On the first pass the tolerance is set from the planes'
    // extent seen from the vertex.
    double min_gap = std::numeric_limits<double>::infinity();
    double extent = 0.0;
    double probe = 0.0;  // becomes NaN if any gap is NaN or infinite
    int enter = -1;
    for (int j = 0; j < m; ++j) {
      const double g = pb.d(j) - pb.normal_dot(j, st.y[0], st.y[1], st.y[2]);
      pb.gap[j] = g;
      extent = std::max(extent, std::abs(g));
      probe += 0.0 * g;
      if (g < min_gap) {
        min_gap = g;
        enter = j;
      }
    }
    if (probe != 0.0) return false;  // the primal restart reports it
    pb.min_gap = min_gap;
    pb.min_gap_valid = true;
    const double worst = std::min(min_gap - st.y[3], 0.0);
    if (pb.feasibility_tol < 0.0) pb.feasibility_tol = kFeasibilityRel * extent;
    if (worst >= -pb.feasibility_tol) {
      st.size = 4;
      return true;
    }
    if (st.iterations >= budget) return false;
    // w = B^-T a_enter: a_enter expressed in the basis rows. Leaving row by the ratio mu_i / w_i.
    const Vec4 w = b_inv.transpose() * pb.row(enter);
    int leave = -1;
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 4; ++i) {
      if (w[i] <= kPivotTol) continue;
      const double ratio = std::max(mu[i], 0.0) / w[i];
      if (leave < 0 || ratio < best || (ratio == best && w[i] > w[leave])) {
        best = ratio;
        leave = i;
      }
    }
    if (leave < 0) return false;  // would mean an infeasible LP: numerical trouble
    // Replace row `leave` by a_enter: B'^-1 = B^-1 - col (w - e_leave)^T / w_leave.
    const Vec4 col = b_inv.col(leave);
    Vec4 w_shift = w;
    w_shift[leave] -= 1.0;
    b_inv -= (col / w[leave]) * w_shift.transpose();
    mu = b_inv.row(3).transpose();
    rhs[leave] = pb.d(enter);
    st.working[leave] = enter;
  }
}

// Fills the public result from a solved state. The radius is min_j (d_j - n_j·x) at the returned
// centre (from the gaps; not the r of the state, which may exceed it by the feasibility
// tolerance), so that the ball of that radius there is inside every half-space.
InscribedBall make_result(const Problem& pb, const State& st, bool bounded) {
  InscribedBall out;
  out.center = st.y.head<3>();
  out.bounded = bounded;
  out.iterations = st.iterations;
  out.active = st.working;
  out.num_active = st.size;
  if (!bounded) {
    out.radius = std::numeric_limits<double>::infinity();
    return out;
  }
  out.radius = pb.min_gap_valid
                   ? pb.min_gap
                   : Eigen::Map<const Eigen::ArrayXd>(pb.gap, pb.m).minCoeff();  // vectorised
  return out;
}

// Runs `solve` with the gap and step workspace on the stack for short plane lists and on the
// heap otherwise.
template <typename Solve>
InscribedBall with_workspace(const PlaneColumns& planes, Solve&& solve) {
  if (planes.size() == 0) {
    throw std::invalid_argument("largest_inscribed_ball: the plane list is empty");
  }
  const int m = static_cast<int>(planes.size());
  std::array<double, 2 * kInscribedBallStackPlanes> stack_buffer;
  std::vector<double> heap_buffer;
  double* buffer = stack_buffer.data();
  if (m > kInscribedBallStackPlanes) {
    heap_buffer.resize(2 * planes.size());
    buffer = heap_buffer.data();
  }
  Problem pb;
  pb.nx = planes.nx();
  pb.ny = planes.ny();
  pb.nz = planes.nz();
  pb.offsets = planes.d();
  pb.m = m;
  pb.gap = buffer;
  pb.alpha = buffer + m;
  pb.max_iterations = 100 + 20 * m;
  return solve(pb);
}

// The mean of the foot points d_j n_j: the centre of a box, near the middle of a pair of blocks.
// (Component by component in plane order, as the sum of the vectors d_j n_j.)
Eigen::Vector3d mean_foot_point(const Problem& pb) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int j = 0; j < pb.m; ++j)
    sum += Eigen::Vector3d(pb.offsets[j] * pb.nx[j], pb.offsets[j] * pb.ny[j],
                           pb.offsets[j] * pb.nz[j]);
  return sum / static_cast<double>(pb.m);
}

InscribedBall solve_cold(Problem& pb, const Eigen::Vector3d& x0, int iterations_so_far) {
  State st;
  st.iterations = iterations_so_far;
  start_at(pb, x0, st);
  WorkingBasis basis;
  basis.rebuild(pb, st);
  const bool bounded = solve_primal(pb, st, basis);
  return make_result(pb, st, bounded);
}

// True if the previous active set has 1..4 distinct indices into a list of m planes.
bool valid_warm_set(const InscribedBall& previous, int m) {
  if (previous.num_active < 1 || previous.num_active > 4) return false;
  for (int i = 0; i < previous.num_active; ++i) {
    const int j = previous.active[i];
    if (j < 0 || j >= m) return false;
    for (int l = 0; l < i; ++l) {
      if (previous.active[l] == j) return false;
    }
  }
  return true;
}

// Warm start for an active set of fewer than 4 planes (an optimum that is not a vertex, as in
// face-to-face contact): moves the previous point y_prev = (x*, r*) to the nearest point where the
// old working planes are tight with the new plane data, y = y_prev + Q R^-T (d_W - A_W y_prev).
// If that point is feasible, the primal method continues from it (often just confirming the
// optimality conditions); otherwise returns false with the gaps undefined.
bool projected_start(Problem& pb, const InscribedBall& previous, State& st, WorkingBasis& basis) {
  st.working = previous.active;
  st.size = previous.num_active;
  basis.rebuild(pb, st);
  if (st.size == 0) return false;
  Vec4 y_prev;
  y_prev << previous.center, previous.radius;
  // Forward substitution R^T u = d_W - A_W y_prev, then y = y_prev + Q u.
  double u[4];
  st.y = y_prev;
  for (int i = 0; i < st.size; ++i) {
    const int j = st.working[i];
    double sum = pb.d(j) - pb.row(j).dot(y_prev);
    for (int l = 0; l < i; ++l) sum -= basis.rr[l][i] * u[l];
    u[i] = sum * basis.inv_diag[i];
    st.y += u[i] * basis.q[i];
  }
  if (!st.y.allFinite()) return false;
  double min_gap = std::numeric_limits<double>::infinity();
  double extent = 0.0;
  double probe = 0.0;  // becomes NaN if any gap is NaN or infinite
  for (int j = 0; j < pb.m; ++j) {
    const double g = pb.d(j) - pb.normal_dot(j, st.y[0], st.y[1], st.y[2]);
    pb.gap[j] = g;
    extent = std::max(extent, std::abs(g));
    probe += 0.0 * g;
    min_gap = std::min(min_gap, g);
  }
  if (probe != 0.0) return false;  // the primal restart reports it
  pb.min_gap = min_gap;
  pb.min_gap_valid = true;
  if (pb.feasibility_tol < 0.0) pb.feasibility_tol = kFeasibilityRel * extent;
  return min_gap - st.y[3] >= -pb.feasibility_tol;
}

// The planes of a 4-plane warm set whose multipliers mu = B^-T c are positive with the new plane
// data (the whole set if B is singular).
InscribedBall positive_multiplier_set(const Problem& pb, const InscribedBall& previous) {
  Mat4 b;
  for (int i = 0; i < 4; ++i) b.row(i) = pb.row(previous.active[i]).transpose();
  const Mat4 b_inv = b.inverse();
  if (!b_inv.allFinite()) return previous;
  InscribedBall reduced = previous;
  reduced.num_active = 0;
  for (int i = 0; i < 4; ++i) {
    if (b_inv(3, i) > kMultiplierTol) reduced.active[reduced.num_active++] = previous.active[i];
  }
  for (int i = reduced.num_active; i < 4; ++i) reduced.active[i] = -1;
  return reduced.num_active > 0 ? reduced : previous;
}

}  // namespace

namespace {
// The warm path (below): the dual simplex from the previous vertex, else the primal method
// re-entered near it.
InscribedBall warm_solve(const PlaneColumns& planes, const InscribedBall& previous);
}  // namespace

InscribedBall largest_inscribed_ball(std::span<const Halfspace> planes) {
  return largest_inscribed_ball(PlaneColumns(planes));
}

InscribedBall largest_inscribed_ball(std::span<const Halfspace> planes,
                                     const InscribedBall& previous) {
  return largest_inscribed_ball(PlaneColumns(planes), previous);
}

InscribedBall largest_inscribed_ball(const PlaneColumns& planes) {
  // Cold start from the mean of the foot points.
  return with_workspace(planes,
                        [&](Problem& pb) { return solve_cold(pb, mean_foot_point(pb), 0); });
}

InscribedBall largest_inscribed_ball(const PlaneColumns& planes, const InscribedBall& previous) {
  if (!previous.bounded || !previous.center.allFinite()) return largest_inscribed_ball(planes);
  InscribedBall out = warm_solve(planes, previous);
  // Any point x gives a feasible radius, min_j (d_j - n_j·x): the previous centre's is a lower
  // bound of the optimum. A warm result below it by more than round-off is not the optimum: the
  // warm path ended at a wrong vertex (seen at a degenerate vertex of a pressed face contact,
  // whose planes come in parallel and coplanar pairs: -1.89 m where the optimum was +0.12 mm,
  // a pressed joint taken for an open one). The cold solve then decides.
  const double* nx = planes.nx();
  const double* ny = planes.ny();
  const double* nz = planes.nz();
  const double* d = planes.d();
  const Eigen::Vector3d& c = previous.center;
  double bound = std::numeric_limits<double>::infinity();
  double scale = c.cwiseAbs().maxCoeff();
  for (std::size_t j = 0; j < planes.size(); ++j) {
    bound = std::min(bound, d[j] - (nx[j] * c.x() + ny[j] * c.y() + nz[j] * c.z()));
    scale = std::max(scale, std::abs(d[j]));
  }
  if (out.radius < bound - 1e-10 * (1.0 + scale)) {
    out = largest_inscribed_ball(planes);
    out.restarted = true;
  }
  return out;
}

namespace {

InscribedBall warm_solve(const PlaneColumns& planes, const InscribedBall& previous) {
  return with_workspace(planes, [&](Problem& pb) {
    State st;
    st.y.setConstant(std::numeric_limits<double>::quiet_NaN());  // no vertex reached yet
    if (valid_warm_set(previous, pb.m)) {
      bool try_projected = previous.num_active < 4;
      if (previous.num_active == 4) {
        st.working = previous.active;
        st.size = 4;
        if (solve_dual(pb, st)) return make_result(pb, st, true);
        // Rejected before any pivot (not dual feasible: a multiplier that was zero at a
        // degenerate vertex, as in face contact, turned slightly negative; or ill-conditioned):
        // re-enter at the vertex like a smaller set; the primal method then drops the planes
        // with negative multipliers.
        try_projected = !st.y.allFinite();
      }
      if (!try_projected) {
        // the dual simplex pivoted and stalled: primal from its last vertex, below
      } else if (WorkingBasis basis; projected_start(pb, previous, st, basis)) {
        const bool bounded = solve_primal(pb, st, basis);
        return make_result(pb, st, bounded);
      } else if (WorkingBasis reduced_basis;
                 previous.num_active == 4 &&
                 projected_start(pb, positive_multiplier_set(pb, previous), st, reduced_basis)) {
        // The vertex itself became infeasible: re-enter where only its planes with positive
        // multipliers (in face contact, the two touching faces) are tight.
        const bool bounded = solve_primal(pb, st, reduced_basis);
        return make_result(pb, st, bounded);
      } else {
        st.y.setConstant(std::numeric_limits<double>::quiet_NaN());
      }
    }
    // The old basis is unusable (singular, no longer dual feasible, stalled, or its tight point
    // infeasible): primal from the last vertex the dual simplex reached, else from the previous
    // centre.
    const Eigen::Vector3d x_start =
        st.y.allFinite() ? Eigen::Vector3d(st.y.head<3>()) : previous.center;
    InscribedBall out = solve_cold(pb, x_start, st.iterations);
    out.restarted = true;
    return out;
  });
}

}  // namespace

}  // namespace blockdem
