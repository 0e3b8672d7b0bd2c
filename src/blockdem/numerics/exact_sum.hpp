// An exact sum of doubles, rounded once: the same bits whatever the order of the terms and however
// they are split among partial sums, so sums over blocks spread over processes can be reduced.
#pragma once

#include <array>
#include <cstdint>
#include <span>

namespace blockdem {

/// Sum of doubles held exactly as a fixed-point number with 32-bit digits in 64-bit limbs
/// (a "long accumulator": Kulisch & Miranker 1981; the deferred carries follow Neal 2015,
/// "Fast exact summation using small and large superaccumulators", arXiv:1505.05571, sec. 3).
/// Digit i weighs 2^(32 i - 1074), so every finite double, down to the smallest subnormal
/// 2^-1074, is an exact integer combination of digits; 68 digits reach 2^1102, room for 2^64
/// terms of the largest double. value() rounds the exact sum once, to nearest with ties to even:
/// the result does not depend on the order of add() calls or on how terms were split between
/// accumulators later merged (a one-process sum and a sum over K processes agree bit for bit).
/// An exact zero is +0. Infinities and NaN are counted apart: the value is NaN when a NaN or
/// both infinities were added, else the infinity added; a finite sum beyond the double range
/// rounds to an infinity.
class ExactSum {
 public:
  static constexpr int kDigits = 68;
  /// Size of limbs(): the digits and the counts of NaN, +inf and -inf terms.
  static constexpr int kLimbs = kDigits + 3;

  void add(double x);
  ExactSum& operator+=(double x) {
    add(x);
    return *this;
  }
  /// Adds another accumulator's exact sum.
  ExactSum& operator+=(const ExactSum& other);
  /// The exact sum rounded to the nearest double (ties to even).
  double value() const;

  /// The state as integers whose element-wise integer sum over several accumulators is the
  /// state of their merged sum (an MPI_SUM reduction of int64; exact for fewer than 2^30 parts).
  std::array<std::int64_t, kLimbs> limbs() const;
  /// The accumulator whose state is `limbs` (e.g. reduced over processes).
  static ExactSum from_limbs(std::span<const std::int64_t> limbs);

 private:
  /// Propagates the deferred carries: digits below the top in [0, 2^32), the top one signed.
  void normalize();

  std::array<std::int64_t, kDigits> digit_{};
  std::int64_t nan_ = 0, pos_inf_ = 0, neg_inf_ = 0;
  /// Terms added since the last normalize(): each changes a digit by less than 2^33, so 2^29 of
  /// them cannot overflow a limb.
  std::int64_t pending_ = 0;
};

}  // namespace blockdem
