// Cost of one contact's normal force in the two contact modes (face-integration issue, item 5):
// boon2012 (point contact: narrow phase, then sigma_n(delta) A_c) against face_integrated
// (narrow phase, then the cells of linear closure and the law integrated over them), for a
// beam joint of the voussoir beam (46 mm faces, closed or partly open), linear and exponential
// laws.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>

#include "blockdem/collision/boon2012.hpp"
#include "blockdem/collision/face_contact.hpp"
#include "blockdem/contact/normal_integral.hpp"
#include "blockdem/geometry/polyhedron.hpp"
#include "blockdem/response/contact_twist.hpp"
#include "blockdem/response/face_twist.hpp"

namespace blockdem {
namespace {

struct Joint {
  std::vector<Halfspace> a, b;
};

// Two 46 mm cubes side by side along x, the right one turned by `tilt` about y (an opening
// joint) and pressed in so that the deepest closure is 1e-5 m.
Joint beam_joint(double tilt) {
  const double s = 0.046;
  Joint j;
  j.a = copy_planes(Polyhedron::box({s, s, s}));
  const Eigen::Matrix3d r = Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const double reach = 0.5 * s * (std::cos(tilt) + std::sin(std::abs(tilt)));
  j.b = copy_planes(Polyhedron::box({s, s, s}).transformed(r, {0.5 * s + reach - 1e-5, 0, 0}));
  return j;
}

const NormalLaw& law_of(int which) {
  static const NormalLaw linear = LinearNormal{10e9};
  static const NormalLaw exponential = ExponentialNormal::eq3();
  return which == 0 ? linear : exponential;
}

void BM_ContactPoint(benchmark::State& state) {
  const Joint j = beam_joint(static_cast<double>(state.range(0)) * 1e-4);
  const NormalLaw& law = law_of(static_cast<int>(state.range(1)));
  Boon2012Cache cache;
  if (!boon2012_contact(j.a, j.b, 0.2, Boon2012Settings{}).touching)
    state.SkipWithError("no contact");
  for (auto _ : state) {
    const ContactGeometry g = boon2012_contact(j.a, j.b, 0.2, Boon2012Settings{}, &cache);
    benchmark::DoNotOptimize(normal_stress(law, g.overlap) * g.area);
  }
}

void BM_ContactFaceIntegrated(benchmark::State& state) {
  const Joint j = beam_joint(static_cast<double>(state.range(0)) * 1e-4);
  const NormalLaw& law = law_of(static_cast<int>(state.range(1)));
  Boon2012Cache cache;
  if (!boon2012_contact(j.a, j.b, 0.2, Boon2012Settings{}).touching)
    state.SkipWithError("no contact");
  for (auto _ : state) {
    const ContactGeometry g = boon2012_contact(j.a, j.b, 0.2, Boon2012Settings{}, &cache);
    const FaceContactGeometry fc = face_contact_geometry(j.a, j.b, g.point, g.normal, 0.2);
    double force = 0.0;
    for (const auto& cell : fc.cells)
      force += integrate_normal_stress_over_polygon(law, cell.vertices, cell.closures).force;
    benchmark::DoNotOptimize(force);
  }
}

// The same with the twisting resistance (issue 14): the compressed area's J and the lower bound
// of ∫ σ_n r dA over the cells, one step of the torsional spring, and the exact ∫ σ_n r dA when
// the bound does not certify the step (a turn that slips).
void BM_ContactFaceIntegratedTwist(benchmark::State& state) {
  const Joint j = beam_joint(static_cast<double>(state.range(0)) * 1e-4);
  const NormalLaw& law = law_of(static_cast<int>(state.range(1)));
  const double spin = state.range(2) == 0 ? 1e-9 : 1.0;  // rad: elastic, or far beyond slip
  const ShearLaw shear = LinearShear{};
  Boon2012Cache cache;
  if (!boon2012_contact(j.a, j.b, 0.2, Boon2012Settings{}).touching)
    state.SkipWithError("no contact");
  for (auto _ : state) {
    const ContactGeometry g = boon2012_contact(j.a, j.b, 0.2, Boon2012Settings{}, &cache);
    const FaceContactGeometry fc = face_contact_geometry(j.a, j.b, g.point, g.normal, 0.2);
    double force = 0.0, area = 0.0;
    Eigen::Vector3d pressure = Eigen::Vector3d::Zero();
    for (const auto& cell : fc.cells) {
      const PolygonStressResultant r =
          integrate_normal_stress_over_polygon(law, cell.vertices, cell.closures);
      force += r.force;
      area += r.compressed_area;
      if (r.centre_of_pressure) pressure += r.force * *r.centre_of_pressure;
    }
    TwistGeometry tg = face_twist_geometry(fc.cells, g.normal, force, pressure / force);
    TwistState twist;
    benchmark::DoNotOptimize(
        advance_twist(twist, shear, ShearState{}, force / area, tg, {fc.cells, law}, spin));
    benchmark::DoNotOptimize(twist.moment);
    benchmark::DoNotOptimize(force);
  }
}

// The whole shear of a face contact with twist (issue 14, distributed shear): the normal force
// and the twist spring as above, the shear law's update and the force and moment together
// against Coulomb's law at every point (interact_shear_twist). Third argument: 0 a joint at 0.15
// of both limits (the certificate suffices), 1 a joint at 0.8 of both (outside the limit
// surface: the full-slip quadratures every step, and the return).
void BM_ContactFaceIntegratedShearTwist(benchmark::State& state) {
  const Joint j = beam_joint(static_cast<double>(state.range(0)) * 1e-4);
  const NormalLaw& law = law_of(static_cast<int>(state.range(1)));
  const double level = state.range(2) == 0 ? 0.15 : 0.8;
  const ShearLaw shear = LinearShear{};
  const double mu = strength_of(shear).friction_coefficient;
  Boon2012Cache cache;
  const ContactGeometry g0 = boon2012_contact(j.a, j.b, 0.2, Boon2012Settings{});
  if (!g0.touching) state.SkipWithError("no contact");
  // The joint's limits, once: μ F_n and μ ∫ σ_n r dA.
  const FaceContactGeometry fc0 = face_contact_geometry(j.a, j.b, g0.point, g0.normal, 0.2);
  double force0 = 0.0;
  for (const auto& cell : fc0.cells)
    force0 += integrate_normal_stress_over_polygon(law, cell.vertices, cell.closures).force;
  Eigen::Vector3d pressure0 = Eigen::Vector3d::Zero();
  for (const auto& cell : fc0.cells) {
    const PolygonStressResultant r =
        integrate_normal_stress_over_polygon(law, cell.vertices, cell.closures);
    if (r.centre_of_pressure) pressure0 += r.force * *r.centre_of_pressure;
  }
  const TwistGeometry tg0 = face_twist_geometry(fc0.cells, g0.normal, force0, pressure0 / force0);
  const double moment0 = mu * face_radial_normal_moment(fc0.cells, law, tg0.centre);
  const Eigen::Vector3d tangent = g0.normal.unitOrthogonal();
  for (auto _ : state) {
    const ContactGeometry g = boon2012_contact(j.a, j.b, 0.2, Boon2012Settings{}, &cache);
    const FaceContactGeometry fc = face_contact_geometry(j.a, j.b, g.point, g.normal, 0.2);
    double force = 0.0, area = 0.0;
    Eigen::Vector3d pressure = Eigen::Vector3d::Zero();
    for (const auto& cell : fc.cells) {
      const PolygonStressResultant r =
          integrate_normal_stress_over_polygon(law, cell.vertices, cell.closures);
      force += r.force;
      area += r.compressed_area;
      if (r.centre_of_pressure) pressure += r.force * *r.centre_of_pressure;
    }
    const Eigen::Vector3d xp = pressure / force;
    TwistGeometry tg = face_twist_geometry(fc.cells, g.normal, force, xp);
    ShearState shear_state;
    shear_state.force = level * mu * force0 * tangent;
    TwistState twist;
    twist.moment = level * moment0;
    const double turn = 1e-9, stress = force / area;
    advance_twist(twist, shear, shear_state, stress, tg, {fc.cells, law}, turn);
    ShearIncrement inc;
    inc.displacement = -1e-9 * tangent;
    inc.normal_force = force;
    inc.normal_stress = stress;
    inc.contact_area = area;
    inc.normal = g.normal;
    update_shear(shear, shear_state, inc);
    const ShearTwistResult st =
        interact_shear_twist(shear_state, twist, shear, {stress, force, area}, tg, {fc.cells, law},
                             {xp, g.normal, inc.displacement, turn});
    benchmark::DoNotOptimize(st);
    benchmark::DoNotOptimize(shear_state.force);
    benchmark::DoNotOptimize(twist.moment);
  }
}

// Arguments: tilt in 1e-4 rad (0: closed joint; 5: partly open), law (0 linear, 1 exponential).
BENCHMARK(BM_ContactPoint)->ArgsProduct({{0, 5}, {0, 1}});
BENCHMARK(BM_ContactFaceIntegrated)->ArgsProduct({{0, 5}, {0, 1}});
// Third argument: 0 an elastic turn (the bound suffices), 1 a turn that slips (exact moment).
BENCHMARK(BM_ContactFaceIntegratedTwist)->ArgsProduct({{0, 5}, {0, 1}, {0, 1}});
// Third argument: 0 well inside both limits, 1 outside the limit surface (full slip).
BENCHMARK(BM_ContactFaceIntegratedShearTwist)->ArgsProduct({{0, 5}, {0, 1}, {0, 1}});

}  // namespace
}  // namespace blockdem
