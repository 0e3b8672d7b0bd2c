// The two-block rig of the virtual laboratory reproduces the joint-law kernels: compression (load
// levels to equilibrium) and direct shear at constant normal stress, each within 1% of the
// kernel's curve, for the linear and exponential normal laws and the linear, stress-linear
// (eq 2) and continuously-yielding (eqs 6-8) shear laws of Boon, Houlsby & Utili (2015), in both
// contact modes (the paper's boon2012 point contact and face_integrated).
#include <gtest/gtest.h>

#include <cmath>
#include <ostream>
#include <string>
#include <tuple>

#include "blockdem/lab/compression_test.hpp"
#include "blockdem/lab/shear_test.hpp"

namespace blockdem {
namespace {

std::string mode_name(ContactMode mode) {
  return to_string(mode);
}

struct CompressionCase {
  const char* name;
  NormalLaw law;
  double max_stress;  // Pa
};

// GoogleTest names a case by its parameter: by its name here, not by the struct's bytes (padding
// and the name's address included, which changed the case's CTest name from build to build).
void PrintTo(const CompressionCase& c, std::ostream* os) {
  *os << c.name;
}

class DemCompression : public ::testing::TestWithParam<std::tuple<CompressionCase, ContactMode>> {};

TEST_P(DemCompression, ClosureUnderLoadLevelsMatchesTheKernelWithinOnePercent) {
  const auto& [c, mode] = GetParam();
  CompressionTestDef def;
  def.law = c.law;
  def.max_stress = c.max_stress;
  def.steps_per_branch = 8;
  const CompressionCurve kernel = run_compression_kernel(def);
  TwoBlockRigDef rig;
  rig.contact_mode = mode;
  const DemCompressionRun dem = run_compression_dem(def, kernel, rig);
  ASSERT_TRUE(dem.converged) << dem.message;
  // Every loaded point of the path: 8 loading levels and 7 unloading ones (zero stress skipped).
  ASSERT_EQ(dem.points.size(), 15u);
  // The closure is read from the block positions, the stress is the applied weight over A.
  EXPECT_LT(dem.max_relative_closure_difference, 0.01);
  EXPECT_LT(dem.max_relative_stress_difference, 0.01);
  for (const auto& p : dem.points) {
    // The load cell carries the applied weight, and the engine's contact is the full face.
    EXPECT_NEAR(p.reading.normal_stress, p.applied_stress, 0.01 * kernel.max_stress);
    EXPECT_NEAR(p.reading.contact_area, rig.joint_area(), 1e-6 * rig.joint_area());
    EXPECT_NEAR(p.reading.overlap, p.reading.closure, 1e-3 * kernel.max_closure);
  }
}

INSTANTIATE_TEST_SUITE_P(
    NormalLaws, DemCompression,
    ::testing::Combine(
        ::testing::Values(CompressionCase{"linear", LinearNormal{10e9}, 1e6},
                          CompressionCase{"exponential_eq4", ExponentialNormal::eq4(), 1e6},
                          CompressionCase{"exponential_eq3", ExponentialNormal::eq3(), 1e6}),
        ::testing::Values(ContactMode::boon2012, ContactMode::face_integrated)),
    [](const auto& case_info) {
      return std::string(std::get<0>(case_info.param).name) + "_" +
             mode_name(std::get<1>(case_info.param));
    });

struct ShearCase {
  const char* name;
  ShearLaw law;
  double normal_stress;     // Pa
  double max_displacement;  // m
  int cycles;
};

class DemShear : public ::testing::TestWithParam<std::tuple<ShearCase, ContactMode>> {};

TEST_P(DemShear, ShearStressPathMatchesTheKernelWithinOnePercent) {
  const auto& [c, mode] = GetParam();
  ShearTestDef def;
  def.law = c.law;
  def.normal_stress = c.normal_stress;
  def.max_displacement = c.max_displacement;
  def.cycles = c.cycles;
  def.steps = 400;
  const ShearCurve kernel = run_shear_kernel(def);
  TwoBlockRigDef rig;
  rig.contact_mode = mode;
  const DemShearRun dem = run_shear_dem(def, ExponentialNormal::eq4(), kernel, rig);
  ASSERT_TRUE(dem.settled) << dem.message;
  ASSERT_EQ(dem.readings.size(), kernel.points.size());
  // The engine found the closure that carries sigma_n (it started at half of it) and held it.
  EXPECT_LT(dem.max_relative_normal_stress_deviation, 0.01);
  EXPECT_LT(dem.max_displacement_difference, 1e-3 * def.max_displacement);
  EXPECT_LT(dem.max_relative_shear_stress_difference, 0.01);
  for (std::size_t i = 0; i < kernel.points.size(); ++i) {
    EXPECT_NEAR(dem.readings[i].plastic_slip, kernel.points[i].plastic_slip,
                0.01 * def.max_displacement)
        << i;
  }
}

INSTANTIATE_TEST_SUITE_P(
    ShearLaws, DemShear,
    ::testing::Combine(
        ::testing::Values(
            ShearCase{"linear", LinearShear{1e9, JointStrength::from_friction_deg(40.0)}, 0.5e6,
                      1e-3, 0},
            ShearCase{"stress_linear", StressLinearShear{}, 0.5e6, 1e-3, 0},
            ShearCase{"continuously_yielding", ContinuouslyYieldingShear{}, 20e3, 1e-4, 0},
            ShearCase{"continuously_yielding_cyclic", ContinuouslyYieldingShear{}, 20e3, 1e-4, 1}),
        ::testing::Values(ContactMode::boon2012, ContactMode::face_integrated)),
    [](const auto& case_info) {
      return std::string(std::get<0>(case_info.param).name) + "_" +
             mode_name(std::get<1>(case_info.param));
    });

}  // namespace
}  // namespace blockdem
