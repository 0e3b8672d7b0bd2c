// Sequential subdivision (Boon, Houlsby & Utili 2015, section 3): each block is cut by the joints
// that really cross it. Departure from the paper: the crossing test is the exact vertex test
// (a plane crosses a convex block iff vertices lie more than the cut tolerance on both sides),
// and the cut is an exact polygon clip (ConvexCell::split) instead of the paper's LP (its
// eq. 9), because the cells carry their vertices anyway. For non-persistent joints the paper's
// LP with extra extent constraints becomes an exact overlap of the block's section with the
// joint's disc or polygon. Joints of one set are parallel, so sorting them by offset and
// cutting each block by those inside its extent along the normal costs O(log J) per block.
#include "blockdem/rockmass/rock_slicer.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include <omp.h>

#include "blockdem/geometry/geometry_error.hpp"
#include "blockdem/numerics/shares.hpp"
#include "blockdem/rockmass/slicing_bounds.hpp"

namespace blockdem {
namespace {

[[noreturn]] void fail(const std::string& key, const std::string& why) {
  throw std::invalid_argument(key + ": " + why);
}

// Orthonormal in-plane axes (a1, a2) with a1 x a2 = n.
std::pair<Eigen::Vector3d, Eigen::Vector3d> in_plane_axes(const Eigen::Vector3d& n) {
  const Eigen::Vector3d seed =
      std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d a1 = (seed - seed.dot(n) * n).normalized();
  return {a1, n.cross(a1)};
}

// The region as the first cell; its faces keep the index of the plane they came from.
ConvexCell region_cell(const Region& region) {
  Polyhedron shape;
  try {
    shape = Polyhedron::from_planes(region.planes);
  } catch (const GeometryError& e) {
    fail("region", std::string("the region is not a closed convex solid: ") + e.what());
  }
  std::vector<FaceTag> tags;
  for (const auto& h : shape.planes()) {
    int found = -1;
    for (std::size_t i = 0; i < region.planes.size() && found < 0; ++i) {
      if ((region.planes[i].normal - h.normal).norm() < 1e-12 &&
          std::abs(region.planes[i].offset - h.offset) < 1e-12 * (1.0 + std::abs(h.offset)))
        found = static_cast<int>(i);
    }
    tags.push_back(FaceTag{FaceSource::region, found, -1, false});
  }
  return ConvexCell::from_polyhedron(shape, tags);
}

bool inside_convex(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& q) {
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector2d a = poly[i], b = poly[(i + 1) % poly.size()];
    if ((b - a).x() * (q - a).y() - (b - a).y() * (q - a).x() < 0.0) return false;
  }
  return true;
}

// A point drawn uniformly in the convex polygon p (in the plane's (s, dv) coordinates, inside
// the box [bmin, bmax]) by rejection. A polygon so thin that 10,000 draws miss it takes its
// vertex mean instead: the loop ends whatever its shape.
Eigen::Vector2d random_point(const std::vector<Eigen::Vector2d>& p, const Eigen::Vector2d& bmin,
                             const Eigen::Vector2d& bmax, PortableRandom& rng) {
  Eigen::Vector2d q;
  int tries = 0;
  do {
    if (++tries > 10000) {
      q = Eigen::Vector2d::Zero();
      for (const auto& x : p) q += x / static_cast<double>(p.size());
      break;
    }
    q = bmin + (bmax - bmin).cwiseProduct(Eigen::Vector2d(rng.uniform(), rng.uniform()));
  } while (!inside_convex(p, q));
  return q;
}

// The joints of one set inside the region, sorted by offset, and their extents; at most
// `max_planes` planes and `max_joints` joints (check_slicing_work refused more beforehand).
void place_joints(const JointSet& set, const ConvexCell& region, double snap, double max_planes,
                  double max_joints, std::vector<Joint>& joints,
                  std::vector<PlanarExtent>& extents) {
  const Eigen::Vector3d n = set.normal();
  const auto [lo, hi] = region.extent_along(n);
  std::vector<Joint> raw;
  if (!set.extent) {
    for (double d : joint_plane_offsets(set, lo, hi, max_planes))
      raw.push_back(Joint{d, true, Eigen::Vector3d::Zero()});
  } else if (!set.centres.empty()) {
    for (const auto& c : set.centres) raw.push_back(Joint{n.dot(c), false, c});
  } else {
    // Random centres on each joint plane, uniform over the region's section, as many as make
    // the covered fraction of the section's area equal to the persistence (overlaps allowed).
    PortableRandom rng(*set.placement_seed);
    const Eigen::Vector3d s = set.strike_vector(), dv = set.dip_vector();
    for (double d : joint_plane_offsets(set, lo, hi, max_planes)) {
      const auto sec = region.section(Halfspace{n, d}, snap);
      if (sec.size() < 3) continue;
      std::vector<Eigen::Vector2d> p;
      Eigen::Vector2d bmin = Eigen::Vector2d::Constant(1e300), bmax = -bmin;
      for (const auto& x : sec) {
        p.emplace_back(x.dot(s), x.dot(dv));
        bmin = bmin.cwiseMin(p.back());
        bmax = bmax.cwiseMax(p.back());
      }
      if (signed_area(p) < 0.0) std::reverse(p.begin(), p.end());
      const double area = signed_area(p);
      if (!(area > 0.0)) continue;  // a section without area: no joint lies on it
      const double want = std::max(1.0, std::round(set.persistence * area / set.extent->area()));
      if (!(static_cast<double>(raw.size()) + want <= max_joints))
        throw std::invalid_argument("extent: more joints than the limit of " +
                                    std::to_string(static_cast<long long>(max_joints)));
      const auto count = static_cast<long>(want);
      for (long k = 0; k < count; ++k) {
        const Eigen::Vector2d q = random_point(p, bmin, bmax, rng);
        raw.push_back(Joint{d, false, n * d + q.x() * s + q.y() * dv});
      }
    }
  }
  std::vector<std::size_t> order(raw.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return raw[a].offset < raw[b].offset; });
  for (std::size_t i : order) {
    joints.push_back(raw[i]);
    if (raw[i].persistent) continue;
    PlanarExtent e;
    e.plane = Halfspace{n, raw[i].offset};
    e.centre = raw[i].centre;
    e.axis1 = set.strike_vector();
    e.axis2 = set.dip_vector();
    if (set.extent->shape == JointExtent::Shape::disc) {
      e.disc = true;
      e.radius = set.extent->radius;
    } else {
      const double a = 0.5 * set.extent->size.x(), b = 0.5 * set.extent->size.y();
      e.polygon = {{-a, -b}, {a, -b}, {a, b}, {-a, b}};
    }
    extents.push_back(std::move(e));
  }
}

