// The base motion's kinematics against independent oracles: a record's displacement against the
// double integral u(T) = ∫_0^T (T - s) a(s) ds by Simpson's rule (exact for the quadratic
// integrand of a piecewise-linear a), its velocity against the trapezoidal rule (exact for a
// linear a), and the pulses' velocity and displacement against numerical quadrature of their
// acceleration (composite Simpson, 20000 panels).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "blockdem/dynamics/base_motion.hpp"
#include "blockdem/numerics/units.hpp"

namespace blockdem::test::base_motion_kinematics {
namespace {

BaseMotion irregular_record() {
  BaseMotion m;
  m.times = {0.01, 0.013, 0.037, 0.05, 0.081, 0.1};
  m.accelerations = {Eigen::Vector3d(0.0, 0.0, 0.0),  Eigen::Vector3d(2.0, -1.0, 0.3),
                     Eigen::Vector3d(-1.5, 0.5, 0.0), Eigen::Vector3d(3.0, 0.0, -0.2),
                     Eigen::Vector3d(-0.5, 1.0, 0.1), Eigen::Vector3d(0.7, 0.0, 0.0)};
  m.prepare();
  return m;
}

// ∫_0^T (T - s) a(s) ds and ∫_0^T a(s) ds of the record, segment by segment (a = 0 outside).
void record_oracle(const BaseMotion& m, double T, Eigen::Vector3d& u, Eigen::Vector3d& v) {
  u.setZero();
  v.setZero();
  for (std::size_t i = 0; i + 1 < m.times.size(); ++i) {
    const double t0 = m.times[i], t1 = std::min(m.times[i + 1], T);
    if (t1 <= t0) break;
    const auto a = [&](double s) {
      const double f = (s - m.times[i]) / (m.times[i + 1] - m.times[i]);
      return Eigen::Vector3d((1 - f) * m.accelerations[i] + f * m.accelerations[i + 1]);
    };
    const double h = t1 - t0, mid = 0.5 * (t0 + t1);
    v += 0.5 * h * (a(t0) + a(t1));
    u += h / 6.0 * ((T - t0) * a(t0) + 4.0 * (T - mid) * a(mid) + (T - t1) * a(t1));
  }
}

TEST(BaseMotionKinematics, RecordIsIntegratedExactly) {
  const BaseMotion m = irregular_record();
  EXPECT_NO_THROW(m.validate());
  // Inside segments, at a knot, and after the record (constant velocity).
  for (const double T : {0.005, 0.012, 0.037, 0.06, 0.0999, 0.1, 0.1734}) {
    Eigen::Vector3d u, v;
    record_oracle(m, T, u, v);
    const BaseKinematics k = m.at(T);
    EXPECT_LE((k.displacement - u).norm(), 1e-12 * std::max(1e-6, u.norm())) << T;
    EXPECT_LE((k.velocity - v).norm(), 1e-12 * std::max(1e-6, v.norm())) << T;
  }
  EXPECT_EQ(m.at(0.2).acceleration, Eigen::Vector3d::Zero());
  EXPECT_DOUBLE_EQ(m.at(0.025).acceleration.x(), 2.0 + (0.025 - 0.013) / 0.024 * (-3.5));
}

// Composite Simpson of f over [0, T] with n panels.
double simpson(const std::function<double(double)>& f, double T, int n) {
  const double h = T / n;
  double s = f(0.0) + f(T);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * f(i * h);
  return s * h / 3.0;
}

void expect_pulse_integrals(const BaseMotion& m, double T) {
  const auto a = [&m](double s) { return m.at(s).acceleration.dot(m.direction); };
  const double v = simpson(a, T, 20000);
  const double u = simpson([&](double s) { return (T - s) * a(s); }, T, 20000);
  const BaseKinematics k = m.at(T);
  const double scale = std::abs(m.amplitude) * std::max(T, m.end_time());
  EXPECT_NEAR(k.velocity.dot(m.direction), v, 1e-9 * scale) << T;
  EXPECT_NEAR(k.displacement.dot(m.direction), u, 1e-9 * scale * T) << T;
}

TEST(BaseMotionKinematics, SineAndRickerMatchQuadrature) {
  BaseMotion sine;
  sine.shape = BaseMotion::Shape::sine;
  sine.amplitude = 3.0;
  sine.period = 0.4;
  sine.cycles = 2;
  sine.direction = Eigen::Vector3d(0.6, 0.8, 0.0);
  EXPECT_NO_THROW(sine.validate());
  for (const double T : {0.13, 0.4, 0.71, 0.8}) expect_pulse_integrals(sine, T);
  // Whole periods end at rest, and the base stays where they leave it.
  EXPECT_NEAR(sine.at(0.8).velocity.norm(), 0.0, 1e-14);
  EXPECT_EQ(sine.at(1.5).displacement, sine.at(0.8).displacement);

  BaseMotion ricker;
  ricker.shape = BaseMotion::Shape::ricker;
  ricker.amplitude = -2.0;
  ricker.frequency = 5.0;
  ricker.peak_time = 0.3;
  EXPECT_NO_THROW(ricker.validate());
  for (const double T : {0.1, 0.3, 0.45, 0.6, 0.9}) expect_pulse_integrals(ricker, T);
}

TEST(BaseMotionKinematics, RectangularPulseKeepsItsFinalVelocity) {
  BaseMotion m;
  m.shape = BaseMotion::Shape::rectangular;
  m.amplitude = 4.905;
  m.duration = 0.1;
  const BaseKinematics k = m.at(0.25);
  EXPECT_DOUBLE_EQ(k.velocity.x(), 0.4905);
  EXPECT_DOUBLE_EQ(k.displacement.x(), 0.5 * 4.905 * 0.01 + 0.4905 * 0.15);
  EXPECT_EQ(k.acceleration, Eigen::Vector3d::Zero());
  EXPECT_DOUBLE_EQ(m.at(0.05).acceleration.x(), 4.905);
}

TEST(BaseMotionKinematics, UnusableHistoriesAreRefused) {
  BaseMotion m;
  m.shape = BaseMotion::Shape::rectangular;
  m.amplitude = 1.0;
  m.duration = 0.0;
  EXPECT_THROW(m.validate(), std::invalid_argument);
  BaseMotion r = irregular_record();
  r.times[3] = r.times[2];
  EXPECT_THROW(r.validate(), std::invalid_argument);
  r = irregular_record();
  r.accelerations[2].x() = std::nan("");
  EXPECT_THROW(r.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace blockdem::test::base_motion_kinematics
