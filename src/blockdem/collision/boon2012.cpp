// Boon et al. (2012) narrow phase: LP overlap, analytic centre, rounded normal, chord overlap,
// slice area.
#include "blockdem/collision/boon2012.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "blockdem/collision/analytic_centre.hpp"
#include "blockdem/collision/inscribed_ball.hpp"
#include "blockdem/collision/plane_columns.hpp"

namespace blockdem {

namespace {

// Per-plane values at the contact point x_c: slack s_j = d_j - n_j·x_c (m) and the in-plane
// components (n_j·u, n_j·v) of the normal for the slice (-); on the stack for up to
// PlaneColumns::kStackPlanes planes.
class PointColumns {
 public:
  explicit PointColumns(std::size_t m) {
    data_ = stack_.data();
    if (m > PlaneColumns::kStackPlanes) {
      heap_.resize(3 * m);
      data_ = heap_.data();
    }
    slack = data_;
    a_u = data_ + m;
    a_v = data_ + 2 * m;
  }
  PointColumns(const PointColumns&) = delete;
  PointColumns& operator=(const PointColumns&) = delete;

  double* slack = nullptr;
  double* a_u = nullptr;
  double* a_v = nullptr;

 private:
  std::array<double, 3 * PlaneColumns::kStackPlanes> stack_;
  std::vector<double> heap_;
  double* data_ = nullptr;
};

// Step 3 for planes [begin, end) at x: fills their slacks s_j = d_j - n_j·x and returns the
// gradient 2 Σ <r - s_j> n_j, or 2 r n of the nearest face (the first of equals) when every
// bracket is zero (NaN if the slacks are not numbers). (One pass over the planes for both: the
// slacks are those fill_slacks gives.)
Eigen::Vector3d gradient_of(const PlaneColumns& c, const Eigen::Vector3d& x, double* slack,
                            std::size_t begin, std::size_t end, double rounding_distance) {
  const double* nx = c.nx();
  const double* ny = c.ny();
  const double* nz = c.nz();
  const double* d = c.d();
  double gx = 0.0, gy = 0.0, gz = 0.0;
  double least = std::numeric_limits<double>::infinity();
  for (std::size_t j = begin; j < end; ++j) {
    const double s = d[j] - (nx[j] * x.x() + ny[j] * x.y() + nz[j] * x.z());
    slack[j] = s;
    const double w = 2.0 * std::max(rounding_distance - s, 0.0);
    gx += w * nx[j];
    gy += w * ny[j];
    gz += w * nz[j];
    least = std::min(least, s);
  }
  if (rounding_distance - least > 0.0 || begin == end) return Eigen::Vector3d(gx, gy, gz);
  std::size_t j = begin;
  while (j < end && slack[j] != least) ++j;
  if (j == end) return Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  return 2.0 * rounding_distance * Eigen::Vector3d(nx[j], ny[j], nz[j]);
}

// The in-plane components (n_j·u, n_j·v) of the normals, for the slice's lines.
void fill_in_plane(const PlaneColumns& c, const Eigen::Vector3d& axis_u,
                   const Eigen::Vector3d& axis_v, PointColumns& pc) {
  for (std::size_t j = 0; j < c.size(); ++j) {
    pc.a_u[j] = c.nx()[j] * axis_u.x() + c.ny()[j] * axis_u.y() + c.nz()[j] * axis_u.z();
    pc.a_v[j] = c.nx()[j] * axis_v.x() + c.ny()[j] * axis_v.y() + c.nz()[j] * axis_v.z();
  }
}

// Fills the slacks at x.
void fill_slacks(const PlaneColumns& c, const Eigen::Vector3d& x, double* slack) {
  for (std::size_t j = 0; j < c.size(); ++j) {
    slack[j] = c.d()[j] - (c.nx()[j] * x.x() + c.ny()[j] * x.y() + c.nz()[j] * x.z());
  }
}

// Step 4 from the slacks at x: exit distances along +u and -u, summed. When `pc` is given, also
// fills the in-plane components for the axes (axis_u, axis_v), as fill_in_plane, in the same
// pass over the planes.
double chord_of(const PlaneColumns& c, const double* slack, const Eigen::Vector3d& u,
                PointColumns* pc, const Eigen::Vector3d& axis_u, const Eigen::Vector3d& axis_v) {
  const double* nx = c.nx();
  const double* ny = c.ny();
  const double* nz = c.nz();
  double forward = std::numeric_limits<double>::infinity();
  double backward = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < c.size(); ++j) {
    const double cos = nx[j] * u.x() + ny[j] * u.y() + nz[j] * u.z();
    if (cos > 1e-14) forward = std::min(forward, slack[j] / cos);
    if (cos < -1e-14) backward = std::min(backward, -slack[j] / cos);
    if (pc != nullptr) {
      pc->a_u[j] = nx[j] * axis_u.x() + ny[j] * axis_u.y() + nz[j] * axis_u.z();
      pc->a_v[j] = nx[j] * axis_v.x() + ny[j] * axis_v.y() + nz[j] * axis_v.z();
    }
  }
  return forward + backward;
}

// A start for the analytic centre when no earlier point is known. The LP's centre x* lies r*
// from its tight planes, which in a face contact include side walls of the thin overlap, and
// Newton's method leaves a near wall only by doubling its distance per step (about 15 steps
// across a 46 mm face from 10 µm). When two tight planes, one of each block, face each other
// (n_a·n_b < -0.99: a face contact), the centroid of the overlap's slice through x* normal to
// n_a - n_b is central instead. False (no start) otherwise or if the slice is empty. `edges`
// receives the slice's edge planes, a warm start for the contact's own slice.
bool face_contact_start(const PlaneColumns& c, std::size_t planes_a, const InscribedBall& ball,
                        double extent, Eigen::Vector3d& start, SliceWarmStart& edges) {
  double most_opposed = -0.99;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (int k = 0; k < ball.num_active; ++k) {
    for (int l = 0; l < ball.num_active; ++l) {
      const int i = ball.active[k], j = ball.active[l];
      if (i < 0 || j < 0 || static_cast<std::size_t>(i) >= planes_a ||
          static_cast<std::size_t>(j) < planes_a || static_cast<std::size_t>(j) >= c.size()) {
        continue;
      }
      const Eigen::Vector3d ni(c.nx()[i], c.ny()[i], c.nz()[i]);
      const Eigen::Vector3d nj(c.nx()[j], c.ny()[j], c.nz()[j]);
      if (ni.dot(nj) < most_opposed) {
        most_opposed = ni.dot(nj);
        normal = (ni - nj).normalized();
      }
    }
  }
  if (normal == Eigen::Vector3d::Zero()) return false;
  Eigen::Vector3d axis_u, axis_v;
  plane_axes(normal, axis_u, axis_v);
  PointColumns at_centre(c.size());
  fill_slacks(c, ball.center, at_centre.slack);
  fill_in_plane(c, axis_u, axis_v, at_centre);
  const SliceLines lines{at_centre.a_u, at_centre.a_v, at_centre.slack, c.size()};
  const SlicePolygon slice =
      slice_lines(lines, ball.center, normal, axis_u, axis_v, extent, &edges);
  if (!(slice.area() > 0.0)) return false;
  start = slice.to_world(slice.centroid_2d());
  return true;
}

}  // namespace