// The outline facets of a convex excavation: each plane's polygon inside the region and the
// excavation's other planes.
std::vector<PlanarExtent> outline_facets(const Excavation& ex, const ConvexCell& region,
                                         double snap) {
  std::vector<PlanarExtent> out;
  for (std::size_t j = 0; j < ex.planes.size(); ++j) {
    PlanarExtent e;
    e.plane = ex.planes[j];
    std::tie(e.axis1, e.axis2) = in_plane_axes(e.plane.normal);
    const auto sec = region.section(e.plane, snap);
    if (sec.size() >= 3) {
      e.centre = e.plane.normal * e.plane.offset;
      std::vector<Eigen::Vector2d> poly;
      for (const auto& x : sec)
        poly.emplace_back((x - e.centre).dot(e.axis1), (x - e.centre).dot(e.axis2));
      if (signed_area(poly) < 0.0) std::reverse(poly.begin(), poly.end());
      // Clip by the other planes: n_k·(c + x a1 + y a2) <= d_k.
      for (std::size_t k = 0; k < ex.planes.size() && poly.size() >= 3; ++k) {
        if (k == j) continue;
        const auto& h = ex.planes[k];
        const Eigen::Vector2d g(h.normal.dot(e.axis1), h.normal.dot(e.axis2));
        const double c = h.offset - h.normal.dot(e.centre);
        std::vector<Eigen::Vector2d> clipped;
        for (std::size_t i = 0; i < poly.size(); ++i) {
          const Eigen::Vector2d p = poly[i], q = poly[(i + 1) % poly.size()];
          const double sp = c - g.dot(p), sq = c - g.dot(q);
          if (sp >= 0.0) clipped.push_back(p);
          if ((sp >= 0.0) != (sq >= 0.0)) clipped.push_back(p + sp / (sp - sq) * (q - p));
        }
        poly = std::move(clipped);
      }
      if (poly.size() >= 3 && std::abs(signed_area(poly)) > snap * snap) e.polygon = poly;
    }
    out.push_back(std::move(e));
  }
  return out;
}

