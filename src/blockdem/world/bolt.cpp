// Rock bolts: the line through the blocks, installation, and the loads of tendon, grout and
// dowels on the blocks at each step.
#include "blockdem/world/bolt.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "blockdem/geometry/segment_clip.hpp"
#include "blockdem/numerics/number_text.hpp"

namespace blockdem {

void BoltSpec::validate() const {
  const auto fail = [](const std::string& key, const std::string& why) {
    throw std::invalid_argument(key + ": " + why);
  };
  if (!start.allFinite()) fail("start", "must be a finite point (m)");
  if (!direction.allFinite() || std::abs(direction.norm() - 1.0) > 1e-9)
    fail("direction", "must be a unit vector");
  if (!(length > 0.0) || !std::isfinite(length)) fail("length", "must be a positive length (m)");
  if (!(axial_stiffness > 0.0) || !std::isfinite(axial_stiffness))
    fail("axial_stiffness", "must be positive (N/m)");
  if (!(yield_force > 0.0)) fail("yield_force", "must be positive (N)");
  if (!(rupture_strain > 0.0)) fail("rupture_strain", "must be positive (-)");
  if (!(bond_stiffness >= 0.0) || !std::isfinite(bond_stiffness))
    fail("bond_stiffness", "must be positive (N/m/m)");
  if (!(bond_strength > 0.0)) fail("bond_strength", "must be positive (N/m)");
  if (!(shear_stiffness >= 0.0) || !std::isfinite(shear_stiffness))
    fail("shear_stiffness", "must be zero or positive (N/m)");
  if (!(shear_capacity > 0.0)) fail("shear_capacity", "must be positive (N)");
  if (!(shear_rupture_displacement > 0.0))
    fail("shear_rupture_displacement", "must be positive (m)");
  if (std::isfinite(shear_rupture_displacement) && !(shear_stiffness > 0.0))
    fail("shear_rupture_displacement", "needs a dowel (shear_stiffness)");
  if (!(pretension >= 0.0) || !std::isfinite(pretension))
    fail("pretension", "must be zero or positive (N)");
  if (pretension >= yield_force) fail("pretension", "must be below yield_force");
  if (pretension > 0.0 && grouted())
    fail("pretension",
         "a pretension needs a point-anchored bolt (no bond_stiffness): a grouted tendon is "
         "tensioned before the grout sets, which this element does not model");
}

const char* to_string(Bolt::State state) {
  switch (state) {
    case Bolt::State::intact:
      return "intact";
    case Bolt::State::yielded:
      return "yielded";
    case Bolt::State::ruptured:
      return "ruptured";
    case Bolt::State::removed:
      return "removed";
  }
  return "intact";
}

std::vector<Halfspace> planes_at_pose(const Block& block) {
  std::vector<Halfspace> planes;
  const Eigen::Matrix3d r = block.rotation();
  for (const Halfspace& h : block.shape.planes()) {
    const Eigen::Vector3d n = r * h.normal;
    planes.push_back({n, h.offset + n.dot(block.position)});
  }
  return planes;
}

PosedBlock posed_block(const Block& block) {
  PosedBlock p;
  for (const auto& v : block.shape.vertices()) p.vertices.push_back(block.to_world(v));
  p.planes = planes_at_pose(block);
  return p;
}

std::vector<BoltSpan> bolt_spans(const BoltSpec& spec, const std::vector<Block>& blocks) {
  const Eigen::Vector3d p0 = spec.start;
  const Eigen::Vector3d p1 = spec.start + spec.length * spec.direction;
  std::vector<BoltSpan> spans;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const Block& b = blocks[i];
    // Far from the segment: no part of it inside.
    const Eigen::Vector3d rel = b.position - p0;
    const double s = std::clamp(rel.dot(spec.direction), 0.0, spec.length);
    if ((rel - s * spec.direction).norm() > b.shape.bounding_radius()) continue;
    const auto t = clip_segment(planes_at_pose(b), p0, p1);
    if (!t) continue;
    const double from = t->first * spec.length, to = t->second * spec.length;
    if (to - from <= 1e-9 * spec.length) continue;
    spans.push_back({static_cast<int>(i), from, to});
  }
  std::stable_sort(spans.begin(), spans.end(),
                   [](const BoltSpan& x, const BoltSpan& y) { return x.from < y.from; });
  return spans;
}

