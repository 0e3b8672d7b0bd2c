// The base's acceleration history and its exact integrals (formulas in base_motion.hpp).
#include "blockdem/dynamics/base_motion.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "blockdem/numerics/units.hpp"

namespace blockdem {

void BaseMotion::prepare() {
  knot_velocity_.assign(times.size(), Eigen::Vector3d::Zero());
  knot_displacement_.assign(times.size(), Eigen::Vector3d::Zero());
  if (times.empty()) return;
  // Before the first sample the base rests: a jump to a_0 there, then the segments in turn.
  for (std::size_t i = 0; i + 1 < times.size(); ++i) {
    const double h = times[i + 1] - times[i];
    const Eigen::Vector3d& a0 = accelerations[i];
    const Eigen::Vector3d da = accelerations[i + 1] - a0;
    knot_velocity_[i + 1] = knot_velocity_[i] + h * a0 + (0.5 * h) * da;
    knot_displacement_[i + 1] =
        knot_displacement_[i] + h * knot_velocity_[i] + (0.5 * h * h) * a0 + (h * h / 6.0) * da;
  }
}

void BaseMotion::validate() const {
  const auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
  if (group.empty()) fail("group: name the group of blocks that moves");
  switch (shape) {
    case Shape::record: {
      if (times.size() < 2) fail("file: needs at least two samples");
      if (accelerations.size() != times.size()) fail("file: one acceleration per time");
      if (!(times.front() >= 0.0)) fail("file: the first time must be >= 0 s");
      for (std::size_t i = 0; i < times.size(); ++i) {
        if (!std::isfinite(times[i]) || !accelerations[i].allFinite())
          fail("file: sample " + std::to_string(i + 1) + " is not finite");
        if (i > 0 && !(times[i] > times[i - 1]))
          fail("file: the times must increase strictly (sample " + std::to_string(i + 1) + ")");
      }
      if (knot_velocity_.size() != times.size()) fail("file: the record was not prepared");
      return;
    }
    case Shape::rectangular:
      if (!(duration > 0.0 && std::isfinite(duration))) fail("duration: must be > 0 s and finite");
      break;
    case Shape::sine:
      if (!(period > 0.0 && std::isfinite(period))) fail("period: must be > 0 s and finite");
      if (cycles < 1) fail("cycles: must be at least 1");
      break;
    case Shape::ricker:
      if (!(frequency > 0.0 && std::isfinite(frequency)))
        fail("frequency: must be > 0 Hz and finite");
      if (!(peak_time > 0.0 && std::isfinite(peak_time)))
        fail("peak_time: must be > 0 s and finite");
      break;
  }
  if (!std::isfinite(amplitude)) fail("amplitude_m_s2: must be finite");
  if (!(std::abs(direction.norm() - 1.0) < 1e-12)) fail("direction: must be a unit vector");
}

double BaseMotion::end_time() const {
  switch (shape) {
    case Shape::record:
      return times.empty() ? 0.0 : times.back();
    case Shape::rectangular:
      return duration;
    case Shape::sine:
      return period * cycles;
    case Shape::ricker:
      return 2.0 * peak_time;
  }
  return 0.0;
}

BaseKinematics BaseMotion::at(double t) const {
  return shape == Shape::record ? record_at(t) : pulse_at(t);
}

BaseKinematics BaseMotion::record_at(double t) const {
  BaseKinematics k;
  if (times.empty() || t <= times.front()) return k;
  if (t >= times.back()) {
    // After the record: no acceleration, the final velocity kept.
    const std::size_t n = times.size() - 1;
    k.velocity = knot_velocity_[n];
    k.displacement = knot_displacement_[n] + (t - times.back()) * knot_velocity_[n];
    return k;
  }
  // The segment [t_i, t_{i+1}) holding t.
  const auto it = std::upper_bound(times.begin(), times.end(), t);
  const auto i = static_cast<std::size_t>(it - times.begin()) - 1;
  const double h = times[i + 1] - times[i];
  const double s = t - times[i];
  const Eigen::Vector3d& a0 = accelerations[i];
  const Eigen::Vector3d da = accelerations[i + 1] - a0;
  k.acceleration = a0 + (s / h) * da;
  k.velocity = knot_velocity_[i] + s * a0 + (0.5 * s * s / h) * da;
  k.displacement = knot_displacement_[i] + s * knot_velocity_[i] + (0.5 * s * s) * a0 +
                   (s * s * s / (6.0 * h)) * da;
  return k;
}

BaseKinematics BaseMotion::pulse_at(double t) const {
  double a = 0.0, v = 0.0, u = 0.0;  // along the direction
  const double a0 = amplitude;
  switch (shape) {
    case Shape::record:
      break;
    case Shape::rectangular: {
      const double T = duration;
      if (t < T) {
        a = a0;
        v = a0 * t;
        u = 0.5 * a0 * t * t;
      } else {
        v = a0 * T;
        u = 0.5 * a0 * T * T + a0 * T * (t - T);
      }
      break;
    }
    case Shape::sine: {
      const double T = period;
      const double w = 2.0 * kPi / T;
      const double te = std::min(t, T * cycles);
      // Ends at rest after whole periods: u stays at its value there.
      if (t < T * cycles) a = a0 * std::sin(w * te);
      v = t < T * cycles ? a0 / w * (1.0 - std::cos(w * te)) : 0.0;
      u = a0 / w * (te - std::sin(w * te) / w);
      break;
    }
    case Shape::ricker: {
      const double b2 = kPi * kPi * frequency * frequency;
      const double tau = t - peak_time;
      const double e = std::exp(-b2 * tau * tau);
      const double e0 = std::exp(-b2 * peak_time * peak_time);
      a = a0 * (1.0 - 2.0 * b2 * tau * tau) * e;
      v = a0 * (tau * e + peak_time * e0);
      u = a0 * ((e0 - e) / (2.0 * b2) + peak_time * e0 * t);
      break;
    }
  }
  BaseKinematics k;
  k.acceleration = a * direction;
  k.velocity = v * direction;
  k.displacement = u * direction;
  return k;
}

}  // namespace blockdem
