// exp, log, pow, sin and cos of core/portable_math.hpp against the C library's long double versions
// (64-bit significands, far below a double's ulp), over random arguments across their ranges and at
// the edges. Their bits are the same on the GPU (bench/gpu/law_bits.cu checks it there); here they
// must be accurate to the bound the header states.
#include "core/portable_math.hpp"

#include <cmath>
#include <cstdint>
#include <gtest/gtest.h>
#include <limits>
#include <random>

namespace yuxi {
namespace {

// |computed - exact| in units of the last place of the exact value's double.
double ulps(double computed, long double exact) {
  const double rounded = static_cast<double>(exact);
  const double ulp = std::nextafter(std::fabs(rounded), std::numeric_limits<double>::infinity()) -
                     std::fabs(rounded);
  return static_cast<double>(std::fabs(static_cast<long double>(computed) - exact) / ulp);
}

// The largest error over n arguments drawn uniformly in [lo, hi).
template <class Computed, class Exact>
double worst_ulps(double lo, double hi, int n, Computed computed, Exact exact) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(lo, hi);
  double worst = 0;
  for (int k = 0; k < n; ++k) {
    const double x = u(rng);
    worst = std::fmax(worst, ulps(computed(x), exact(x)));
  }
  return worst;
}

TEST(PortableMath, ExpIsWithinOneUlpOverItsWholeRange) {
  const auto mine = [](double x) { return portable::exp(x); };
  const auto exact = [](double x) { return std::exp(static_cast<long double>(x)); };
  EXPECT_LE(worst_ulps(-1, 1, 400000, mine, exact), 1.0);
  EXPECT_LE(worst_ulps(-40, 1, 400000, mine, exact), 1.0); // the laws' decays
  EXPECT_LE(worst_ulps(-708, 709.7, 400000, mine, exact), 1.0);
  EXPECT_LE(worst_ulps(-1e-8, 1e-8, 100000, mine, exact), 1.0);
}

TEST(PortableMath, ExpAtTheEdges) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(portable::exp(0.0), 1.0);
  EXPECT_EQ(portable::exp(-0.0), 1.0);
  EXPECT_EQ(portable::exp(inf), inf);
  EXPECT_EQ(portable::exp(-inf), 0.0);
  EXPECT_EQ(portable::exp(710.0), inf);
  EXPECT_EQ(portable::exp(-746.0), 0.0);
  EXPECT_TRUE(std::isnan(portable::exp(std::numeric_limits<double>::quiet_NaN())));
  // Results below the normal range: the long double value rounded once, within a subnormal ulp.
  for (double x : {-708.5, -720.0, -740.0, -744.4}) {
    const double exact = static_cast<double>(std::exp(static_cast<long double>(x)));
    EXPECT_LE(std::fabs(portable::exp(x) - exact), 0x1p-1074) << x;
  }
  EXPECT_LE(ulps(portable::exp(709.78), std::exp(static_cast<long double>(709.78))), 1.0);
}

TEST(PortableMath, LogIsWithinOneUlp) {
  const auto mine = [](double x) { return portable::log(x); };
  const auto exact = [](double x) { return std::log(static_cast<long double>(x)); };
  EXPECT_LE(worst_ulps(0.5, 2, 400000, mine, exact), 1.0);
  EXPECT_LE(worst_ulps(1e-6, 10, 400000, mine, exact), 1.0);
  EXPECT_LE(worst_ulps(1, 1e300, 200000, mine, exact), 1.0);
  // Across the exponents, the subnormals included.
  double worst = 0;
  for (double x = 0x1p-1074; x < 1e300; x = std::fmax(1.37 * x, std::nextafter(x, 1.0)))
    worst = std::fmax(worst, ulps(portable::log(x), std::log(static_cast<long double>(x))));
  EXPECT_LE(worst, 1.0);
}

TEST(PortableMath, LogAtTheEdges) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(portable::log(1.0), 0.0);
  EXPECT_EQ(portable::log(0.0), -inf);
  EXPECT_EQ(portable::log(inf), inf);
  EXPECT_TRUE(std::isnan(portable::log(-1.0)));
  EXPECT_TRUE(std::isnan(portable::log(std::numeric_limits<double>::quiet_NaN())));
}