std::string bolt_span_problem(const BoltSpec& spec, const std::vector<BoltSpan>& spans,
                              const std::vector<Block>& blocks) {
  // A collar or far end off the rock by up to 1 % of the length (a face that settled since the
  // file was written) ties at the point given.
  const double tol = 0.01 * spec.length;
  const auto name = [&](int i) { return "'" + blocks[static_cast<std::size_t>(i)].name + "'"; };
  if (spans.empty())
    return "the collar (start) lies outside every block, and the line (direction, length) "
           "passes through none";
  if (spans.front().from > tol)
    return "the collar (start) lies outside every block: the line first enters block " +
           name(spans.front().block) + " " + number_text(spans.front().from, "%.6g") +
           " m along it";
  for (std::size_t k = 1; k < spans.size(); ++k) {
    const double gap = spans[k].from - spans[k - 1].to;
    if (gap > 0.01 * spec.length)
      return "the line leaves the rock for " + number_text(gap, "%.6g") + " m between blocks " +
             name(spans[k - 1].block) + " and " + name(spans[k].block);
  }
  double end = 0.0;
  for (const BoltSpan& s : spans) end = std::max(end, s.to);
  if (end < spec.length - tol)
    return "the far end lies outside the rock: the line leaves the last block at " +
           number_text(end, "%.6g") + " m of its " + number_text(spec.length, "%.6g") + " m";
  if (spans.size() < 2)
    return "the bolt crosses no joint: all of it lies in block " + name(spans.front().block);
  return {};
}

namespace {

/// Where a world point sits in a block's body frame.
Eigen::Vector3d body_point(const Block& b, const Eigen::Vector3d& x) {
  return b.orientation.conjugate() * (x - b.position);
}

BoltTie tie(int block, const Block& b, const Eigen::Vector3d& x) {
  return {block, body_point(b, x), x};
}

/// The arc length where the bolt crosses from span k to span k + 1: midway across the joint.
double crossing_at(const std::vector<BoltSpan>& spans, std::size_t k) {
  return 0.5 * (spans[k].to + spans[k + 1].from);
}

/// An elastic-perfectly plastic member: its force k (x - plastic) capped at ±cap; the plastic
/// part moves so that the force stays on the cap. Returns whether it yielded.
bool plastic_member(double k, double cap, double x, double& plastic, double& force) {
  force = k * (x - plastic);
  if (std::abs(force) <= cap) return false;
  const double capped = std::copysign(cap, force);
  plastic += (force - capped) / k;
  force = capped;
  return true;
}

/// A tendon solve's vectors, kept per thread between solves.
struct TendonWork {
  std::vector<char> yielded_e, yielded_s, next_e, next_s;
  std::vector<double> diag, off, rhs, delta;
};

}  // namespace

