// The exact accumulator: closed-form sums that naive summation gets wrong, rounding to nearest
// with ties to even, the double range's ends, and agreement with an independent correctly
// rounded summation (Shewchuk's non-overlapping partials) on adversarial random terms, in any
// order and split into any number of merged or limb-reduced parts.
#include "blockdem/numerics/exact_sum.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace blockdem {
namespace {

double exact(const std::vector<double>& xs) {
  ExactSum s;
  for (double x : xs) s.add(x);
  return s.value();
}

/// The oracle: Shewchuk's exact sum as a list of non-overlapping partials (Shewchuk 1997,
/// "Adaptive precision floating-point arithmetic and fast robust geometric predicates", Grow-
/// Expansion with zero elimination), then rounded once to nearest, ties to even. Valid while no
/// partial overflows (the random terms below stay far from the double range's ends).
double oracle(const std::vector<double>& xs) {
  std::vector<double> partials;
  for (double x : xs) {
    std::size_t kept = 0;
    for (double y : partials) {
      if (std::abs(x) < std::abs(y)) std::swap(x, y);
      const double hi = x + y;
      const double lo = y - (hi - x);  // exact error of hi (Dekker's Fast-Two-Sum)
      if (lo != 0.0) partials[kept++] = lo;
      x = hi;
    }
    partials.resize(kept);
    partials.push_back(x);
  }
  // Partials increase in magnitude and do not overlap: add from the top until an addition is
  // inexact, then settle the tie that the remaining partials may break.
  if (partials.empty()) return 0.0;
  std::size_t n = partials.size();
  double hi = partials[--n], lo = 0.0;
  while (n > 0) {
    const double x = hi, y = partials[--n];
    hi = x + y;
    lo = y - (hi - x);
    if (lo != 0.0) break;
  }
  if (n > 0 && ((lo < 0.0 && partials[n - 1] < 0.0) || (lo > 0.0 && partials[n - 1] > 0.0))) {
    // hi + lo is exactly half-way between two doubles and the rest pushes it past: round away.
    const double y = 2.0 * lo, x = hi + y;
    if (y == x - hi) hi = x;
  }
  return hi;
}

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

TEST(ExactSum, ClosedFormsNaiveSummationGetsWrong) {
  // Reference: exact arithmetic by hand. Naive left-to-right summation gives 0, 0 and 0.
  EXPECT_EQ(exact({1e16, 1.0, -1e16}), 1.0);
  EXPECT_EQ(exact({1e100, 1.0, -1e100, 1e-100}), 1.0 + 1e-100);  // = 1.0 after rounding
  // 0.1 + 0.2 - 0.3 in exact arithmetic of the three doubles is 2^-55 (their binary errors).
  EXPECT_EQ(exact({0.1, 0.2, -0.3}), std::ldexp(1.0, -55));
  // The largest doubles: no overflow inside the accumulator.
  const double big = std::numeric_limits<double>::max();
  EXPECT_EQ(exact({big, big, -big}), big);
  EXPECT_EQ(exact({big, big}), std::numeric_limits<double>::infinity());
  EXPECT_EQ(exact({-big, -big}), -std::numeric_limits<double>::infinity());
  // The smallest subnormals are exact digits.
  const double tiny = std::numeric_limits<double>::denorm_min();
  EXPECT_EQ(exact({tiny, tiny, tiny}), 3 * tiny);
  EXPECT_EQ(exact({big, tiny, -big}), tiny);
  EXPECT_EQ(exact({}), 0.0);
  EXPECT_EQ(exact({-2.5, 2.5}), 0.0);
}

TEST(ExactSum, RoundsToNearestTiesToEven) {
  const double u = std::ldexp(1.0, -53);                               // half an ulp of 1
  EXPECT_EQ(exact({1.0, u}), 1.0);                                     // tie: even (1.0)
  EXPECT_EQ(exact({1.0 + 2 * u, u}), 1.0 + 4 * u);                     // tie: even (up)
  EXPECT_EQ(exact({1.0, u, std::ldexp(1.0, -200)}), 1.0 + 2 * u);      // past the tie: up
  EXPECT_EQ(exact({1.0, u, -std::ldexp(1.0, -200)}), 1.0);             // short of it: down
  EXPECT_EQ(exact({-1.0, -u, -std::ldexp(1.0, -200)}), -1.0 - 2 * u);  // symmetric
}

TEST(ExactSum, SpecialValuesFollowIeee) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(exact({1.0, inf, -5.0}), inf);
  EXPECT_EQ(exact({-inf, 3.0}), -inf);
  EXPECT_TRUE(std::isnan(exact({inf, -inf})));
  EXPECT_TRUE(std::isnan(exact({1.0, std::numeric_limits<double>::quiet_NaN()})));
}