// What the cuts of a share of the cells leave behind: the parts, in the order the cells came,
// and the merged or removed parts' counts and volumes. The volumes are kept one by one so that
// the shares' tallies sum in the order of one pass over every cell (bit-identical sums for any
// number of threads).
struct CutTally {
  std::vector<ConvexCell> done;
  int merged_cuts = 0;
  int removed_blocks = 0;
  std::vector<double> merged_volumes, removed_volumes;
};

class Slicer {
 public:
  Slicer(const SlicingSettings& s, double tol, CutTally& out) : s_(s), tol_(tol), out_(out) {}

  // Cuts `cell` by the sorted parallel joints (normal n) in [first, last) that cross it, and
  // appends the parts to the tally's `done`.
  void cut_by_set(ConvexCell cell, const Eigen::Vector3d& n, const std::vector<Joint>& joints,
                  const std::vector<PlanarExtent>* extents, FaceTag tag) {
    std::vector<ConvexCell>& done = out_.done;
    auto [lo, hi] = cell.extent_along(n);
    auto it = std::upper_bound(joints.begin(), joints.end(), lo + tol_,
                               [](double v, const Joint& j) { return v < j.offset; });
    bool alive = true;
    // `extents`, when given, runs parallel to `joints` (a non-persistent set).
    for (auto i = static_cast<std::size_t>(it - joints.begin());
         i < joints.size() && joints[i].offset < hi - tol_; ++i) {
      const Halfspace plane{n, joints[i].offset};
      if (joints[i].offset <= lo + tol_) continue;
      if (extents && overlap(cell.section(plane, snap()), (*extents)[i], tol_) == Overlap::none)
        continue;
      tag.joint = static_cast<int>(i);
      auto parts = cell.split(plane, tag, snap());
      if (!parts) continue;
      const bool small_below = too_small(parts->below);
      const bool small_above = too_small(parts->above);
      if (small_below || small_above) {
        if (s_.small_blocks == SlicingSettings::SmallBlocks::merge) {
          ++out_.merged_cuts;
          out_.merged_volumes.push_back(std::min(parts->below.volume(), parts->above.volume()));
          continue;
        }
        if (small_below) remove(parts->below);
        if (small_above) {
          remove(parts->above);
          if (!small_below) done.push_back(std::move(parts->below));
          alive = false;
          break;
        }
      }
      if (!small_below) done.push_back(std::move(parts->below));
      cell = std::move(parts->above);
      lo = joints[i].offset;
    }
    if (alive) done.push_back(std::move(cell));
  }

 private:
  double snap() const { return 1e-3 * tol_; }
  bool too_small(const ConvexCell& c) const {
    return c.volume() < s_.min_block_volume ||
           (s_.max_aspect_ratio > 0.0 && c.aspect_ratio() > s_.max_aspect_ratio);
  }
  void remove(const ConvexCell& c) {
    ++out_.removed_blocks;
    out_.removed_volumes.push_back(c.volume());
  }

  const SlicingSettings& s_;
  double tol_;
  CutTally& out_;
};

