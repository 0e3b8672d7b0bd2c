// Joint set orientation, checks, and joint plane positions from constant or random spacing.
#include "blockdem/rockmass/joint_set.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "blockdem/numerics/number_text.hpp"
#include "blockdem/numerics/units.hpp"

namespace blockdem {
namespace {

constexpr double kDeg = deg_to_rad(1.0);

// One spacing drawn from the set's distribution (m). Normal draws that are not positive are
// drawn again (a truncated normal; with sd <= mean/3 fewer than 0.2 % are redrawn). Lognormal:
// ln s ~ N(μ, σ²) with σ² = ln(1 + sd²/mean²), μ = ln mean - σ²/2, so that E[s] = mean and
// sd[s] = sd.
double draw_spacing(const Spacing& sp, PortableRandom& rng) {
  switch (sp.distribution) {
    case Spacing::Distribution::constant:
      return sp.mean;
    case Spacing::Distribution::exponential:
      return sp.mean * rng.exponential();
    case Spacing::Distribution::normal:
      for (;;) {
        const double s = sp.mean + sp.sd * rng.normal();
        if (s > 0.0) return s;
      }
    case Spacing::Distribution::lognormal: {
      const double var = std::log(1.0 + (sp.sd * sp.sd) / (sp.mean * sp.mean));
      const double mu = std::log(sp.mean) - 0.5 * var;
      return std::exp(mu + std::sqrt(var) * rng.normal());
    }
  }
  return sp.mean;
}

}  // namespace

std::uint64_t PortableRandom::next() {
  // SplitMix64 (Steele, Lea & Flood 2014).
  std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

double PortableRandom::uniform() {
  return static_cast<double>(next() >> 11) * 0x1.0p-53;
}

double PortableRandom::exponential() {
  return -std::log1p(-uniform());
}

double PortableRandom::normal() {
  if (spare_) {
    const double z = *spare_;
    spare_.reset();
    return z;
  }
  const double u1 = 1.0 - uniform();  // in (0, 1]
  const double u2 = uniform();
  const double r = std::sqrt(-2.0 * std::log(u1));
  spare_ = r * std::sin(2.0 * std::numbers::pi * u2);
  return r * std::cos(2.0 * std::numbers::pi * u2);
}

double JointExtent::area() const {
  return shape == Shape::disc ? std::numbers::pi * radius * radius : size.x() * size.y();
}

Eigen::Vector3d JointSet::normal() const {
  const double d = dip_deg * kDeg, a = dip_direction_deg * kDeg;
  return {std::sin(d) * std::sin(a), std::sin(d) * std::cos(a), std::cos(d)};
}

Eigen::Vector3d JointSet::dip_vector() const {
  const double d = dip_deg * kDeg, a = dip_direction_deg * kDeg;
  return {std::cos(d) * std::sin(a), std::cos(d) * std::cos(a), -std::sin(d)};
}

Eigen::Vector3d JointSet::strike_vector() const {
  const double a = dip_direction_deg * kDeg;
  return {std::cos(a), -std::sin(a), 0.0};
}

void JointSet::validate() const {
  auto fail = [](const std::string& key, const std::string& why) {
    throw std::invalid_argument(key + ": " + why);
  };
  if (!(dip_deg >= 0.0 && dip_deg <= 90.0))
    fail("dip_deg", "must be in [0, 90] degrees, got " + number_text(dip_deg));
  if (!(dip_direction_deg >= 0.0 && dip_direction_deg < 360.0))
    fail("dip_direction_deg", "must be in [0, 360) degrees, got " + number_text(dip_direction_deg));
  if (!origin.allFinite()) fail("origin", "must be finite");
  const bool explicit_joints = extent && !centres.empty();
  if (!explicit_joints) {
    if (!(spacing.mean > 0.0) || !std::isfinite(spacing.mean))
      fail("spacing", "must be positive, got " + number_text(spacing.mean));
    if (spacing.distribution != Spacing::Distribution::constant && !spacing.seed)
      fail("spacing.seed", "a spacing distribution needs a seed (same seed, same blocks)");
    const bool needs_sd = spacing.distribution == Spacing::Distribution::normal ||
                          spacing.distribution == Spacing::Distribution::lognormal;
    if (needs_sd && !(spacing.sd > 0.0))
      fail("spacing.sd", "a normal or lognormal spacing needs sd > 0");
  }
  if (extent) {
    if (extent->shape == JointExtent::Shape::disc && !(extent->radius > 0.0))
      fail("extent.radius", "must be positive");
    if (extent->shape == JointExtent::Shape::rectangle &&
        !(extent->size.x() > 0.0 && extent->size.y() > 0.0))
      fail("extent.size", "both sides must be positive");
    if (centres.empty()) {
      if (!placement_seed)
        fail("extent.seed", "non-persistent joints need a seed for their positions");
      if (!(persistence > 0.0 && persistence <= 1.0))
        fail("extent.persistence", "must be in (0, 1]");
    }
  } else if (!centres.empty()) {
    fail("extent.centres", "joint centres need an extent");
  }
}

JointPlaneEstimate estimate_joint_planes(const JointSet& set, double lo, double hi) {
  const double start = set.normal().dot(set.origin);
  JointPlaneEstimate e;
  e.planes = std::floor((hi - lo) / set.spacing.mean) + 1.0;
  // A random spacing is drawn from the origin's joint to the far side of [lo, hi].
  if (set.spacing.distribution != Spacing::Distribution::constant)
    e.draws = (std::max(hi, start) - std::min(lo, start)) / set.spacing.mean + 1.0;
  return e;
}

std::vector<double> joint_plane_offsets(const JointSet& set, double lo, double hi,
                                        double max_planes) {
  const double start = set.normal().dot(set.origin);
  const bool constant = set.spacing.distribution == Spacing::Distribution::constant;
  std::vector<double> below, above;
  // Separate streams up and down from the origin's joint, so that enlarging the region keeps
  // the joints already placed.
  const std::uint64_t seed = set.spacing.seed.value_or(0);
  PortableRandom up(seed), down(seed ^ 0xA5A5A5A5A5A5A5A5ULL);
  double draws = 0.0;
  // The next offset from d, one spacing s up (sign 1) or down (-1): it must move, and the
  // planes and draws stay within their limits, whatever the numbers.
  auto step = [&](double d, double s, double sign) {
    const double next = d + sign * s;
    if (constant && next == d)
      throw std::invalid_argument("spacing: " + number_text(s) +
                                  " m does not move a joint plane at n.x = " + number_text(d) +
                                  " m (below the resolution of a double there)");
    if (!constant && ++draws > kMaxSpacingDraws)
      throw std::invalid_argument("spacing: placing the joints would draw more than 1e8 spacings");
    if (static_cast<double>(below.size() + above.size()) > max_planes)
      throw std::invalid_argument("spacing: more than " + number_text(max_planes) +
                                  " joint planes cross the region (the limit; [rock_mass] "
                                  "max_blocks sets it for a scenario)");
    return next;
  };
  // A constant spacing from an origin outside [lo, hi] steps straight to the first plane in it.
  const double s0 = set.spacing.mean;
  double first_up = start, first_down = start - s0;
  if (constant && start < lo) first_up = start + std::ceil((lo - start) / s0) * s0;
  if (constant && start - s0 > hi) first_down = start - std::ceil((start - hi) / s0) * s0;
  for (double d = first_up; d <= hi; d = step(d, draw_spacing(set.spacing, up), 1.0)) {
    if (d >= lo) above.push_back(d);
  }
  if (!constant) first_down = step(start, draw_spacing(set.spacing, down), -1.0);
  for (double d = first_down; d >= lo; d = step(d, draw_spacing(set.spacing, down), -1.0)) {
    if (d <= hi) below.push_back(d);
  }
  std::vector<double> out(below.rbegin(), below.rend());
  out.insert(out.end(), above.begin(), above.end());
  return out;
}

}  // namespace blockdem