Eigen::Vector3d potential_gradient(std::span<const Halfspace> planes, const Eigen::Vector3d& x,
                                   double rounding_distance) {
  const PlaneColumns columns(planes);
  PointColumns at_x(planes.size());
  return gradient_of(columns, x, at_x.slack, 0, planes.size(), rounding_distance);
}

double chord_length(std::span<const Halfspace> planes, const Eigen::Vector3d& x,
                    const Eigen::Vector3d& u) {
  const PlaneColumns columns(planes);
  PointColumns at_x(planes.size());
  fill_slacks(columns, x, at_x.slack);
  return chord_of(columns, at_x.slack, u, nullptr, u, u);
}

namespace {

// Clears the cache if it was filled for other plane lists.
void match_cache(std::span<const Halfspace> planes_a, std::span<const Halfspace> planes_b,
                 Boon2012Cache* cache) {
  if (cache == nullptr) return;
  const int size_a = static_cast<int>(planes_a.size());
  const int size_b = static_cast<int>(planes_b.size());
  if (cache->planes_a == size_a && cache->planes_b == size_b) return;
  *cache = Boon2012Cache{};
  cache->planes_a = size_a;
  cache->planes_b = size_b;
}

// Steps 3 and 4 at the contact point x_c: the normal from the two inner potential particles,
// A to B, and the overlap, the chord of A∩B through x_c along it. Fills the slacks at x_c and
// the in-plane components for the normal's axes (axis_u, axis_v) for the slice.
void normal_and_overlap(const PlaneColumns& columns, std::size_t planes_a,
                        const Eigen::Vector3d& point, const Boon2012Settings& settings,
                        PointColumns& at_point, Eigen::Vector3d& normal, double& overlap,
                        Eigen::Vector3d& axis_u, Eigen::Vector3d& axis_v) {
  const double r = settings.rounding_distance;
  const Eigen::Vector3d ga = gradient_of(columns, point, at_point.slack, 0, planes_a, r);
  const Eigen::Vector3d gb =
      gradient_of(columns, point, at_point.slack, planes_a, columns.size(), r);
  normal = (ga - gb).normalized();
  plane_axes(normal, axis_u, axis_v);
  overlap = chord_of(columns, at_point.slack, normal, &at_point, axis_u, axis_v);
}

// Steps 2-5 given the LP solution for the planes of A then those of B.
// `columns` holds the planes of A (the first `planes_a`) followed by those of B.
ContactGeometry contact_from_ball(const PlaneColumns& columns, std::size_t planes_a,
                                  const InscribedBall& ball, double extent,
                                  const Boon2012Settings& settings, Boon2012Cache* cache) {
  ContactGeometry out;
  out.inscribed_radius = ball.radius;
  out.inscribed_centre = ball.center;
  if (!ball.bounded || !(ball.radius > settings.overlap_tolerance)) return out;
  out.touching = true;

  // 2. Contact point: analytic centre of all planes, from the previous step's point when it is
  //    still strictly inside, otherwise from the ball's centre or, when that is far from
  //    central, from a central point of a face contact's overlap.
  SliceWarmStart local_edges;
  SliceWarmStart& edges = cache != nullptr ? cache->slice : local_edges;
  AnalyticCentreResult centre;
  if (cache != nullptr && cache->has_point) centre = analytic_centre(columns, cache->last_point);
  if (!centre.start_inside) {
    // One Newton evaluation at x* tells whether it is already near the centre (λ < 1/4, the
    // quadratic phase: continue from there); if not, a face contact starts from its slice.
    centre = analytic_centre(columns, ball.center, 1);
    Eigen::Vector3d start = centre.point;
    if (!(centre.decrement < 0.25)) {
      face_contact_start(columns, planes_a, ball, extent, start, edges);
    }
    if (!centre.converged) centre = analytic_centre(columns, start);
  }
  out.point = centre.point;
  if (cache != nullptr) {
    cache->has_point = true;
    cache->last_point = out.point;
  }

  // 3-4. Normal and overlap.
  PointColumns at_point(columns.size());
  Eigen::Vector3d axis_u, axis_v;
  normal_and_overlap(columns, planes_a, out.point, settings, at_point, out.normal, out.overlap,
                     axis_u, axis_v);

  // 5. Contact area: the slice of A∩B by the plane through x_c normal to n.
  const SliceLines lines{at_point.a_u, at_point.a_v, at_point.slack, columns.size()};
  out.slice = slice_lines(lines, out.point, out.normal, axis_u, axis_v, extent, &edges);
  out.area = out.slice.area();
  return out;
}

}  // namespace

