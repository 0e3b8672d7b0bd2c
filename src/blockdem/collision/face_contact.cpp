// Cells of linear closure over the projection of A∩B on the contact plane: the projection first,
// then the lower envelope of the upper planes and the upper envelope of the lower planes within it.
#include "blockdem/collision/face_contact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "blockdem/collision/slice_polygon.hpp"

namespace blockdem {
namespace {

// A linear function of the plane coordinates y = (a, b): f(y) = c0 + c·y.
struct Linear {
  double c0;
  Eigen::Vector2d c;
  // c0 + c·y with the dot product written out: the same operations as Eigen's c.dot(y)
  // (c_a y_a + c_b y_b), without its packing into one register and out again.
  double operator()(const Eigen::Vector2d& y) const { return c0 + (c.x() * y.x() + c.y() * y.y()); }
  Linear operator-(const Linear& o) const { return {c0 - o.c0, c - o.c}; }
};

// A convex polygon in a caller's buffer of sufficient capacity.
struct Polygon {
  Eigen::Vector2d* v = nullptr;
  int n = 0;
};

// Keeps the part of `poly` where f(y) <= 0 (Sutherland-Hodgman, one half-plane), writing the
// result into `spare` (a buffer as large as poly's, not poly's own) and pointing poly there; a
// polygon reduced below three vertices is emptied. A half-plane that keeps every vertex leaves
// poly untouched.
// Inlined at each of its few call sites: a clip is a few dozen operations on a handful of
// vertices, and the call itself cost a tenth of it.
[[gnu::always_inline]] inline void clip(Polygon& poly, const Linear& f, Eigen::Vector2d* spare,
                                        double* values) {
  if (poly.n == 0) return;
  // Which side each vertex is on decides whether anything is cut at all: some vertex is out
  // when the largest value is > 0, some in when the least is <= 0 (a NaN counts as neither).
  double largest = -std::numeric_limits<double>::infinity();
  double least = std::numeric_limits<double>::infinity();
  for (int i = 0; i < poly.n; ++i) {
    const double fp = f(poly.v[i]);
    values[i] = fp;
    largest = fp > largest ? fp : largest;
    least = fp < least ? fp : least;
  }
  if (!(largest > 0.0)) return;
  if (!(least <= 0.0)) {
    poly.n = 0;
    return;
  }
  int count = 0;
  for (int i = 0; i < poly.n; ++i) {
    const int j = i + 1 < poly.n ? i + 1 : 0;
    const Eigen::Vector2d& p = poly.v[i];
    const Eigen::Vector2d& q = poly.v[j];
    const double fp = values[i], fq = values[j];
    if (fp <= 0.0) spare[count++] = p;
    if ((fp < 0.0 && fq > 0.0) || (fp > 0.0 && fq < 0.0))
      spare[count++] = p + (fp / (fp - fq)) * (q - p);
  }
  poly.v = spare;
  poly.n = count >= 3 ? count : 0;
}

struct Box2 {
  Eigen::Vector2d lo, hi;
  bool meets(const Box2& o) const {
    return lo.x() <= o.hi.x() && o.lo.x() <= hi.x() && lo.y() <= o.hi.y() && o.lo.y() <= hi.y();
  }
};

[[gnu::always_inline]] inline Box2 box_of(const Polygon& p) {
  Box2 b{p.v[0], p.v[0]};
  for (int i = 1; i < p.n; ++i) {
    b.lo = b.lo.cwiseMin(p.v[i]);
    b.hi = b.hi.cwiseMax(p.v[i]);
  }
  return b;
}

// Where a half-plane f(y) <= 0 leaves a polygon, told from the polygon's box alone when the
// box is clearly on one side: f's bounds over the box, c0 + max (or min) of c_a y_a plus max (or
// min) of c_b y_b at its corners, are beyond a margin of 1e-12 of the terms' magnitude, while f
// at a vertex inside the box and the bounds themselves are formed within a few ulps of it. A clip
// the box tells keeps every vertex (inside) or none (outside), as clip() would find vertex by
// vertex; otherwise (unknown, or a NaN anywhere) clip() decides.
enum class BoxSide { inside, outside, unknown };
constexpr double kBoxMargin = 1e-12;
[[gnu::always_inline]] inline BoxSide box_side(const Linear& f, const Box2& box) {
  const double xa = f.c.x() * box.lo.x(), xb = f.c.x() * box.hi.x();
  const double ya = f.c.y() * box.lo.y(), yb = f.c.y() * box.hi.y();
  const double high = f.c0 + (std::max(xa, xb) + std::max(ya, yb));
  const double low = f.c0 + (std::min(xa, xb) + std::min(ya, yb));
  const double margin = kBoxMargin * (std::abs(f.c0) + std::max(std::abs(xa), std::abs(xb)) +
                                      std::max(std::abs(ya), std::abs(yb)));
  if (high <= -margin) return BoxSide::inside;
  if (low > margin) return BoxSide::outside;
  return BoxSide::unknown;
}

// Two buffers of one nesting level: a clip writes to the one that does not hold the polygon; a
// polygon of an outer level is read in place, so a level's polygons start as an outer one's
// without a copy.
struct Level {
  Eigen::Vector2d* first = nullptr;
  Eigen::Vector2d* spare = nullptr;
  double* values = nullptr;  // f at each vertex during a clip
  [[gnu::always_inline]] void clip_by(Polygon& poly, const Linear& f) {
    clip(poly, f, poly.v == first ? spare : first, values);
  }
  // clip_by told from `box`, the box of poly, where it can be (box_side); box stays poly's.
  [[gnu::always_inline]] void clip_within_box(Polygon& poly, const Linear& f, Box2& box) {
    const BoxSide side = box_side(f, box);
    if (side == BoxSide::inside) return;
    if (side == BoxSide::outside) {
      poly.n = 0;
      return;
    }
    clip_by(poly, f);
    if (poly.n > 0) box = box_of(poly);
  }
};

// Stack storage for the polygons (three nesting levels of two buffers) while the number of clips
// any polygon may see stays below kStackCapacity (cube pairs need at most 52); a heap buffer
// beyond.
constexpr int kBuffers = 6;
constexpr int kStackCapacity = 128;
// Planes of both blocks held on the stack (a heap table beyond).
constexpr std::size_t kFaceStackPlanes = 32;

}  // namespace

std::uint64_t planes_holding(std::span<const Halfspace> planes, const Eigen::Vector3d& box_min,
                             const Eigen::Vector3d& box_max, double clearance) {
  std::uint64_t held = 0;
  const std::size_t count = std::min<std::size_t>(planes.size(), 64);
  for (std::size_t j = 0; j < count; ++j) {
    // The box's farthest corner along n: each coordinate at the end where n_i x_i is larger.
    const Eigen::Vector3d& n = planes[j].normal;
    const double reach = std::max(n.x() * box_min.x(), n.x() * box_max.x()) +
                         std::max(n.y() * box_min.y(), n.y() * box_max.y()) +
                         std::max(n.z() * box_min.z(), n.z() * box_max.z());
    if (reach <= planes[j].offset - clearance) held |= std::uint64_t{1} << j;
  }
  return held;
}

FaceContactGeometry face_contact_geometry(std::span<const Halfspace> planes_a,
                                          std::span<const Halfspace> planes_b,
                                          const Eigen::Vector3d& origin,
                                          const Eigen::Vector3d& normal, double extent,
                                          const FaceContactSettings& settings,
                                          const ClosureOffset* offset, RedundantPlanes redundant) {
  FaceContactGeometry out;
  // The angle is the same for every contact of a run: its cosine is kept per thread.
  thread_local double cached_angle = std::numeric_limits<double>::quiet_NaN(), cached_cos = 1.0;
  if (!(settings.face_angle == cached_angle)) {
    cached_cos = std::cos(settings.face_angle);
    cached_angle = settings.face_angle;
  }
  const double cos_face = cached_cos;

  Eigen::Vector3d u, v;
  plane_axes(normal, u, v);
  // Every plane in plane coordinates: slack s(y) = s0 - (n·u) a - (n·v) b. Upper planes bound
  // the chord from above (t <= s/c), lower planes from below (t >= s/c), lateral ones the
  // plane region (-s <= 0).
  // The three lists live in one stack table (each as long as all planes together) up to
  // kFaceStackPlanes planes, in a heap buffer beyond.
  const std::size_t m = planes_a.size() + planes_b.size();
  std::array<Linear, 3 * kFaceStackPlanes> stack_lines;
  std::vector<Linear> heap_lines;
  Linear* lines = stack_lines.data();
  if (m > kFaceStackPlanes) {
    heap_lines.resize(3 * m);
    lines = heap_lines.data();
  }
  Linear* const top = lines;
  Linear* const bottom = lines + m;
  Linear* const lateral = lines + 2 * m;
  int nt = 0, nb = 0, nl = 0;
  // The same pass finds whether a block presents a face: A where one of its normals is within
  // the face angle of n, B where one is within it of -n.
  bool face = false;
  auto add = [&](const Halfspace& p, bool of_a, bool bounds_laterally, bool left_out) {
    const double c = p.normal.dot(normal);
    face |= of_a ? c > cos_face : c < -cos_face;
    if (left_out) return;
    const Linear slack{p.offset - p.normal.dot(origin),
                       Eigen::Vector2d(-p.normal.dot(u), -p.normal.dot(v))};
    if (bounds_laterally || std::abs(c) <= settings.lateral_tolerance) {
      lateral[nl++] = {-slack.c0, -slack.c};
    } else if (c > 0.0) {
      top[nt++] = {slack.c0 / c, slack.c / c};
    } else {
      bottom[nb++] = {slack.c0 / c, slack.c / c};
    }
  };
  // A prestressed face: only the two face planes close the chord; every other plane of either
  // block bounds the face laterally, by its trace on the contact plane.
  const auto lateral_for = [&](std::size_t j, int face_plane) {
    return offset != nullptr && static_cast<int>(j) != face_plane;
  };
  // Planes that do not bound A∩B (RedundantPlanes), never with a prestressed face.
  if (offset != nullptr) redundant = {};
  const auto left_out = [](std::uint64_t bits, std::size_t j) {
    return j < 64 && ((bits >> j) & 1U) != 0;
  };
  for (std::size_t j = 0; j < planes_a.size(); ++j) {
    const int before = nt;
    add(planes_a[j], true, lateral_for(j, offset != nullptr ? offset->plane_a : -1),
        left_out(redundant.a, j));
    // The closure added over A's face moves its end of the chord up by e(y), which is linear in
    // the plane coordinates: e(origin + a u + b v) = e(origin) + (e'·u) a + (e'·v) b.
    if (offset != nullptr && static_cast<int>(j) == offset->plane_a && nt > before) {
      top[before].c0 += offset->value + offset->gradient.dot(origin - offset->point);
      top[before].c += Eigen::Vector2d(offset->gradient.dot(u), offset->gradient.dot(v));
    }
  }
  const int top_a = nt, bottom_a = nb;
  for (std::size_t j = 0; j < planes_b.size(); ++j)
    add(planes_b[j], false, lateral_for(j, offset != nullptr ? offset->plane_b : -1),
        left_out(redundant.b, j));
  if (!face) return out;
  out.face_type = true;
  if (nt == 0 || nb == 0) return out;

  // A clip adds at most one vertex, and no polygon below sees more clips than this.
  const int capacity = 4 + nl + nt * nb + nt + nb;
  std::array<Eigen::Vector2d, kBuffers * kStackCapacity> stack_buffer;
  std::array<double, kStackCapacity> stack_values;
  std::vector<Eigen::Vector2d> heap_buffer;
  std::vector<double> heap_values;
  Eigen::Vector2d* buffer = stack_buffer.data();
  double* values = stack_values.data();
  int stride = kStackCapacity;
  if (capacity > kStackCapacity) {
    heap_buffer.resize(static_cast<std::size_t>(kBuffers) * static_cast<std::size_t>(capacity));
    heap_values.resize(static_cast<std::size_t>(capacity));
    stride = capacity;
    buffer = heap_buffer.data();
    values = heap_values.data();
  }
  Level outer{buffer, buffer + stride, values};
  Level middle{buffer + 2 * stride, buffer + 3 * stride, values};
  Level inner{buffer + 4 * stride, buffer + 5 * stride, values};

  // A region P' that contains the projection P of A∩B: the plane region where every pair of an
  // upper plane of one block and a lower plane of the other leaves a non-negative chord,
  // lower_k - upper_i <= 0 (the pairs of one block's own planes, which bound that block's own
  // projection, are left out: P' may exceed P, and the cells below are exact within any such
  // region, since within the region where i is the lowest upper plane and k the highest lower
  // one the chord is upper_i - lower_k and each cell is clipped to its being non-negative).
  Polygon region{outer.first, 4};
  region.v[0] = {-extent, -extent};
  region.v[1] = {extent, -extent};
  region.v[2] = {extent, extent};
  region.v[3] = {-extent, extent};
  for (int l = 0; l < nl; ++l) outer.clip_by(region, lateral[l]);
  if (region.n == 0) return out;
  // The box of the region as it stands (kept so after every clip below that may cut): most of
  // the clips below keep every vertex or none, which the box tells at once (box_side).
  Box2 region_box = box_of(region);
  for (int i = 0; i < nt && region.n > 0; ++i) {
    for (int k = 0; k < nb && region.n > 0; ++k) {
      if ((i < top_a) != (k < bottom_a))
        outer.clip_within_box(region, bottom[k] - top[i], region_box);
    }
  }
  if (region.n == 0) return out;

  // Ties (two planes giving the same chord end) go to the lower index, so that no region is
  // counted twice: plane i is the lowest upper plane where upper_i <= upper_j - tie for j < i
  // and upper_i <= upper_j for j > i (and likewise for the highest lower plane).
  const Linear tie{1e-12 * extent, Eigen::Vector2d::Zero()};
  // The region where plane i is the lowest (or highest) of `planes`: poly starts as the region
  // (its vertices are read, never written: a clip writes to the middle level's buffers) and box
  // as its box, kept the box of poly. Inlined at both calls: most of them are one box test.
  auto envelope_region = [&](const Linear* planes, int count, int i, bool lowest, Polygon& poly,
                             Box2& box) __attribute__((always_inline)) {
    for (int j = 0; j < count && poly.n > 0; ++j) {
      if (j == i) continue;
      const Linear below = lowest ? planes[i] - planes[j] : planes[j] - planes[i];
      middle.clip_within_box(poly, j < i ? Linear{below.c0 + tie.c0, below.c} : below, box);
    }
  };

  // Lower planes that are the highest somewhere in P', with the box of that region; the others
  // never bound a chord in P' and drop out of the cells' constraints.
  std::array<int, kFaceStackPlanes> stack_active;
  std::array<Box2, kFaceStackPlanes> stack_boxes;
  std::vector<int> heap_active;
  std::vector<Box2> heap_boxes;
  int* active_bottom = stack_active.data();
  Box2* bottom_box = stack_boxes.data();
  if (m > kFaceStackPlanes) {
    heap_active.resize(m);
    heap_boxes.resize(m);
    active_bottom = heap_active.data();
    bottom_box = heap_boxes.data();
  }
  int n_active = 0;
  for (int k = 0; k < nb; ++k) {
    Polygon poly = region;
    Box2 box = region_box;
    envelope_region(bottom, nb, k, false, poly, box);
    if (poly.n == 0) continue;
    active_bottom[n_active] = k;
    bottom_box[n_active++] = box;
  }

  // For each upper plane that is the lowest somewhere in P', the cell of each active lower plane
  // inside that region: clip to the pair's non-negative closure and to lower plane k being the
  // highest of the active ones.
  for (int i = 0; i < nt; ++i) {
    Polygon upper = region;
    Box2 upper_box = region_box;
    envelope_region(top, nt, i, true, upper, upper_box);
    if (upper.n == 0) continue;
    for (int a = 0; a < n_active; ++a) {
      if (!upper_box.meets(bottom_box[a])) continue;
      const int k = active_bottom[a];
      // Read from upper's buffer; a clip writes to the inner level's.
      Polygon poly = upper;
      Box2 box = upper_box;
      inner.clip_within_box(poly, bottom[k] - top[i], box);
      for (int b = 0; b < n_active && poly.n > 0; ++b) {
        const int j = active_bottom[b];
        if (j == k) continue;
        const Linear below = bottom[j] - bottom[k];
        inner.clip_by(poly, j < k ? Linear{below.c0 + tie.c0, below.c} : below);
      }
      if (poly.n == 0) continue;
      // Filled in place: a cell is a few hundred bytes, not worth a copy.
      ClosureCell& cell = out.cells.emplace_back();
      const Linear g = top[i] - bottom[k];
      for (int q = 0; q < poly.n; ++q) {
        const Eigen::Vector2d& y = poly.v[q];
        cell.vertices.push_back(origin + y.x() * u + y.y() * v);
        cell.closures.push_back(std::max(0.0, g(y)));
      }
    }
  }
  return out;
}

}  // namespace blockdem
