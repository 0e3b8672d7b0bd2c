// Joint set orientation, checks, and joint plane positions from constant or random spacing.
#include "blockdem/rockmass/joint_set.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

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
    fail("dip_deg", "must be in [0, 90] degrees, got " + std::to_string(dip_deg));
  if (!(dip_direction_deg >= 0.0 && dip_direction_deg < 360.0))
    fail("dip_direction_deg",
         "must be in [0, 360) degrees, got " + std::to_string(dip_direction_deg));
  if (!origin.allFinite()) fail("origin", "must be finite");
  const bool explicit_joints = extent && !centres.empty();
  if (!explicit_joints) {
    if (!(spacing.mean > 0.0) || !std::isfinite(spacing.mean))
      fail("spacing", "must be positive, got " + std::to_string(spacing.mean));
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

std::vector<double> joint_plane_offsets(const JointSet& set, double lo, double hi) {
  const double start = set.normal().dot(set.origin);
  std::vector<double> below, above;
  // Separate streams up and down from the origin's joint, so that enlarging the region keeps
  // the joints already placed.
  const std::uint64_t seed = set.spacing.seed.value_or(0);
  PortableRandom up(seed), down(seed ^ 0xA5A5A5A5A5A5A5A5ULL);
  for (double d = start; d <= hi; d += draw_spacing(set.spacing, up)) {
    if (d >= lo) above.push_back(d);
  }
  for (double d = start - draw_spacing(set.spacing, down); d >= lo;
       d -= draw_spacing(set.spacing, down)) {
    if (d <= hi) below.push_back(d);
  }
  std::vector<double> out(below.rbegin(), below.rend());
  out.insert(out.end(), above.begin(), above.end());
  return out;
}

}  // namespace blockdem