// Cuts every cell by the joints (normal n) on `threads` threads: each takes a contiguous share of
// the cells, and the shares' parts and tallies are joined in the cells' order, so the parts, their
// order and the sums are those of one thread.
void cut_cells(std::vector<ConvexCell>& cells, const SlicingSettings& settings, double tol,
               const Eigen::Vector3d& n, const std::vector<Joint>& joints,
               const std::vector<PlanarExtent>* extents, const FaceTag& tag, int threads,
               RockMass& rm) {
  const std::int64_t count = static_cast<std::int64_t>(cells.size());
  const std::int64_t shares = share_count(count, threads, 8);
  std::vector<CutTally> tally(static_cast<std::size_t>(shares));
  for_each_share(shares, count, threads, [&](std::int64_t k, std::int64_t begin, std::int64_t end) {
    CutTally& t = tally[static_cast<std::size_t>(k)];
    t.done.reserve(static_cast<std::size_t>(2 * (end - begin)));
    Slicer slicer(settings, tol, t);
    for (std::int64_t i = begin; i < end; ++i)
      slicer.cut_by_set(std::move(cells[static_cast<std::size_t>(i)]), n, joints, extents, tag);
  });
  std::size_t parts = 0;
  for (const auto& t : tally) parts += t.done.size();
  std::vector<ConvexCell> next;
  next.reserve(parts);
  for (auto& t : tally) {
    for (auto& c : t.done) next.push_back(std::move(c));
    std::vector<ConvexCell>().swap(t.done);
    rm.merged_cuts += t.merged_cuts;
    rm.removed_blocks += t.removed_blocks;
    for (double v : t.merged_volumes) rm.merged_volume += v;
    for (double v : t.removed_volumes) rm.removed_volume += v;
  }
  cells = std::move(next);
}

}  // namespace

Region Region::box(const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
  Region r;
  const char* names[3][2] = {{"x_min", "x_max"}, {"y_min", "y_max"}, {"z_min", "z_max"}};
  for (int axis = 0; axis < 3; ++axis) {
    r.planes.push_back(Halfspace{-Eigen::Vector3d::Unit(axis), -min[axis]});
    r.face_names.emplace_back(names[axis][0]);
    r.planes.push_back(Halfspace{Eigen::Vector3d::Unit(axis), max[axis]});
    r.face_names.emplace_back(names[axis][1]);
  }
  return r;
}

Region Region::from_planes(std::vector<Halfspace> planes) {
  Region r;
  r.planes = std::move(planes);
  for (std::size_t i = 0; i < r.planes.size(); ++i)
    r.face_names.push_back("plane_" + std::to_string(i));
  return r;
}

double RockMass::total_volume() const {
  double v = 0.0;
  for (const auto& b : blocks) v += b.volume();
  return v;
}

std::vector<int> RockMass::blocks_inside(const RockMassSpec& spec, int e) const {
  std::vector<int> out;
  const auto& planes = spec.excavations.at(e).planes;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const Eigen::Vector3d& c = blocks[i].centroid();
    if (std::all_of(planes.begin(), planes.end(),
                    [&](const Halfspace& h) { return h.signed_distance(c) < 0.0; }))
      out.push_back(static_cast<int>(i));
  }
  return out;
}