bool Tendon::solve(std::span<const double> rock) {
  const std::size_t n = u.size() - 1;  // unknowns u[1..n]
  const auto element_trial = [&](std::size_t e) {
    return elements[e].stiffness * (u[e + 1] - u[e] - elements[e].plastic);
  };
  const auto spring_trial = [&](std::size_t k) {
    const Spring& s = springs[k];
    return s.stiffness * (u[static_cast<std::size_t>(s.node)] - rock[k] - s.slip);
  };
  // The solve's vectors are kept per thread from one solve to the next: a step solves every
  // bolt's tendon, and allocating them each time cost as much as the arithmetic.
  thread_local TendonWork work;
  // Per member: yielded at the present u (its force the cap, its tangent ~0).
  std::vector<char>& yielded_e = work.yielded_e;
  std::vector<char>& yielded_s = work.yielded_s;
  std::vector<char>& next_e = work.next_e;
  std::vector<char>& next_s = work.next_s;
  yielded_e.resize(elements.size());
  yielded_s.resize(springs.size());
  next_e.resize(elements.size());
  next_s.resize(springs.size());
  const auto classify = [&](std::vector<char>& ye, std::vector<char>& ys) {
    for (std::size_t e = 0; e < elements.size(); ++e)
      ye[e] = std::abs(element_trial(e)) > yield_force ? 1 : 0;
    for (std::size_t k = 0; k < springs.size(); ++k)
      ys[k] = std::abs(spring_trial(k)) > springs[k].strength ? 1 : 0;
  };
  classify(yielded_e, yielded_s);
  std::vector<double>& diag = work.diag;
  std::vector<double>& off = work.off;
  std::vector<double>& rhs = work.rhs;
  std::vector<double>& delta = work.delta;
  diag.resize(n + 1);
  off.resize(n + 1);
  rhs.resize(n + 1);
  delta.resize(n + 1);
  for (int iteration = 0; iteration < 64; ++iteration) {
    // Newton on the residual R_i = N_i - N_{i-1} - Σ g (forces on node i along the bolt), the
    // yielded members at their caps; a floor of 1e-9 of a member's stiffness keeps the matrix
    // regular where every member at a node has yielded.
    std::fill(diag.begin(), diag.end(), 0.0);
    std::fill(off.begin(), off.end(), 0.0);
    std::fill(rhs.begin(), rhs.end(), 0.0);
    for (std::size_t e = 0; e < elements.size(); ++e) {
      const double trial = element_trial(e);
      const double f = yielded_e[e] ? std::copysign(yield_force, trial) : trial;
      const double k = elements[e].stiffness * (yielded_e[e] ? 1e-9 : 1.0);
      rhs[e] += f;  // pulls node e along +
      rhs[e + 1] -= f;
      diag[e] += k;
      diag[e + 1] += k;
      off[e] -= k;  // between e and e + 1
    }
    for (std::size_t k = 0; k < springs.size(); ++k) {
      const auto i = static_cast<std::size_t>(springs[k].node);
      const double trial = spring_trial(k);
      const double g = yielded_s[k] ? std::copysign(springs[k].strength, trial) : trial;
      rhs[i] -= g;
      diag[i] += springs[k].stiffness * (yielded_s[k] ? 1e-9 : 1.0);
    }
    // K δ = R over nodes 1..n (node 0 is the plate's, given): the Thomas algorithm. Every
    // δ_i, i >= 1, is written before it is read.
    for (std::size_t i = 2; i <= n; ++i) {
      const double m = off[i - 1] / diag[i - 1];
      diag[i] -= m * off[i - 1];
      rhs[i] -= m * rhs[i - 1];
    }
    for (std::size_t i = n; i >= 1; --i) {
      delta[i] = (rhs[i] - (i < n ? off[i] * delta[i + 1] : 0.0)) / diag[i];
    }
    for (std::size_t i = 1; i <= n; ++i) u[i] += delta[i];
    classify(next_e, next_s);
    if (next_e == yielded_e && next_s == yielded_s) break;
    yielded_e.swap(next_e);
    yielded_s.swap(next_s);
  }
  bool yielded = false;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    Element& el = elements[e];
    yielded |= plastic_member(el.stiffness, yield_force, u[e + 1] - u[e], el.plastic, el.force);
  }
  for (std::size_t k = 0; k < springs.size(); ++k) {
    Spring& s = springs[k];
    yielded |= plastic_member(s.stiffness, s.strength,
                              u[static_cast<std::size_t>(s.node)] - rock[k], s.slip, s.force);
  }
  return yielded;
}

double Tendon::plate_force() const {
  double f = elements.empty() ? 0.0 : elements.front().force;
  for (const Spring& s : springs) {
    if (s.node == 0) f -= s.force;
  }
  return f;
}

double Bolt::largest_axial_force(double from, double to) const {
  if (!spec.grouted()) return axial_force;
  double best = 0.0;
  for (std::size_t e = 0; e < tendon.elements.size(); ++e) {
    if (node_at[e + 1] <= from || node_at[e] >= to) continue;
    const double f = tendon.elements[e].force;
    if (std::abs(f) > std::abs(best)) best = f;
  }
  return best;
}

