// The fast face-contact cells and law integrals against their first implementation (kept as the
// oracle in tests/oracle/face_integration_reference): same resultants to 1e-12 on random hulls,
// tilted and turned cubes, closed and partly open joints, linear and exponential laws; with every
// plane, and with the planes that hold the other block's box left out (planes_holding).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <vector>

#include "blockdem/collision/boon2012.hpp"
#include "blockdem/collision/face_contact.hpp"
#include "blockdem/contact/normal_integral.hpp"
#include "oracle/face_integration_reference.hpp"
#include "support/random_shapes.hpp"

namespace blockdem {
namespace {

using test_shapes::Planes;
using test_shapes::Rng;
using test_shapes::uniform;

// What the world takes from one face contact: the sums over the cells.
struct Resultant {
  int cells = 0;
  double force = 0.0;                                // (N)
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();  // sum of force * centre of pressure (N m)
  double area = 0.0;                                 // (m^2)
  double compressed_area = 0.0;                      // (m^2)
  double peak_stress = 0.0;                          // (Pa)
  double peak_closure = 0.0;                         // (m)
};

template <class Cells, class Integrate>
Resultant sum_cells(const Cells& cells, Integrate integrate) {
  Resultant r;
  for (const auto& cell : cells) {
    const PolygonStressResultant p = integrate(cell.vertices, cell.closures);
    ++r.cells;
    r.force += p.force;
    r.area += p.area;
    r.compressed_area += p.compressed_area;
    r.peak_stress = std::max(r.peak_stress, p.peak_stress);
    if (p.centre_of_pressure) r.moment += p.force * *p.centre_of_pressure;
    for (const double g : cell.closures) r.peak_closure = std::max(r.peak_closure, g);
  }
  return r;
}

const NormalLaw kLaws[] = {LinearNormal{10e9}, ExponentialNormal::eq3(), ExponentialNormal::eq4()};

struct Tally {
  int contacts = 0;         // face contacts compared
  int multi_cell = 0;       // of which with more than one cell
  int partly_open = 0;      // of which with part of the joint open (a vertex of zero closure)
  int wide_exponent = 0;    // of which with b (max g - min g) > 1 (recursive divided differences)
  int ill_conditioned = 0;  // contact-law comparisons where area, force or centre needed it
  double worst = 0.0;       // largest difference seen, relative to the 1e-12 tolerance's scale
  long planes = 0;          // planes of both blocks over the face contacts
  long left_out = 0;        // of which left out as holding the other block
  int ill_conditioned_left_out = 0;  // as ill_conditioned, with those planes left out
};

Resultant reference(const Planes& a, const Planes& b, const ContactGeometry& g, double extent,
                    const NormalLaw& law, const oracle::ReferenceFaceGeometry* geometry = nullptr) {
  const oracle::ReferenceFaceGeometry own =
      geometry ? oracle::ReferenceFaceGeometry{}
               : oracle::reference_face_contact_geometry(a, b, g.point, g.normal, extent);
  return sum_cells((geometry ? *geometry : own).cells, [&](const auto& v, const auto& c) {
    return oracle::reference_stress_over_polygon(law, v, c);
  });
}

// B moved along its face normals by `ulps` units in the last place of its offsets: a change of
// the input at round-off level.
Planes nudged(const Planes& b, double ulps) {
  Planes out = b;
  for (Halfspace& h : out) h.offset += ulps * std::numeric_limits<double>::epsilon() * h.offset;
  return out;
}

// The resultants of `fast` against the reference's (`slow`) on one pair; `extent` as the world
// passes it; `count` adds the contact to the tally's kinds. Each resultant must
// agree to 1e-12 of its scale, or, where the contact is ill-conditioned, to within four times the
// change of the reference itself when B's offsets move by two units in the last place (a partly
// open joint tilted by θ moves its opening line by δ/θ: at θ ~ 1e-9 rad, round-off in the planes
// alone changes the compressed area by ~1e-11 and the closure at sliver vertices by ~1e-4 of its
// value, in either implementation).
void compare_resultants(const Planes& a, const Planes& b, double extent, const ContactGeometry& g,
                        const FaceContactGeometry& fast, const oracle::ReferenceFaceGeometry& slow,
                        bool count, Tally& tally) {
  // The peak closure is the largest vertex closure of any cell, and a cell's closure is linear
  // with in-plane gradient up to |n_j - (n_j·n) n| / |n_j·n| per plane: a vertex computed with
  // round-off ~8 eps |y| (|y| <= extent) moves it by that much times the steepest gradient.
  // Planes nearly along n (a block turned by θ ~ 1e-9 rad) make it ~1e9, in either
  // implementation.
  double steepest = 0.0;
  for (const Planes* planes : {&a, &b}) {
    for (const Halfspace& h : *planes) {
      const double c = std::abs(h.normal.dot(g.normal));
      if (c > FaceContactSettings{}.lateral_tolerance)
        steepest = std::max(steepest, (h.normal - h.normal.dot(g.normal) * g.normal).norm() / c);
    }
  }
  const double closure_allowance =
      2.0 * steepest * 8.0 * std::numeric_limits<double>::epsilon() * extent;
  for (const NormalLaw& law : kLaws) {
    const Resultant f = sum_cells(fast.cells, [&](const auto& v, const auto& c) {
      return integrate_normal_stress_over_polygon(law, v, c);
    });
    const Resultant s = reference(a, b, g, extent, law, &slow);
    if (s.cells == 0) {
      EXPECT_EQ(f.cells, 0);
      continue;
    }
    const Resultant up = reference(a, nudged(b, 2.0), g, extent, law);
    const Resultant down = reference(a, nudged(b, -2.0), g, extent, law);
    const double size = std::sqrt(s.area);
    auto centre = [](const Resultant& r) { return Eigen::Vector3d(r.moment / r.force); };
    // Each quantity: fast value, reference value, its scale, the reference's own spread and
    // any further allowance.
    bool beyond = false;
    auto check = [&](const char* what, double x, double y, double scale, double y_up, double y_down,
                     double allowance = 0.0) {
      const double spread = std::max(std::abs(y_up - y), std::abs(y_down - y));
      const double d = std::abs(x - y);
      beyond |= allowance == 0.0 && d > 1e-12 * scale;
      tally.worst = std::max(tally.worst, d / scale);
      EXPECT_LE(d, 1e-12 * scale + 4.0 * spread + allowance) << what;
    };
    check("area", f.area, s.area, s.area, up.area, down.area);
    check("compressed area", f.compressed_area, s.compressed_area, s.area, up.compressed_area,
          down.compressed_area);
    check("peak closure", f.peak_closure, s.peak_closure, s.peak_closure, up.peak_closure,
          down.peak_closure, closure_allowance);
    check("peak stress", f.peak_stress, s.peak_stress, s.peak_stress, up.peak_stress,
          down.peak_stress, normal_tangent_stiffness(law, s.peak_closure) * closure_allowance);
    if (s.force > 0.0) {
      check("force", f.force, s.force, s.force, up.force, down.force);
      check("centre of pressure", (centre(f) - centre(s)).norm(), 0.0, size,
            (centre(up) - centre(s)).norm(), (centre(down) - centre(s)).norm());
    }
    if (beyond) ++(count ? tally.ill_conditioned : tally.ill_conditioned_left_out);
    if (!count) continue;
    if (&law == &kLaws[0]) {
      ++tally.contacts;
      if (s.cells > 1) ++tally.multi_cell;
      bool open = false;
      for (const auto& cell : slow.cells) {
        const auto p = oracle::reference_stress_over_polygon(law, cell.vertices, cell.closures);
        for (const double gc : cell.closures) open |= p.area > 1e-6 * s.area && gc == 0.0;
      }
      if (open) ++tally.partly_open;
    } else if (&law == &kLaws[1]) {
      double lo = s.peak_closure;
      for (const auto& cell : slow.cells) {
        for (const double gc : cell.closures) lo = std::min(lo, gc);
      }
      if (std::get<ExponentialNormal>(law).b * (s.peak_closure - lo) > 1.0) ++tally.wide_exponent;
    }
  }
}

// The box of a hull's vertices (world frame), as the world keeps it per block.
struct Box {
  Eigen::Vector3d min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d max = -min;
};
Box box_of(const Planes& hull) {
  Box box;
  for (const Eigen::Vector3d& v : test_shapes::vertices(hull)) {
    box.min = box.min.cwiseMin(v);
    box.max = box.max.cwiseMax(v);
  }
  return box;
}

// The planes of `a` and of `b` that hold the other block's box, with no clearance.
RedundantPlanes redundant_planes(const Planes& a, const Planes& b) {
  const Box ba = box_of(a), bb = box_of(b);
  return {planes_holding(a, bb.min, bb.max, 0.0), planes_holding(b, ba.min, ba.max, 0.0)};
}

// Compares both implementations on one pair, the fast one with every plane and with the planes
// that hold the other block left out.
void compare(const Planes& a, const Planes& b, double extent, Tally& tally) {
  const ContactGeometry g = boon2012_contact(a, b, extent, Boon2012Settings{});
  if (!g.touching) return;
  const oracle::ReferenceFaceGeometry slow =
      oracle::reference_face_contact_geometry(a, b, g.point, g.normal, extent);
  // Every plane, then the planes that do not bound A∩B left out: both against the reference.
  const RedundantPlanes redundant = redundant_planes(a, b);
  for (const bool leave_out : {false, true}) {
    SCOPED_TRACE(leave_out ? "planes holding the other block left out" : "every plane");
    const FaceContactGeometry fast =
        face_contact_geometry(a, b, g.point, g.normal, extent, FaceContactSettings{}, nullptr,
                              leave_out ? redundant : RedundantPlanes{});
    ASSERT_EQ(fast.face_type, slow.face_type);
    if (!fast.face_type) return;
    if (leave_out) {
      tally.planes += static_cast<long>(a.size() + b.size());
      tally.left_out += std::popcount(redundant.a) + std::popcount(redundant.b);
    }
    compare_resultants(a, b, extent, g, fast, slow, !leave_out, tally);
  }
}

// Two 46 mm cubes side by side along x, B turned by a small random rotation and pressed in by
// `closure` at its deepest point, the pair then turned as a whole (closed or partly open joints).
TEST(FaceContactCells, TiltedCubesMatchReference) {
  Rng rng(20261125);
  Tally tally;
  const double s = 0.046;
  const Planes cube = test_shapes::box(Eigen::Vector3d::Constant(s / 2));
  for (int trial = 0; trial < 400; ++trial) {
    // Tilts from 1e-9 rad (lateral faces just past the lateral tolerance) to 1e-2 rad.
    const double tilt = std::pow(10.0, uniform(rng, -9.0, -2.0));
    const Eigen::Vector3d axis =
        trial % 2 == 0 ? Eigen::Vector3d::UnitY() : test_shapes::random_unit_vector(rng);
    const Eigen::Matrix3d turn_b = Eigen::AngleAxisd(tilt, axis).toRotationMatrix();
    Planes b = test_shapes::transformed(cube, turn_b, Eigen::Vector3d::Zero());
    // Push B against A's +x face: its deepest point reaches x = s/2 + closure.
    const double closure = std::pow(10.0, uniform(rng, -6.0, -4.0));
    const std::vector<Eigen::Vector3d> vb = test_shapes::vertices(b);
    const double reach = -test_shapes::extreme_vertex(vb, Eigen::Vector3d::UnitX()).x();
    const Eigen::Vector3d shift(s / 2 + reach - closure, uniform(rng, -0.3, 0.3) * s,
                                uniform(rng, -0.3, 0.3) * s);
    b = test_shapes::transformed(b, Eigen::Matrix3d::Identity(), shift);
    // A third of the pairs keep the world axes (lateral faces exactly lateral), the rest are
    // turned as a whole.
    const Eigen::Matrix3d whole =
        trial % 3 == 0 ? Eigen::Matrix3d::Identity() : test_shapes::random_rotation(rng);
    const Planes aw = test_shapes::transformed(cube, whole, Eigen::Vector3d::Zero());
    const Planes bw = test_shapes::transformed(b, whole, Eigen::Vector3d::Zero());
    compare(aw, bw, 4.0 * s, tally);
  }
  EXPECT_GT(tally.contacts, 300);
  EXPECT_GT(tally.multi_cell, 100);
  EXPECT_GT(tally.partly_open, 30);
  EXPECT_GT(tally.wide_exponent, 20);
  // Most comparisons of area, force and centre agree to 1e-12 outright (3 laws per contact).
  EXPECT_LT(tally.ill_conditioned, 3 * tally.contacts / 5);
  EXPECT_LT(tally.ill_conditioned_left_out, 3 * tally.contacts / 5);
  // The planes that hold the other block's box are a fair share of them (the far faces).
  EXPECT_GT(tally.left_out, tally.planes / 10);
  std::printf(
      "contacts %d, multi-cell %d, partly open %d, wide exponent %d, beyond 1e-12: %d (%d with "
      "%ld of %ld planes left out), worst %.2e\n",
      tally.contacts, tally.multi_cell, tally.partly_open, tally.wide_exponent,
      tally.ill_conditioned, tally.ill_conditioned_left_out, tally.left_out, tally.planes,
      tally.worst);
}

// Random sphere-tangent hulls: face on face with a small tilt and spin, and vertex into face.
TEST(FaceContactCells, RandomHullsMatchReference) {
  Rng rng(7);
  Tally tally;
  const double radius = 0.02;
  for (int trial = 0; trial < 300; ++trial) {
    const Planes a = test_shapes::random_hull(rng, 8 + trial % 7, radius);
    const Planes b0 = test_shapes::random_hull(rng, 8 + (trial / 7) % 7, radius);
    const std::size_t fa = static_cast<std::size_t>(trial) % a.size();
    const std::size_t fb = static_cast<std::size_t>(trial / 3) % b0.size();
    Planes b;
    if (trial % 4 == 3) {
      b = test_shapes::place_vertex_on_face(a, fa, b0, -std::pow(10.0, uniform(rng, -6.0, -4.0)));
    } else {
      b = test_shapes::place_face_on_face(a, fa, b0, fb, uniform(rng, 0.0, 6.28),
                                          -std::pow(10.0, uniform(rng, -6.0, -4.0)));
      // A small tilt of B about a random axis through A's face centroid (possibly opening part
      // of the joint).
      const double tilt = std::pow(10.0, uniform(rng, -8.0, -2.5));
      const Eigen::Vector3d pivot = test_shapes::face_centroid(a, test_shapes::vertices(a), fa);
      const Eigen::Matrix3d r =
          Eigen::AngleAxisd(tilt, test_shapes::random_unit_vector(rng)).toRotationMatrix();
      b = test_shapes::transformed(b, r, pivot - r * pivot);
    }
    compare(a, b, 8.0 * radius, tally);
  }
  EXPECT_GT(tally.contacts, 150);
  EXPECT_GT(tally.multi_cell, 50);
  EXPECT_GT(tally.partly_open, 20);
  // Most comparisons of area, force and centre agree to 1e-12 outright (3 laws per contact).
  EXPECT_LT(tally.ill_conditioned, 3 * tally.contacts / 5);
  EXPECT_LT(tally.ill_conditioned_left_out, 3 * tally.contacts / 5);
  // The planes that hold the other block's box are a fair share of them (the far faces).
  EXPECT_GT(tally.left_out, tally.planes / 10);
  std::printf(
      "contacts %d, multi-cell %d, partly open %d, wide exponent %d, beyond 1e-12: %d (%d with "
      "%ld of %ld planes left out), worst %.2e\n",
      tally.contacts, tally.multi_cell, tally.partly_open, tally.wide_exponent,
      tally.ill_conditioned, tally.ill_conditioned_left_out, tally.left_out, tally.planes,
      tally.worst);
}

// The triangle integral alone, on closures from all positive to partly negative and from equal to
// far apart (b Δg from 0 to ~20), both laws: mean stress and vertex weights to 1e-12 of the mean.
TEST(FaceContactCells, TriangleIntegralMatchesReference) {
  Rng rng(11);
  double worst = 0.0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double scale = std::pow(10.0, uniform(rng, -9.0, -3.7));
    Eigen::Vector3d g;
    for (int i = 0; i < 3; ++i) g[i] = scale * uniform(rng, trial % 5 == 0 ? -0.5 : 0.0, 1.0);
    if (trial % 7 == 0) g[1] = g[0];  // repeated nodes
    if (trial % 11 == 0) g[2] = 0.0;  // a vertex on the contact's edge
    for (const NormalLaw& law : kLaws) {
      const TriangleStressMoments f = integrate_normal_stress_over_triangle(law, g);
      const TriangleStressMoments s = oracle::reference_stress_over_triangle(law, g);
      EXPECT_NEAR(f.compressed_fraction, s.compressed_fraction, 1e-15);
      if (s.mean_stress == 0.0) {
        EXPECT_EQ(f.mean_stress, 0.0);
        continue;
      }
      const double d = std::max(std::abs(f.mean_stress - s.mean_stress),
                                (f.vertex_weights - s.vertex_weights).cwiseAbs().maxCoeff()) /
                       s.mean_stress;
      worst = std::max(worst, d);
      ASSERT_LE(d, 1e-12) << "closures " << g.transpose();
    }
  }
  RecordProperty("worst_relative_difference", std::to_string(worst));
}

// Which planes hold the other block's box: A a unit cube at the origin, B one above it pressed in
// by 1e-4 and turned by 30 degrees about z: only A's bottom face holds B's box (B's corners reach
// past A's sides), and only B's top face holds A's box (A's corners reach past B's turned sides).
TEST(FaceContactCells, PlanesHoldingTheOtherBlocksBoxAreItsFarFacesOnly) {
  const Planes cube = test_shapes::box(Eigen::Vector3d::Constant(0.5));
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(M_PI / 6.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d at(0.0, 0.0, 1.0 - 1e-4);
  const Planes b = test_shapes::transformed(cube, turn, at);
  const auto bit_of = [](const Planes& planes, const Eigen::Vector3d& normal) {
    for (std::size_t j = 0; j < planes.size(); ++j) {
      if (planes[j].normal.dot(normal) > 1.0 - 1e-12) return std::uint64_t{1} << j;
    }
    return std::uint64_t{0};
  };
  const std::uint64_t a_bottom = bit_of(cube, -Eigen::Vector3d::UnitZ());
  const std::uint64_t a_east = bit_of(cube, Eigen::Vector3d::UnitX());
  const std::uint64_t b_top = bit_of(b, Eigen::Vector3d::UnitZ());
  ASSERT_NE(a_bottom, 0U);
  ASSERT_NE(a_east, 0U);
  ASSERT_NE(b_top, 0U);
  // B turned: its box reaches 0.5 (cos 30 + sin 30) = 0.683 from the axis, past A's sides.
  const Box ba = box_of(cube), bb = box_of(b);
  EXPECT_NEAR(bb.max.x(), 0.5 * (std::cos(M_PI / 6.0) + std::sin(M_PI / 6.0)), 1e-12);
  EXPECT_EQ(planes_holding(cube, bb.min, bb.max, 0.0), a_bottom);
  EXPECT_EQ(planes_holding(b, ba.min, ba.max, 0.0), b_top);
  // Unturned, each box lies within the other's four sides too, flush: held with no clearance,
  // not with any; moved west by a micrometre, B's box is held by A's east side with a clearance
  // below that.
  const Box straight = box_of(test_shapes::transformed(cube, Eigen::Matrix3d::Identity(), at));
  EXPECT_EQ(std::popcount(planes_holding(cube, straight.min, straight.max, 0.0)), 5);
  EXPECT_EQ(planes_holding(cube, straight.min, straight.max, 1e-9), a_bottom);
  const Eigen::Vector3d west(-1e-6, 0.0, 0.0);
  EXPECT_EQ(planes_holding(cube, straight.min + west, straight.max + west, 0.9e-6),
            a_bottom | a_east);
  EXPECT_EQ(planes_holding(cube, straight.min + west, straight.max + west, 1.1e-6), a_bottom);
}

// A triangle compressed at every vertex (some exactly at zero closure) skips the clip at g = 0 and
// the fan; for the linear law both routes form the same products and sums, so the result must be
// the reference's clipped fan bit for bit.
TEST(FaceContactCells, CompressedTriangleIsTheClippedFanBitForBit) {
  Rng rng(13);
  const NormalLaw& law = kLaws[0];
  for (int trial = 0; trial < 5000; ++trial) {
    const double scale = std::pow(10.0, uniform(rng, -9.0, -3.7));
    Eigen::Vector3d g;
    for (int i = 0; i < 3; ++i) g[i] = scale * uniform(rng, 0.0, 1.0);
    if (trial % 7 == 0) g[1] = g[0];         // repeated nodes
    if (trial % 5 == 0) g[trial % 3] = 0.0;  // a vertex on the contact's edge
    const TriangleStressMoments f = integrate_normal_stress_over_triangle(law, g);
    const TriangleStressMoments s = oracle::reference_stress_over_triangle(law, g);
    ASSERT_EQ(f.compressed_fraction, 1.0);
    ASSERT_EQ(f.compressed_fraction, s.compressed_fraction);
    ASSERT_EQ(f.mean_stress, s.mean_stress) << "closures " << g.transpose();
    for (int i = 0; i < 3; ++i) {
      ASSERT_EQ(f.vertex_weights[i], s.vertex_weights[i]) << "closures " << g.transpose();
    }
  }
}

}  // namespace
}  // namespace blockdem
