// Normal joint laws (Boon, Houlsby & Utili 2015, eqs 1, 3, 4): closed forms, tangent stiffness,
// antiderivatives against quadrature, validation and the named-parameter factory.
#include "blockdem/contact/normal_laws.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "law_test_support.hpp"

namespace blockdem {
namespace {

using test::invalid_argument_message;
using test::relative_difference;

/// Closures up to 0.1 mm: eq 3 reaches 88 MPa there, far beyond the beam's 1 MPa.
constexpr double kMaxClosure = 1e-4;

TEST(NormalLaws, ZeroStressAndStiffnessWhenOpen) {
  for (const NormalLaw law : {NormalLaw{LinearNormal{}}, NormalLaw{ExponentialNormal::eq3()}}) {
    EXPECT_EQ(normal_stress(law, 0.0), 0.0);
    EXPECT_EQ(normal_stress(law, -1e-5), 0.0);
    EXPECT_EQ(normal_tangent_stiffness(law, -1e-5), 0.0);
    EXPECT_EQ(normal_stress_integral(law, -1e-5), 0.0);
    EXPECT_EQ(normal_stress_second_integral(law, -1e-5), 0.0);
  }
}

TEST(NormalLaws, NanClosureStaysVisible) {
  const double nan = std::nan("");
  for (const NormalLaw law : {NormalLaw{LinearNormal{}}, NormalLaw{ExponentialNormal::eq4()}}) {
    EXPECT_TRUE(std::isnan(normal_stress(law, nan))) << law_name(law);
    EXPECT_TRUE(std::isnan(normal_tangent_stiffness(law, nan))) << law_name(law);
    EXPECT_TRUE(std::isnan(normal_stress_integral(law, nan))) << law_name(law);
    EXPECT_TRUE(std::isnan(normal_stress_second_integral(law, nan))) << law_name(law);
  }
}

TEST(NormalLaws, LinearIsHookean) {
  const NormalLaw law = LinearNormal{10e9};
  EXPECT_DOUBLE_EQ(normal_stress(law, 2e-5), 2e5);
  EXPECT_DOUBLE_EQ(normal_tangent_stiffness(law, 0.0), 10e9);
  EXPECT_DOUBLE_EQ(normal_tangent_stiffness(law, 3e-5), 10e9);
}

TEST(NormalLaws, ExponentialHitsItsClosedFormAtLogarithmicClosures) {
  // sigma = a [exp(b u) - 1] equals m a exactly at u = ln(1 + m) / b.
  const ExponentialNormal e{0.5405e5, 3.7e4};
  for (const double m : {1e-9, 1e-3, 0.5, 1.0, 10.0, 1e4}) {
    const double u = std::log1p(m) / e.b;
    EXPECT_LT(relative_difference(normal_stress(e, u), m * e.a), 1e-13) << "m = " << m;
  }
}

TEST(NormalLaws, ExponentialTangentIsTheDerivativeOfTheStress) {
  // Central differences of sigma(u), independent of normal_tangent_stiffness.
  const NormalLaw law = ExponentialNormal::eq4();
  for (double u = 2e-6; u < kMaxClosure; u += 7e-6) {
    const double h = 1e-9;
    const double numeric = (normal_stress(law, u + h) - normal_stress(law, u - h)) / (2.0 * h);
    EXPECT_LT(relative_difference(normal_tangent_stiffness(law, u), numeric), 1e-6) << u;
  }
}

TEST(NormalLaws, Eq3TangentIsEq1) {
  // Eq 1: k_n = 4e9 + 7.4e4 sigma_n, at every closure.
  const NormalLaw law = ExponentialNormal::eq3();
  EXPECT_DOUBLE_EQ(normal_tangent_stiffness(law, 0.0), 4e9);
  for (double u = 0.0; u < kMaxClosure; u += 1.3e-6) {
    const double expected = 4e9 + 7.4e4 * normal_stress(law, u);
    EXPECT_LT(relative_difference(normal_tangent_stiffness(law, u), expected), 1e-12) << u;
  }
  // The paper prints eq 3's a = k0 / c = 54054.05... Pa to four digits, as 0.5405e5 (+-5 Pa).
  EXPECT_NEAR(std::get<ExponentialNormal>(law).a, 0.5405e5, 5.0);
}

TEST(NormalLaws, Eq4IsHalfTheStiffnessOfEq3) {
  const auto eq3 = ExponentialNormal::eq3();
  const auto eq4 = ExponentialNormal::eq4();
  // Stiffness at zero closure: 2e9 Pa/m, up to the paper's rounding of a to 4 digits (7.5e-5).
  EXPECT_LT(relative_difference(normal_tangent_stiffness(eq4, 0.0), 2e9), 1e-4);
  // At equal stress the tangent of eq 4 is half that of eq 3 (k = (4e9 + 7.4e4 sigma) / 2), and
  // eq 4 needs twice the closure of eq 3 for the same stress.
  for (double u = 0.0; u < kMaxClosure; u += 3.1e-6) {
    const double sigma = normal_stress(eq3, u);
    EXPECT_LT(
        relative_difference(normal_tangent_stiffness(eq4, 2.0 * u), 0.5 * (4e9 + 7.4e4 * sigma)),
        1e-4);
    EXPECT_LT(relative_difference(normal_stress(eq4, 2.0 * u), sigma), 1e-4);
  }
}

TEST(NormalLaws, AntiderivativesMatchQuadrature) {
  for (const NormalLaw law : {NormalLaw{LinearNormal{10e9}}, NormalLaw{ExponentialNormal::eq3()},
                              NormalLaw{ExponentialNormal::eq4()}}) {
    for (const double u : {1e-7, 3e-6, 2e-5, 8e-5}) {
      const double phi1 =
          test::gauss_legendre([&](double s) { return normal_stress(law, s); }, 0.0, u, 50);
      const double phi2 = test::gauss_legendre(
          [&](double s) { return normal_stress_integral(law, s); }, 0.0, u, 50);
      EXPECT_LT(relative_difference(normal_stress_integral(law, u), phi1), 1e-12)
          << law_name(law) << " u = " << u;
      EXPECT_LT(relative_difference(normal_stress_second_integral(law, u), phi2), 1e-12)
          << law_name(law) << " u = " << u;
    }
  }
}

TEST(NormalLaws, AntiderivativesKeepFullPrecisionAtTinyClosure) {
  // For b u << 1: Phi1 = a b u^2/2 (1 + b u/3 + ...), Phi2 = a b u^3/6 (1 + b u/4 + ...).
  const ExponentialNormal e = ExponentialNormal::eq3();
  for (const double u : {1e-15, 1e-12, 1e-10}) {
    const double x = e.b * u;
    EXPECT_LT(relative_difference(normal_stress_integral(e, u),
                                  e.a * e.b * u * u / 2.0 * (1.0 + x / 3.0 + x * x / 12.0)),
              1e-14);
    EXPECT_LT(relative_difference(normal_stress_second_integral(e, u),
                                  e.a * e.b * u * u * u / 6.0 * (1.0 + x / 4.0 + x * x / 20.0)),
              1e-14);
  }
}

TEST(NormalLaws, StripIntegralsFromAntiderivatives) {
  // The header's strip formulas: mean stress and mean of t sigma for closure u0 + t (u1 - u0).
  const NormalLaw law = ExponentialNormal::eq4();
  const double u0 = -2e-5, u1 = 6e-5;
  const auto closure = [&](double t) { return u0 + t * (u1 - u0); };
  const double mean =
      (normal_stress_integral(law, u1) - normal_stress_integral(law, u0)) / (u1 - u0);
  const double first = (normal_stress_integral(law, u1) - (normal_stress_second_integral(law, u1) -
                                                           normal_stress_second_integral(law, u0)) /
                                                              (u1 - u0)) /
                       (u1 - u0);
  // The kink of sigma at t = 0.25 sits on a piece boundary of the oracle.
  EXPECT_LT(relative_difference(
                mean, test::gauss_legendre([&](double t) { return normal_stress(law, closure(t)); },
                                           0.0, 1.0, 40)),
            1e-12);
  EXPECT_LT(
      relative_difference(
          first, test::gauss_legendre([&](double t) { return t * normal_stress(law, closure(t)); },
                                      0.0, 1.0, 40)),
      1e-12);
}

TEST(NormalLaws, ValidationNamesLawAndParameter) {
  const auto message_linear = invalid_argument_message([] { LinearNormal{-1.0}.validate(); });
  EXPECT_NE(message_linear.find("normal law 'linear'"), std::string::npos) << message_linear;
  EXPECT_NE(message_linear.find("'stiffness'"), std::string::npos) << message_linear;
  const auto message_b = invalid_argument_message([] {
    validate(NormalLaw{ExponentialNormal{1e5, std::nan("")}});
  });
  EXPECT_NE(message_b.find("normal law 'exponential'"), std::string::npos) << message_b;
  EXPECT_NE(message_b.find("'b'"), std::string::npos) << message_b;
  EXPECT_NE(message_b.find("nan"), std::string::npos) << message_b;
  EXPECT_NE(invalid_argument_message([] {
              ExponentialNormal{0.0, 1e4}.validate();
            }).find("'a'"),
            std::string::npos);
  EXPECT_NE(
      invalid_argument_message([] { ExponentialNormal::from_tangent(4e9, -1.0); }).find("'c'"),
      std::string::npos);
  EXPECT_NO_THROW(validate(NormalLaw{ExponentialNormal::eq3()}));
  EXPECT_NO_THROW(validate(NormalLaw{LinearNormal{}}));
}

TEST(NormalLaws, FactoryBuildsPresetsAndNamedParameters) {
  const auto eq4 = std::get<ExponentialNormal>(normal_law_from_params("exponential", {}, "eq4"));
  EXPECT_EQ(eq4.a, 0.5405e5);
  EXPECT_EQ(eq4.b, 3.7e4);
  const auto eq3 = std::get<ExponentialNormal>(normal_law_from_params("exponential", {}, "eq3"));
  EXPECT_DOUBLE_EQ(eq3.initial_stiffness(), 4e9);
  const auto tangent = std::get<ExponentialNormal>(
      normal_law_from_params("exponential", {{"k0", 4e9}, {"c", 7.4e4}}));
  EXPECT_EQ(tangent.a, eq3.a);
  EXPECT_EQ(tangent.b, eq3.b);
  const auto ab =
      std::get<ExponentialNormal>(normal_law_from_params("exponential", {{"a", 2e4}, {"b", 5e4}}));
  EXPECT_EQ(ab.a, 2e4);
  EXPECT_EQ(ab.b, 5e4);
  EXPECT_EQ(std::get<LinearNormal>(normal_law_from_params("linear", {})).stiffness, 10e9);
  EXPECT_EQ(
      std::get<LinearNormal>(normal_law_from_params("linear", {{"stiffness", 5e9}})).stiffness,
      5e9);
  EXPECT_EQ(law_name(normal_law_from_params("exponential", {})), "exponential");
}

TEST(NormalLaws, FactoryRejectsWhatItCannotRead) {
  const auto unknown = invalid_argument_message([] {
    normal_law_from_params("linear", {{"k_n", 1e9}});
  });
  EXPECT_NE(unknown.find("unknown parameter 'k_n'"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("stiffness"), std::string::npos) << unknown;
  EXPECT_NE(invalid_argument_message([] { normal_law_from_params("hertz", {}); }).find("'hertz'"),
            std::string::npos);
  EXPECT_NE(invalid_argument_message([] {
              normal_law_from_params("exponential", {}, "eq5");
            }).find("'eq5'"),
            std::string::npos);
  EXPECT_NE(invalid_argument_message([] {
              normal_law_from_params("exponential", {{"a", 1e4}}, "eq4");
            }).find("cannot be combined"),
            std::string::npos);
  EXPECT_NE(invalid_argument_message([] {
              normal_law_from_params("exponential", {{"a", 1e4}});
            }).find("needs 'b'"),
            std::string::npos);
  EXPECT_NE(invalid_argument_message([] {
              normal_law_from_params("exponential", {{"a", 1e4}, {"k0", 1e9}});
            }).find("not both"),
            std::string::npos);
  EXPECT_NE(invalid_argument_message([] {
              normal_law_from_params("linear", {}, "eq4");
            }).find("no presets"),
            std::string::npos);
  EXPECT_NE(invalid_argument_message([] {
              normal_law_from_params("linear", {{"stiffness", -5.0}});
            }).find("'stiffness'"),
            std::string::npos);
}

}  // namespace
}  // namespace blockdem
