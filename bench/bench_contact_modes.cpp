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
#include "blockdem/world/contact_twist.hpp"

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
  j.a = Polyhedron::box({s, s, s}).planes();
  const Eigen::Matrix3d r = Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const double reach = 0.5 * s * (std::cos(tilt) + std::sin(std::abs(tilt)));
  j.b = Polyhedron::box({s, s, s}).transformed(r, {0.5 * s + reach - 1e-5, 0, 0}).planes();
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

// The same with the twisting resistance (issue 14): the compressed area's J and ∫ σ_n r dA over
// the cells, and one step of the torsional spring.
void BM_ContactFaceIntegratedTwist(benchmark::State& state) {
  const Joint j = beam_joint(static_cast<double>(state.range(0)) * 1e-4);
  const NormalLaw& law = law_of(static_cast<int>(state.range(1)));
  const ShearLaw shear = LinearShear{};
  Boon2012Cache cache;
  if (!boon2012_contact(j.a, j.b, 0.2, Boon2012Settings{}).touching)
    state.SkipWithError("no contact");
  TwistState twist;
  for (auto _ : state) {
    const ContactGeometry g = boon2012_contact(j.a, j.b, 0.2, Boon2012Settings{}, &cache);
    const FaceContactGeometry fc = face_contact_geometry(j.a, j.b, g.point, g.normal, 0.2);
    double force = 0.0, area = 0.0;
    for (const auto& cell : fc.cells) {
      const PolygonStressResultant r =
          integrate_normal_stress_over_polygon(law, cell.vertices, cell.closures);
      force += r.force;
      area += r.compressed_area;
    }
    const TwistGeometry tg = face_twist_geometry(fc.cells, law);
    benchmark::DoNotOptimize(
        advance_contact_twist(twist, shear, ShearState{}, force / area, tg, 1e-9));
    benchmark::DoNotOptimize(force);
  }
}

// Arguments: tilt in 1e-4 rad (0: closed joint; 5: partly open), law (0 linear, 1 exponential).
BENCHMARK(BM_ContactPoint)->ArgsProduct({{0, 5}, {0, 1}});
BENCHMARK(BM_ContactFaceIntegrated)->ArgsProduct({{0, 5}, {0, 1}});
BENCHMARK(BM_ContactFaceIntegratedTwist)->ArgsProduct({{0, 5}, {0, 1}});

}  // namespace
}  // namespace blockdem
