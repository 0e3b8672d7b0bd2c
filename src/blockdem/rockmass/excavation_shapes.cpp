// Tunnel outlines as plane sets.
#include "blockdem/rockmass/excavation_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "blockdem/numerics/units.hpp"

namespace blockdem {

Eigen::Vector3d TunnelSpec::axis() const {
  const double t = deg_to_rad(trend_deg), p = deg_to_rad(plunge_deg);
  return {std::cos(p) * std::sin(t), std::cos(p) * std::cos(t), -std::sin(p)};
}

std::vector<Halfspace> tunnel_planes(const TunnelSpec& t) {
  const double pi = std::numbers::pi;
  const double tr = deg_to_rad(t.trend_deg);
  const Eigen::Vector3d a = t.axis();
  // Section axes: horizontal eh (right of the axis looking along it) and ev = eh x a (up).
  const Eigen::Vector3d eh(std::cos(tr), -std::sin(tr), 0.0);
  const Eigen::Vector3d ev = eh.cross(a);
  auto plane = [&](const Eigen::Vector3d& n, double offset_from_centre) {
    return Halfspace{n, n.dot(t.centre) + offset_from_centre};
  };
  std::vector<Halfspace> out;
  if (t.profile == TunnelSpec::Profile::circle) {
    // Edge k of the inscribed m-gon: normal at angle (k + 1/2) 2π/m, offset r cos(π/m).
    for (int k = 0; k < t.sides; ++k) {
      const double th = (k + 0.5) * 2.0 * pi / t.sides;
      out.push_back(
          plane(std::cos(th) * eh + std::sin(th) * ev, t.radius * std::cos(pi / t.sides)));
    }
  } else {
    const int arch = std::max(2, t.sides / 2);
    for (int k = 0; k < arch; ++k) {
      const double th = (k + 0.5) * pi / arch;
      out.push_back(
          plane(std::cos(th) * eh + std::sin(th) * ev, t.radius * std::cos(0.5 * pi / arch)));
    }
    out.push_back(plane(eh, t.radius));
    out.push_back(plane(-eh, t.radius));
    out.push_back(plane(-ev, t.wall_height));
  }
  if (t.length) {
    out.push_back(plane(a, 0.5 * *t.length));
    out.push_back(plane(-a, 0.5 * *t.length));
  }
  return out;
}

}  // namespace blockdem
