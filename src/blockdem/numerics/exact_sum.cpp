// Exact summation of doubles in a long fixed-point accumulator, rounded once.
#include "blockdem/numerics/exact_sum.hpp"

#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace blockdem {
namespace {

constexpr std::int64_t kDigitMask = 0xffffffff;
constexpr std::int64_t kMaxPending = std::int64_t{1} << 29;
/// Exponent of the lowest digit's unit: digit i weighs 2^(32 i + kLowestExponent).
constexpr int kLowestExponent = -1074;

}  // namespace

void ExactSum::add(double x) {
  if (std::isnan(x)) {
    ++nan_;
    return;
  }
  if (std::isinf(x)) {
    ++(x > 0 ? pos_inf_ : neg_inf_);
    return;
  }
  const auto bits = std::bit_cast<std::uint64_t>(x);
  const auto biased = static_cast<int>((bits >> 52) & 0x7ff);
  const std::uint64_t fraction = bits & ((std::uint64_t{1} << 52) - 1);
  if (biased == 0 && fraction == 0) return;  // +0 or -0
  // x = ±m 2^(p - 1074) with m < 2^53 and p >= 0: p is the bit position in the accumulator.
  const std::uint64_t m = biased == 0 ? fraction : fraction | (std::uint64_t{1} << 52);
  const int p = biased == 0 ? 0 : biased - 1;
  const int i = p / 32, s = p % 32;
  // m 2^s spread over digits i, i+1, i+2 in pieces below 2^32 (no 64-bit overflow: m's low
  // 32 bits shifted by s < 32 stay below 2^63, its high 21 bits below 2^52).
  const std::uint64_t low = (m & 0xffffffff) << s, high = (m >> 32) << s;
  const auto d0 = static_cast<std::int64_t>(low & 0xffffffff);
  const auto d1 = static_cast<std::int64_t>((low >> 32) + (high & 0xffffffff));
  const auto d2 = static_cast<std::int64_t>(high >> 32);
  if (bits >> 63) {
    digit_[i] -= d0;
    digit_[i + 1] -= d1;
    digit_[i + 2] -= d2;
  } else {
    digit_[i] += d0;
    digit_[i + 1] += d1;
    digit_[i + 2] += d2;
  }
  if (++pending_ >= kMaxPending) normalize();
}

ExactSum& ExactSum::operator+=(const ExactSum& other) {
  ExactSum o = other;
  o.normalize();
  normalize();
  for (int k = 0; k < kDigits; ++k) digit_[k] += o.digit_[k];
  nan_ += o.nan_;
  pos_inf_ += o.pos_inf_;
  neg_inf_ += o.neg_inf_;
  pending_ = 2;  // digits now below 2^33: as after two adds
  return *this;
}

void ExactSum::normalize() {
  for (int k = 0; k + 1 < kDigits; ++k) {
    const std::int64_t carry = digit_[k] >> 32;  // floor division by 2^32
    digit_[k] &= kDigitMask;
    digit_[k + 1] += carry;
  }
  pending_ = 0;
}

std::array<std::int64_t, ExactSum::kLimbs> ExactSum::limbs() const {
  ExactSum n = *this;
  n.normalize();
  std::array<std::int64_t, kLimbs> out{};
  for (int k = 0; k < kDigits; ++k) out[k] = n.digit_[k];
  out[kDigits] = n.nan_;
  out[kDigits + 1] = n.pos_inf_;
  out[kDigits + 2] = n.neg_inf_;
  return out;
}

ExactSum ExactSum::from_limbs(std::span<const std::int64_t> limbs) {
  if (limbs.size() != static_cast<std::size_t>(kLimbs))
    throw std::invalid_argument("ExactSum::from_limbs: expected " + std::to_string(kLimbs) +
                                " limbs");
  ExactSum s;
  for (int k = 0; k < kDigits; ++k) s.digit_[k] = limbs[static_cast<std::size_t>(k)];
  s.nan_ = limbs[kDigits];
  s.pos_inf_ = limbs[kDigits + 1];
  s.neg_inf_ = limbs[kDigits + 2];
  s.normalize();
  return s;
}

double ExactSum::value() const {
  if (nan_ > 0 || (pos_inf_ > 0 && neg_inf_ > 0)) return std::numeric_limits<double>::quiet_NaN();
  if (pos_inf_ > 0) return std::numeric_limits<double>::infinity();
  if (neg_inf_ > 0) return -std::numeric_limits<double>::infinity();
  ExactSum n = *this;
  n.normalize();
  // The magnitude in digits [0, 2^32): negate a negative sum (two's complement over digits).
  const bool negative = n.digit_[kDigits - 1] < 0;
  if (negative) {
    for (auto& d : n.digit_) d = -d;
    n.normalize();
  }
  int top = kDigits - 1;
  while (top >= 0 && n.digit_[top] == 0) --top;
  if (top < 0) return 0.0;
  // The leading bit L; keep bits L .. L-52, then round on bit L-53 and the bits below it.
  const auto bit = [&n](int pos) {
    return (static_cast<std::uint64_t>(n.digit_[pos / 32]) >> (pos % 32)) & 1;
  };
  const int lead = 32 * top + 63 - std::countl_zero(static_cast<std::uint64_t>(n.digit_[top]));
  const int last = lead >= 52 ? lead - 52 : 0;  // below 2^-1021 every bit is kept: exact
  std::uint64_t keep = 0;
  for (int pos = lead; pos >= last; --pos) keep = (keep << 1) | bit(pos);
  if (last > 0 && bit(last - 1) != 0) {
    // At least half an ulp: up when more than half (any lower bit) or on a tie to even.
    bool below = false;
    const int r = last - 1;
    for (int k = 0; k < r / 32 && !below; ++k) below = n.digit_[k] != 0;
    below = below || (static_cast<std::uint64_t>(n.digit_[r / 32]) &
                      ((std::uint64_t{1} << (r % 32)) - 1)) != 0;
    if (below || (keep & 1) != 0) ++keep;
  }
  const int exponent = last + kLowestExponent;
  // keep <= 2^53 converts exactly; ldexp is exact unless the result overflows (to infinity).
  const double magnitude = std::ldexp(static_cast<double>(keep), exponent);
  return negative ? -magnitude : magnitude;
}

}  // namespace blockdem
