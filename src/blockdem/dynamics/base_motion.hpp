// Prescribed base motion of a dynamic stage: an acceleration history a(t) of the base blocks
// (a record, linear between its samples, or a named pulse) and its exact integrals v(t), u(t).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace blockdem {

/// The base's acceleration, velocity and displacement at one time of its history (world frame).
struct BaseKinematics {
  Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();  ///< (m/s^2)
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();      ///< (m/s)
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();  ///< from the stage start (m)
};

/// An acceleration history of the base, starting at rest at stage time 0 (translation only).
///
/// - `record`: samples (t_i, a_i), a(t) linear between them, 0 before the first sample. On a
///   segment of length h, with s = t - t_i and a(s) = a_i + (a_{i+1} - a_i) s / h:
///     v(s) = v_i + a_i s + (a_{i+1} - a_i) s^2 / (2h),
///     u(s) = u_i + v_i s + a_i s^2 / 2 + (a_{i+1} - a_i) s^3 / (6h),
///   the exact integrals of the piecewise-linear a (v piecewise quadratic, u cubic).
/// - `rectangular`: a = a0 d for 0 <= t < duration: v = a0 t d, u = a0 t^2 / 2 d.
/// - `sine`: a = a0 sin(2 pi t / T) d over `cycles` whole periods T:
///     v = a0 T / (2 pi) (1 - cos(2 pi t / T)) d, u = a0 T / (2 pi) (t - T / (2 pi) sin(2 pi t /
///     T)) d;
///   it ends at rest.
/// - `ricker`: the Ricker wavelet (Ricker 1953, "The form and laws of propagation of seismic
///   wavelets", Geophysics 18(1), 10-40: a Gaussian's second derivative, negated), with b = pi f
///   and tau = t - t_p: a = a0 (1 - 2 b^2 tau^2) exp(-b^2 tau^2) d for every t >= 0. Since d/dtau
///   [tau exp(-b^2 tau^2)] = (1 - 2 b^2 tau^2) exp(-b^2 tau^2), in closed form
///     v = a0 (tau e^{-b^2 tau^2} + t_p e^{-b^2 t_p^2}) d,
///     u = a0 ((e^{-b^2 t_p^2} - e^{-b^2 tau^2}) / (2 b^2) + t_p e^{-b^2 t_p^2} t) d.
///
/// After a record or a rectangular or sine pulse ends (the last sample, the pulse's end) the
/// acceleration is zero and the base keeps its final velocity: a record should end at rest. The
/// Ricker wavelet has no end (its tail is below 1e-8 a0 from t_p + 1.5 / f on); end_time() gives
/// 2 t_p for it, and it leaves the base at 2 a0 t_p e^{-b^2 t_p^2}, negligible for t_p >= 1/f.
struct BaseMotion {
  enum class Shape { record, rectangular, sine, ricker };
  Shape shape = Shape::record;
  std::string group = "base";  ///< the blocks that move (a group of fixed blocks)

  // Shape::record: sample times (s, strictly increasing, the first >= 0) and accelerations.
  std::vector<double> times;
  std::vector<Eigen::Vector3d> accelerations;  ///< (m/s^2)

  // The pulses: a0 along the unit direction d.
  double amplitude = 0.0;                                ///< a0 (m/s^2)
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  ///< d (unit)
  double duration = 0.0;                                 ///< rectangular (s)
  double period = 0.0;                                   ///< sine: T (s)
  int cycles = 1;                                        ///< sine: whole periods (-)
  double frequency = 0.0;                                ///< ricker: f (Hz)
  double peak_time = 0.0;                                ///< ricker: t_p (s)

  /// Fills the record's knot velocities and displacements (call after setting the samples).
  void prepare();
  /// Throws std::invalid_argument naming the field when a value is unusable.
  void validate() const;
  /// The base's kinematics at stage time t >= 0 (s).
  BaseKinematics at(double t) const;
  /// Where the history ends (s): the last sample, the pulse's end, 2 t_p for the Ricker wavelet.
  double end_time() const;

 private:
  std::vector<Eigen::Vector3d> knot_velocity_;      ///< v(t_i) of the record (m/s)
  std::vector<Eigen::Vector3d> knot_displacement_;  ///< u(t_i) of the record (m)
  BaseKinematics record_at(double t) const;
  BaseKinematics pulse_at(double t) const;
};

}  // namespace blockdem