RockMass slice_rock_mass(const RockMassSpec& spec) {
  RockMass rm;
  rm.region_face_names = spec.region.face_names;
  const ConvexCell region = region_cell(spec.region);
  rm.region_volume = region.volume();
  double diameter = 0.0;
  for (const auto& v : region.vertices())
    diameter = std::max(diameter, (v - region.vertices().front()).norm());
  const double tol =
      spec.settings.cut_tolerance > 0.0 ? spec.settings.cut_tolerance : 1e-6 * diameter;
  rm.cut_tolerance = tol;
  if (spec.settings.min_block_volume < 0.0) fail("min_block_volume", "must be >= 0");
  if (spec.settings.max_aspect_ratio < 0.0) fail("max_aspect_ratio", "must be >= 0");

  for (std::size_t s = 0; s < spec.joint_sets.size(); ++s) {
    try {
      spec.joint_sets[s].validate();
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("joint_sets[" + std::to_string(s + 1) + "]." + e.what());
    }
  }
  // Before any joint is placed: what does not fit in memory or time is refused.
  check_slicing_work(spec, region);

  const int threads = spec.settings.threads > 0 ? spec.settings.threads : omp_get_max_threads();
  std::vector<ConvexCell> cells{region};
  for (std::size_t s = 0; s < spec.joint_sets.size(); ++s) {
    const JointSet& set = spec.joint_sets[s];
    rm.joints.emplace_back();
    rm.joint_extents.emplace_back();
    try {
      place_joints(set, region, 1e-3 * tol, static_cast<double>(spec.settings.max_blocks),
                   static_cast<double>(spec.settings.max_joints), rm.joints.back(),
                   rm.joint_extents.back());
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("joint_sets[" + std::to_string(s + 1) + "]." + e.what());
    }
    const FaceTag tag{FaceSource::joint, static_cast<int>(s), -1, false};
    const auto* ext = set.extent ? &rm.joint_extents.back() : nullptr;
    cut_cells(cells, spec.settings, tol, set.normal(), rm.joints.back(), ext, tag, threads, rm);
  }
  for (std::size_t e = 0; e < spec.excavations.size(); ++e) {
    rm.facets.push_back(outline_facets(spec.excavations[e], region, 1e-3 * tol));
    const auto& facets = rm.facets.back();
    if (std::all_of(facets.begin(), facets.end(),
                    [](const PlanarExtent& f) { return f.polygon.empty(); })) {
      // No outline inside the region: the excavation is outside it or contains all of it.
      fail("excavations[" + std::to_string(e + 1) + "]",
           "the excavation \"" + spec.excavations[e].name + "\" has no outline inside the region");
    }
    // Each facet cuts every cell it crosses: one joint, bounded by the facet's polygon.
    for (std::size_t j = 0; j < facets.size(); ++j) {
      const PlanarExtent& facet = facets[j];
      if (facet.polygon.empty()) continue;
      const std::vector<Joint> one{Joint{facet.plane.offset, false, facet.centre}};
      const std::vector<PlanarExtent> ext{facet};
      cut_cells(cells, spec.settings, tol, facet.plane.normal, one, &ext,
                FaceTag{FaceSource::excavation, static_cast<int>(e), static_cast<int>(j), false},
                threads, rm);
    }
  }
  // Bonded faces: a cut face of a non-persistent joint or an outline facet is an open joint only
  // where the face lies wholly inside the joint's extent; elsewhere it is intact rock. The cells
  // are kept with the rock mass: no spare capacity from the cuts' push_backs.
  const std::int64_t count = static_cast<std::int64_t>(cells.size());
  for_each_share(share_count(count, threads, 64), count, threads,
                 [&](std::int64_t, std::int64_t begin, std::int64_t end) {
                   for (std::int64_t i = begin; i < end; ++i) {
                     ConvexCell& c = cells[static_cast<std::size_t>(i)];
                     for (int f = 0; f < static_cast<int>(c.faces().size()); ++f) {
                       FaceTag& t = c.faces()[f].tag;
                       const PlanarExtent* ext = nullptr;
                       if (t.source == FaceSource::joint && spec.joint_sets[t.index].extent)
                         ext = &rm.joint_extents[t.index][t.joint];
                       if (t.source == FaceSource::excavation) ext = &rm.facets[t.index][t.joint];
                       if (ext) t.bonded = overlap(c.face_polygon(f), *ext, tol) != Overlap::inside;
                     }
                     c.shrink_to_fit();
                   }
                 });
  rm.blocks = std::move(cells);
  for (std::size_t e = 0; e < spec.excavations.size(); ++e) {
    if (rm.blocks_inside(spec, static_cast<int>(e)).empty())
      fail(
          "excavations[" + std::to_string(e + 1) + "]",
          "no block of the region lies inside the excavation \"" + spec.excavations[e].name + "\"");
  }
  return rm;
}

}  // namespace blockdem
