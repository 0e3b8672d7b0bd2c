// The in-situ field's traction on a face, exact for a field linear in depth, and the joint closure
// that carries it.
#include "blockdem/response/in_situ.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "blockdem/contact/normal_integral.hpp"
#include "blockdem/geometry/polygon_moments.hpp"
#include "blockdem/numerics/units.hpp"

namespace blockdem {

std::string StressField::problem() const {
  for (const Eigen::Matrix3d* m : {&stress, &gradient_z}) {
    if (!m->allFinite()) return "has a value that is not finite";
    if (!((*m - m->transpose()).cwiseAbs().maxCoeff() <= 1e-12 * m->cwiseAbs().maxCoeff()))
      return "is not symmetric";
  }
  return {};
}

StressField stress_from_overburden(double ground_z, double density, double gravity, double k_x,
                                   double k_y, double trend_deg) {
  // The k_x axis turned clockwise from east by the trend, seen from above.
  const double t = deg_to_rad(trend_deg);
  const Eigen::Vector3d ex(std::cos(t), -std::sin(t), 0.0);
  const Eigen::Vector3d ey(std::sin(t), std::cos(t), 0.0);
  // σ per unit of vertical stress; σ_v = ρ g (ground_z - z).
  const Eigen::Matrix3d unit = k_x * ex * ex.transpose() + k_y * ey * ey.transpose() +
                               Eigen::Vector3d::UnitZ() * Eigen::Vector3d::UnitZ().transpose();
  const double weight = density * gravity;  // (Pa/m)
  StressField f;
  f.reference_z = ground_z;
  f.stress = Eigen::Matrix3d::Zero();
  f.gradient_z = -weight * unit;
  return f;
}

FaceTraction face_traction(const StressField& field, std::span<const Eigen::Vector3d> vertices,
                           const Eigen::Vector3d& n) {
  if (vertices.size() < 3) throw std::invalid_argument("face_traction: fewer than 3 vertices");
  const PolygonMoments pm = polygon_area_centroid(vertices);
  if (!(pm.area > 0.0)) throw std::invalid_argument("face_traction: the face has no area");
  FaceTraction t;
  t.area = pm.area;
  t.centroid = pm.centroid;
  // The second moment ∫ (x - x̄)(x - x̄)ᵀ dA.
  const Eigen::Matrix3d second = polygon_second_moment(vertices, pm.centroid, n);
  // σ(x) n = σ(x̄) n + (z - z̄) G n: the mean traction at the centroid, and the moment of the
  // gradient part, ∫ (x - x̄)(z - z̄) dA × G n = (S e_z) × G n.
  const Eigen::Matrix3d mean = field.at(pm.centroid);
  const Eigen::Vector3d gn = field.gradient_z * n;
  t.force = pm.area * (mean * n);
  t.moment = (second * Eigen::Vector3d::UnitZ()).cross(gn);
  t.normal_stress = n.dot(mean * n);
  const Eigen::Vector3d up_in_face = Eigen::Vector3d::UnitZ() - n.z() * n;
  t.normal_stress_gradient = n.dot(gn) * up_in_face;
  t.least_normal_stress = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& v : vertices) {
    const double s = t.normal_stress + t.normal_stress_gradient.dot(v - pm.centroid);
    if (s < t.least_normal_stress) {
      t.least_normal_stress = s;
      t.least_point = v;
    }
  }
  return t;
}

double closure_for_stress(const NormalLaw& law, double normal_stress) {
  if (!(normal_stress > 0.0))
    throw std::invalid_argument("closure_for_stress: the normal stress must be positive");
  return std::visit(
      [&](const auto& l) -> double {
        using L = std::decay_t<decltype(l)>;
        if constexpr (std::is_same_v<L, LinearNormal>) {
          return normal_stress / l.stiffness;
        } else {
          // σ_n = a (exp(b u) - 1): u = ln(1 + σ_n / a) / b.
          return std::log1p(normal_stress / l.a) / l.b;
        }
      },
      law);
}