ContactGeometry boon2012_contact(std::span<const Halfspace> planes_a,
                                 std::span<const Halfspace> planes_b, double extent,
                                 const Boon2012Settings& settings, Boon2012Cache* cache) {
  // 1. Overlap test: the largest ball inside A∩B (4-variable LP), warm-started from this pair's
  //    solution at the previous step when the cache has one for the same plane lists.
  //    The planes are laid out column by column once, for every step below.
  match_cache(planes_a, planes_b, cache);
  const PlaneColumns columns(planes_a, planes_b);
  const bool warm = cache != nullptr && cache->has_ball;
  const InscribedBall ball =
      warm ? largest_inscribed_ball(columns, cache->ball) : largest_inscribed_ball(columns);
  if (cache != nullptr) {
    cache->ball = ball;
    cache->has_ball = true;
  }
  return contact_from_ball(columns, planes_a.size(), ball, extent, settings, cache);
}

void boon2012_normal_and_overlap(std::span<const Halfspace> planes_a,
                                 std::span<const Halfspace> planes_b, const Eigen::Vector3d& point,
                                 const Boon2012Settings& settings, Eigen::Vector3d& normal,
                                 double& overlap) {
  const PlaneColumns columns(planes_a, planes_b);
  PointColumns at_point(columns.size());
  Eigen::Vector3d axis_u, axis_v;
  normal_and_overlap(columns, planes_a.size(), point, settings, at_point, normal, overlap, axis_u,
                     axis_v);
}

ContactGeometry boon2012_contact_from_ball(std::span<const Halfspace> planes_a,
                                           std::span<const Halfspace> planes_b,
                                           const InscribedBall& ball, double extent,
                                           const Boon2012Settings& settings, Boon2012Cache* cache) {
  match_cache(planes_a, planes_b, cache);
  const PlaneColumns columns(planes_a, planes_b);
  return contact_from_ball(columns, planes_a.size(), ball, extent, settings, cache);
}

}  // namespace blockdem