Bolt install_bolt(const BoltSpec& spec, std::vector<BoltSpan> spans,
                  const std::vector<Block>& blocks) {
  spec.validate();
  Bolt bolt;
  bolt.spec = spec;
  bolt.spans = std::move(spans);
  const auto& sp = bolt.spans;
  const auto block = [&](int i) -> const Block& { return blocks[static_cast<std::size_t>(i)]; };
  const auto point = [&](double s) -> Eigen::Vector3d { return spec.start + s * spec.direction; };
  for (std::size_t k = 0; k + 1 < sp.size(); ++k) {
    const double at = crossing_at(sp, k);
    const Eigen::Vector3d x = point(at);
    BoltCrossing c;
    c.block_a = sp[k].block;
    c.block_b = sp[k + 1].block;
    c.body_a = body_point(block(c.block_a), x);
    c.body_b = body_point(block(c.block_b), x);
    c.at = at;
    bolt.crossings.push_back(c);
  }
  if (!spec.grouted()) {
    // Point-anchored: the head at the collar, the anchor at the far end.
    bolt.ties = {tie(sp.front().block, block(sp.front().block), point(0.0)),
                 tie(sp.back().block, block(sp.back().block), point(spec.length))};
    bolt.node_at = {0.0, spec.length};
    bolt.anchored_length = spec.length;
    bolt.axial_force = spec.pretension;
    return bolt;
  }
  // Grouted: elements no longer than h_max, nodes at every crossing, springs lumped at the
  // nodes of each element (half its length to each end), in the element's block.
  const double alpha = std::sqrt(spec.bond_stiffness / spec.axial_rigidity());
  const double h_max = std::min(spec.length / 64.0, 0.25 / alpha);
  Tendon& t = bolt.tendon;
  t.yield_force = spec.yield_force;
  bolt.node_at.push_back(0.0);
  for (std::size_t k = 0; k < sp.size(); ++k) {
    const double from = k == 0 ? 0.0 : crossing_at(sp, k - 1);
    const double to = k + 1 == sp.size() ? spec.length : crossing_at(sp, k);
    const int m = std::max(1, static_cast<int>(std::ceil((to - from) / h_max - 1e-9)));
    const Block& b = block(sp[k].block);
    for (int j = 0; j < m; ++j) {
      const double s0 = from + (to - from) * j / m;
      const double s1 = j + 1 == m ? to : from + (to - from) * (j + 1) / m;
      const double h = s1 - s0;
      const int node = static_cast<int>(bolt.node_at.size()) - 1;
      bolt.node_at.push_back(s1);
      t.elements.push_back({spec.axial_rigidity() / h, 0.0, 0.0});
      for (int end = 0; end < 2; ++end) {
        const double s = end == 0 ? s0 : s1;
        t.springs.push_back(
            {node + end, 0.5 * h * spec.bond_stiffness, 0.5 * h * spec.bond_strength, 0.0, 0.0});
        bolt.ties.push_back(tie(sp[k].block, b, point(s)));
      }
    }
  }
  t.u.assign(bolt.node_at.size(), 0.0);
  bolt.ties.push_back(tie(sp.front().block, block(sp.front().block), point(0.0)));  // the plate
  return bolt;
}