namespace {

// The normal force and the two moments in the face (about x̄, along u and v) of the law over the
// polygon under the closure field c = (value at x̄, slope along u, slope along v).
Eigen::Vector3d resultant(const NormalLaw& law, std::span<const Eigen::Vector3d> vertices,
                          const Eigen::Vector3d& centroid, const Eigen::Vector3d& u,
                          const Eigen::Vector3d& v, const Eigen::Vector3d& c) {
  std::vector<double> closures;
  closures.reserve(vertices.size());
  for (const Eigen::Vector3d& x : vertices) {
    const Eigen::Vector3d d = x - centroid;
    closures.push_back(c[0] + c[1] * u.dot(d) + c[2] * v.dot(d));
  }
  const PolygonStressResultant r = integrate_normal_stress_over_polygon(law, vertices, closures);
  if (!r.centre_of_pressure) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d arm = *r.centre_of_pressure - centroid;
  return {r.force, r.force * u.dot(arm), r.force * v.dot(arm)};
}

}  // namespace

LinearClosure closure_for_traction(const NormalLaw& law, std::span<const Eigen::Vector3d> vertices,
                                   const Eigen::Vector3d& n, const FaceTraction& traction) {
  if (!(traction.least_normal_stress > 0.0)) {
    std::ostringstream s;
    s << "the normal stress " << traction.least_normal_stress << " Pa at ("
      << traction.least_point.x() << ", " << traction.least_point.y() << ", "
      << traction.least_point.z() << ") is not compressive: a joint cannot start in tension";
    throw std::invalid_argument(s.str());
  }
  // A basis of the face.
  const Eigen::Vector3d u = n.unitOrthogonal();
  const Eigen::Vector3d v = n.cross(u);
  const Eigen::Vector3d& xc = traction.centroid;
  // The pointwise inverse linearised at the centroid: exact for the linear law.
  const double c0 = closure_for_stress(law, traction.normal_stress);
  const double k0 = normal_tangent_stiffness(law, c0);
  Eigen::Vector3d c(c0, traction.normal_stress_gradient.dot(u) / k0,
                    traction.normal_stress_gradient.dot(v) / k0);
  LinearClosure out;
  out.point = xc;
  if (!std::holds_alternative<LinearNormal>(law)) {
    // The target: the field's normal force and its moments in the face, ∫ (x - x̄) σ_n dA.
    const Eigen::Vector3d normal_moment = traction.moment - n.dot(traction.moment) * n;
    // (x - x̄) × σ_n n = -n × (x - x̄) σ_n: the first moment is n × moment.
    const Eigen::Vector3d first = n.cross(normal_moment);
    const Eigen::Vector3d target(traction.force.dot(n), first.dot(u), first.dot(v));
    const double scale = std::abs(target[0]);
    const double extent = std::sqrt(traction.area);
    bool solved = false;
    for (int it = 0; it < 50 && !solved; ++it) {
      const Eigen::Vector3d r = resultant(law, vertices, xc, u, v, c) - target;
      if (std::abs(r[0]) <= 1e-14 * scale && r.tail<2>().norm() <= 1e-14 * scale * extent) {
        solved = true;
        break;
      }
      // The Jacobian by central differences.
      Eigen::Matrix3d jac;
      const double h0 = 1e-6 * c0;
      const Eigen::Vector3d steps(h0, h0 / extent, h0 / extent);
      for (int k = 0; k < 3; ++k) {
        Eigen::Vector3d hi = c, lo = c;
        hi[k] += steps[k];
        lo[k] -= steps[k];
        jac.col(k) =
            (resultant(law, vertices, xc, u, v, hi) - resultant(law, vertices, xc, u, v, lo)) /
            (2.0 * steps[k]);
      }
      c -= jac.fullPivLu().solve(r);
    }
    if (!solved || !c.allFinite())
      throw std::invalid_argument("no closure of the joint law carries the in-situ traction");
  }
  out.value = c[0];
  out.gradient = c[1] * u + c[2] * v;
  for (const Eigen::Vector3d& x : vertices) {
    if (!(out.at(x) > 0.0))
      throw std::invalid_argument("the closure carrying the in-situ traction is not positive");
  }
  return out;
}

}  // namespace blockdem