TEST(PortableMath, PowIsWithinItsBound) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> base(1e-6, 10), power(0.05, 3);
  for (int k = 0; k < 200000; ++k) {
    const double x = base(rng), p = power(rng);
    const double bound = 1 + 2 * std::fabs(p * std::log(x));
    ASSERT_LE(ulps(portable::pow(x, p),
                   std::pow(static_cast<long double>(x), static_cast<long double>(p))),
              bound)
        << x << "^" << p;
  }
  EXPECT_EQ(portable::pow(0.3, 0.5), std::sqrt(0.3));
  EXPECT_EQ(portable::pow(0.3, 0.0), 1.0);
  EXPECT_EQ(portable::pow(0.3, 1.0), 0.3);
  EXPECT_EQ(portable::pow(0.0, 1.5), 0.0);
}

TEST(PortableMath, SinAndCosAreWithinTheirBound) {
  const auto sin_of = [](double x) { return portable::sin_cos(x).sin; };
  const auto cos_of = [](double x) { return portable::sin_cos(x).cos; };
  const auto sinl_of = [](double x) { return std::sin(static_cast<long double>(x)); };
  const auto cosl_of = [](double x) { return std::cos(static_cast<long double>(x)); };
  // Within pi/4 the kernels alone: 1 ulp. Beyond, the reduced argument's rounding adds up to
  // about one more.
  for (const double reach : {1e-8, 0.7}) {
    EXPECT_LE(worst_ulps(-reach, reach, 200000, sin_of, sinl_of), 1.0) << reach;
    EXPECT_LE(worst_ulps(-reach, reach, 200000, cos_of, cosl_of), 1.0) << reach;
  }
  for (const double reach : {4.0, 1e4, 1.5e6}) {
    EXPECT_LE(worst_ulps(-reach, reach, 200000, sin_of, sinl_of), 2.5) << reach;
    EXPECT_LE(worst_ulps(-reach, reach, 200000, cos_of, cosl_of), 2.5) << reach;
  }
}

TEST(PortableMath, SinAndCosNextToMultiplesOfHalfPi) {
  // There the reduced argument is tiny and its rounding decides the result's last bits.
  const long double half_pi = 1.570796326794896619231321691639751442L;
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<long> multiple(1, 1000000);
  double worst = 0;
  for (int n = 0; n < 100000; ++n) {
    double x = static_cast<double>(static_cast<long double>(multiple(rng)) * half_pi);
    if (n % 2) x = std::nextafter(x, 0.0);
    const auto [s, c] = portable::sin_cos(x);
    worst = std::fmax(worst, ulps(s, std::sin(static_cast<long double>(x))));
    worst = std::fmax(worst, ulps(c, std::cos(static_cast<long double>(x))));
  }
  EXPECT_LE(worst, 2.5);
}

TEST(PortableMath, SinAndCosAtTheEdges) {
  EXPECT_EQ(portable::sin_cos(0.0).sin, 0.0);
  EXPECT_EQ(portable::sin_cos(0.0).cos, 1.0);
  // -0 gives +0, as the general path's reduction would make it: a turn by -0 and one by +0 are
  // the same bits, whichever path a loop takes.
  EXPECT_FALSE(std::signbit(portable::sin_cos(-0.0).sin));
  EXPECT_FALSE(std::signbit(portable::detail::sin_kernel(-0.0)));
  EXPECT_EQ(portable::sin_cos(-0.0).cos, 1.0);
  EXPECT_EQ(portable::sin_cos(1e-300).sin, 1e-300);
  EXPECT_TRUE(std::isnan(portable::sin_cos(std::numeric_limits<double>::infinity()).sin));
  EXPECT_TRUE(std::isnan(portable::sin_cos(std::numeric_limits<double>::quiet_NaN()).cos));
  // Far beyond the accurate range: still a sine and a cosine, with no undefined conversion.
  const auto [s_far, c_far] = portable::sin_cos(1e300);
  EXPECT_NEAR(s_far * s_far + c_far * c_far, 1.0, 1e-15);
  for (const double x : {0.5, 1.0, 2.0, 3.0, 10.0, -7.5}) {
    const auto [s, c] = portable::sin_cos(x);
    EXPECT_NEAR(s * s + c * c, 1.0, 4e-16) << x;
  }
}

} // namespace
} // namespace yuxi