void bolt_loads(Bolt& bolt, const std::vector<Block>& blocks, std::vector<BoltLoad>& loads) {
  loads.clear();
  if (!bolt.active()) return;
  const BoltSpec& spec = bolt.spec;
  const auto world = [&](const BoltTie& t) -> Eigen::Vector3d {
    return blocks[static_cast<std::size_t>(t.block)].to_world(t.body_point);
  };
  const auto add = [&](int block, const Eigen::Vector3d& f, const Eigen::Vector3d& x, double k) {
    loads.push_back({block, f, x, k});
  };
  // A dowel sheared to its rupture displacement at any crossing breaks the bolt, before any of
  // its forces of this step (as a tendon that ruptures): the shear across the bolt's axis (the
  // head-anchor line of a point-anchored bolt, the installed direction of a grouted one).
  if (std::isfinite(spec.shear_rupture_displacement)) {
    Eigen::Vector3d line = spec.direction;
    if (!spec.grouted()) line = (world(bolt.ties[1]) - world(bolt.ties[0])).normalized();
    for (const BoltCrossing& c : bolt.crossings) {
      const Eigen::Vector3d d = blocks[static_cast<std::size_t>(c.block_b)].to_world(c.body_b) -
                                blocks[static_cast<std::size_t>(c.block_a)].to_world(c.body_a);
      if ((d - d.dot(line) * line).norm() >= spec.shear_rupture_displacement) {
        bolt.state = Bolt::State::ruptured;
        bolt.axial_force = 0.0;
        return;
      }
    }
  }
  bool yielded = false;
  Eigen::Vector3d axis = spec.direction;
  if (!spec.grouted()) {
    // Point-anchored: one tendon between head and anchor, slack in compression.
    const Eigen::Vector3d x0 = world(bolt.ties[0]), x1 = world(bolt.ties[1]);
    const double l = (x1 - x0).norm();
    axis = (x1 - x0) / l;
    const double k = spec.axial_stiffness;
    const double strain =
        (l - bolt.anchored_length) / bolt.anchored_length + spec.pretension / spec.axial_rigidity();
    bolt.largest_strain = std::max(bolt.largest_strain, strain);
    if (strain > spec.rupture_strain) {
      bolt.state = Bolt::State::ruptured;
      bolt.axial_force = 0.0;
      return;
    }
    // Yield in tension only: a slack tendon carries nothing, so it cannot yield in compression.
    const double stretch = l - bolt.anchored_length + spec.pretension / k;
    double force = k * (stretch - bolt.plastic_extension);
    if (force > spec.yield_force) {
      yielded |= plastic_member(k, spec.yield_force, stretch, bolt.plastic_extension, force);
    }
    bolt.axial_force = std::max(force, 0.0);
    add(bolt.ties[0].block, bolt.axial_force * axis, x0, k);
    add(bolt.ties[1].block, -bolt.axial_force * axis, x1, k);
  } else {
    // Grouted: the tendon solved against the rock's displacements along the bolt. Each tie's
    // world point is formed once; neighbouring elements' springs share a node, and a tie equal
    // to the one before (same block, same body point) takes its point.
    Tendon& t = bolt.tendon;
    thread_local std::vector<Eigen::Vector3d> at;
    thread_local std::vector<double> rock;
    at.resize(t.springs.size());
    rock.resize(t.springs.size());
    for (std::size_t k = 0; k < t.springs.size(); ++k) {
      const BoltTie& tie = bolt.ties[k];
      const bool same = k > 0 && tie.block == bolt.ties[k - 1].block &&
                        tie.body_point == bolt.ties[k - 1].body_point;
      at[k] = same ? at[k - 1] : world(tie);
      rock[k] = (at[k] - tie.installed).dot(axis);
    }
    const BoltTie& plate = bolt.ties.back();
    const Eigen::Vector3d plate_at = world(plate);
    t.u[0] = (plate_at - plate.installed).dot(axis);
    yielded |= t.solve(rock);
    for (std::size_t e = 0; e < t.elements.size(); ++e) {
      const double strain = (t.u[e + 1] - t.u[e]) / (bolt.node_at[e + 1] - bolt.node_at[e]);
      bolt.largest_strain = std::max(bolt.largest_strain, strain);
    }
    if (bolt.largest_strain > spec.rupture_strain) {
      bolt.state = Bolt::State::ruptured;
      return;
    }
    for (std::size_t k = 0; k < t.springs.size(); ++k)
      add(bolt.ties[k].block, t.springs[k].force * axis, at[k], t.springs[k].stiffness);
    add(plate.block, t.plate_force() * axis, plate_at, t.elements.front().stiffness);
  }
  // Dowels: the relative displacement of the blocks across the bolt's axis at each crossing.
  if (spec.shear_stiffness > 0.0) {
    for (BoltCrossing& c : bolt.crossings) {
      const Block& a = blocks[static_cast<std::size_t>(c.block_a)];
      const Block& b = blocks[static_cast<std::size_t>(c.block_b)];
      const Eigen::Vector3d xa = a.to_world(c.body_a), xb = b.to_world(c.body_b);
      const Eigen::Vector3d d = xb - xa;
      const Eigen::Vector3d shear = d - d.dot(axis) * axis;
      Eigen::Vector3d elastic = shear - c.plastic;
      const double f = spec.shear_stiffness * elastic.norm();
      if (f > spec.shear_capacity) {
        elastic *= spec.shear_capacity / f;
        c.plastic = shear - elastic;
        yielded = true;
      }
      c.force = -spec.shear_stiffness * elastic;
      const Eigen::Vector3d x = 0.5 * (xa + xb);
      add(c.block_b, c.force, x, spec.shear_stiffness);
      add(c.block_a, -c.force, x, spec.shear_stiffness);
    }
  }
  bolt.yielded |= yielded;
  if (bolt.yielded) bolt.state = Bolt::State::yielded;
}

void add_bolt_loads(std::span<const BoltLoad> loads, std::vector<Block>& blocks,
                    std::vector<double>& stiffness, std::vector<double>& rotational) {
  for (const BoltLoad& l : loads) {
    const auto i = static_cast<std::size_t>(l.block);
    Block& b = blocks[i];
    b.force += l.force;
    b.torque += (l.point - b.position).cross(l.force);
    stiffness[i] += l.stiffness;
    rotational[i] += l.stiffness * (l.point - b.position).squaredNorm();
  }
}

}  // namespace blockdem