/// Terms whose magnitudes span 600 binades with heavy cancellation: each term and its near
/// negation, shuffled, plus small remainders.
std::vector<double> adversarial_terms(std::mt19937_64& rng, int count) {
  std::uniform_real_distribution<double> mantissa(1.0, 2.0);
  std::uniform_int_distribution<int> exponent(-300, 300);
  std::vector<double> xs;
  for (int k = 0; k < count; ++k) {
    const double x = std::ldexp(mantissa(rng), exponent(rng)) * (k % 3 == 0 ? -1.0 : 1.0);
    xs.push_back(x);
    if (k % 2 == 0) xs.push_back(-x * (1.0 - std::ldexp(1.0, -40)));
  }
  std::shuffle(xs.begin(), xs.end(), rng);
  return xs;
}

TEST(ExactSum, AgreesWithShewchukOracleInAnyOrderAndSplit) {
  // Reference: the oracle above, bit for bit; the sum must not change with the order of the
  // terms nor with how they are split into parts merged by += or by integer sums of limbs().
  std::mt19937_64 rng(20261125);
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<double> xs = adversarial_terms(rng, 50 + 10 * trial);
    const double want = oracle(xs);
    ASSERT_TRUE(same_bits(exact(xs), want)) << "trial " << trial;
    std::shuffle(xs.begin(), xs.end(), rng);
    EXPECT_TRUE(same_bits(exact(xs), want));
    for (int parts : {2, 3, 7}) {
      std::vector<ExactSum> part(static_cast<std::size_t>(parts));
      for (std::size_t k = 0; k < xs.size(); ++k) part[k % part.size()].add(xs[k]);
      ExactSum merged;
      std::array<std::int64_t, ExactSum::kLimbs> reduced{};
      for (const ExactSum& p : part) {
        merged += p;
        const auto limbs = p.limbs();
        for (int q = 0; q < ExactSum::kLimbs; ++q) reduced[q] += limbs[q];
      }
      EXPECT_TRUE(same_bits(merged.value(), want)) << parts << " parts";
      EXPECT_TRUE(same_bits(ExactSum::from_limbs(reduced).value(), want)) << parts << " parts";
    }
  }
}

TEST(ExactSum, CarriesAcrossDigits) {
  // Doubling by merging an accumulator with a copy of itself carries a bit through the digits;
  // reference: 2^-1074 doubled 1000 times is 2^-74 exactly, less itself an exact 0, and 3
  // doubled 1020 times is 3 2^1020 (near the top of the double range).
  ExactSum s;
  s.add(std::numeric_limits<double>::denorm_min());
  for (int k = 0; k < 1000; ++k) {
    const ExactSum copy = s;
    s += copy;
  }
  EXPECT_EQ(s.value(), std::ldexp(1.0, 1000 - 1074));
  s.add(-std::ldexp(1.0, 1000 - 1074));
  EXPECT_EQ(s.value(), 0.0);
  ExactSum t;
  t.add(3.0);
  for (int k = 0; k < 1020; ++k) {
    const ExactSum copy = t;
    t += copy;
  }
  EXPECT_EQ(t.value(), std::ldexp(3.0, 1020));
}

}  // namespace
}  // namespace blockdem
