// exp, log, pow, sin and cos that give the same bits on every backend.
//
// The C library's exp and the GPU's differ in the last bit for about 6 % of arguments (pow 23 %,
// log 0.1 %; measured on an H100 against glibc 2.36: docs/results/gpu/), while sqrt and division
// are correctly rounded on both and agree always. A contact law that calls std::exp therefore
// gives a GPU run that drifts from the CPU's. These versions use only what is the same everywhere:
// +, -, *, / and sqrt, correctly rounded, never fused (FMA contraction is off for g++ and nvcc),
// and integer work on the bits. They are written by hand because no packaged library promises the
// same bits on the CPU and on the GPU (docs/ARCHITECTURE.md, "The seam for a second backend").
//
// Accuracy (tests/unit/test_portable_math.cpp, against long double): exp and log within 1 ulp;
// pow(x, p) within 1 + 2 |p ln x| ulp (the error of ln x
// grows by the factor p ln x); sin and cos within 1 ulp for |x| <= pi/4, 2.5 ulp for
// |x| < 1.6e6. Methods: Cody & Waite's argument reduction with Taylor
// series (W. J. Cody & W. Waite, Software Manual for the Elementary Functions, 1980).
#pragma once

#include "core/host_device.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace yuxi::portable {

namespace detail {

YUXI_HD inline double from_bits(std::uint64_t b) {
  double d;
  std::memcpy(&d, &b, sizeof d);
  return d;
}
YUXI_HD inline std::uint64_t to_bits(double d) {
  std::uint64_t b;
  std::memcpy(&b, &d, sizeof b);
  return b;
}
// 2^k for a normal power, -1022 <= k <= 1023: built from its bits, exactly.
YUXI_HD inline double power_of_two(int k) {
  return from_bits(static_cast<std::uint64_t>(k + 1023) << 52);
}

// ln 2 in two parts: ln2_hi has 32 significant bits, so k * ln2_hi is exact for |k| < 2^20.
constexpr double ln2_hi = 6.93147180369123816490e-01;
constexpr double ln2_lo = 1.90821492927058770002e-10;
constexpr double inv_ln2 = 1.44269504088896338700e+00;

} // namespace detail

// e^x. Reduction x = k ln2 + r with |r| <= ln2/2, e^r by its Taylor series to r^13 (truncation
// below 4e-18 relative), then scaled by 2^k from the bits.
YUXI_HD inline double exp(double x) {
  using namespace detail;
  if (!(x == x)) return x; // NaN
  if (x > 709.782712893384) return std::numeric_limits<double>::infinity();
  if (x < -745.1332191019412) return 0.0;
  // k = nearest integer to x / ln2; the conversion truncates toward zero, hence the +-0.5.
  const double t = x * inv_ln2;
  const int k = static_cast<int>(t < 0 ? t - 0.5 : t + 0.5);
  const double kd = static_cast<double>(k);
  const double r = (x - kd * ln2_hi) - kd * ln2_lo;
  // e^r = 1 + (r + r^2 q), q = 1/2! + r/3! + ... + r^11/13!: the rounding of the r^2 q term is
  // scaled down by r^2 <= 0.12.
  double q = 1.0 / 6227020800.0;
  q = q * r + 1.0 / 479001600.0;
  q = q * r + 1.0 / 39916800.0;
  q = q * r + 1.0 / 3628800.0;
  q = q * r + 1.0 / 362880.0;
  q = q * r + 1.0 / 40320.0;
  q = q * r + 1.0 / 5040.0;
  q = q * r + 1.0 / 720.0;
  q = q * r + 1.0 / 120.0;
  q = q * r + 1.0 / 24.0;
  q = q * r + 1.0 / 6.0;
  q = q * r + 0.5;
  const double y = 1.0 + (r + (r * r) * q);
  if (k >= -1022 && k <= 1023) return y * power_of_two(k);
  // Results near overflow or below the normal range: two exact scalings, one rounding at the end.
  const int half = k / 2;
  return y * power_of_two(half) * power_of_two(k - half);
}

// ln x. x = 2^e m with sqrt(1/2) <= m < sqrt(2); ln m = 2 atanh(s), s = (m - 1)/(m + 1),
// |s| <= 0.172, by its series to s^25.
YUXI_HD inline double log(double x) {
  using namespace detail;
  if (!(x > 0))
    return x == 0 ? -std::numeric_limits<double>::infinity()
                  : std::numeric_limits<double>::quiet_NaN();
  if (x == std::numeric_limits<double>::infinity()) return x;
  int e = 0;
  if (x < 0x1p-1022) { // subnormal: scale into the normal range first (exact)
    x *= 0x1p54;
    e = -54;
  }
  const std::uint64_t bits = to_bits(x);
  e += static_cast<int>((bits >> 52) & 0x7ff) - 1023;
  double m = from_bits((bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL); // in [1, 2)
  if (m > 1.4142135623730951) {
    m *= 0.5;
    ++e;
  }
  // f = m - 1 is exact; with s = f / (2 + f), ln(1 + f) = 2 atanh(s) = f - s (f - R), where
  // R = 2 s^2/3 + 2 s^4/5 + ... : the rounding of the correction s (f - R) is scaled by |s|.
  const double f = m - 1.0;
  const double s = f / (2.0 + f);
  const double s2 = s * s;
  double q = 2.0 / 25.0;
  q = q * s2 + 2.0 / 23.0;
  q = q * s2 + 2.0 / 21.0;
  q = q * s2 + 2.0 / 19.0;
  q = q * s2 + 2.0 / 17.0;
  q = q * s2 + 2.0 / 15.0;
  q = q * s2 + 2.0 / 13.0;
  q = q * s2 + 2.0 / 11.0;
  q = q * s2 + 2.0 / 9.0;
  q = q * s2 + 2.0 / 7.0;
  q = q * s2 + 2.0 / 5.0;
  q = q * s2 + 2.0 / 3.0;
  const double correction = s * (f - s2 * q);
  const double ed = static_cast<double>(e);
  return ed * ln2_hi + (f - (correction - ed * ln2_lo));
}

// x^p for x >= 0 (NaN for x < 0 unless p is 0): e^(p ln x), with x^0.5 as sqrt (exact rounding).
YUXI_HD inline double pow(double x, double p) {
  if (p == 0.0) return 1.0;
  if (p == 1.0) return x;
  if (p == 0.5 && x >= 0) return std::sqrt(x);
  if (x == 0.0) return p > 0 ? 0.0 : std::numeric_limits<double>::infinity();
  return exp(p * log(x));
}

namespace detail {

// pi/2 in three parts of 33 significant bits each and the tail of the third: k * part is exact
// for |k| < 2^20, so the reduction below loses nothing for |x| < 1.6e6 (fdlibm's constants).
constexpr double pio2_1 = 1.57079632673412561417e+00;
constexpr double pio2_2 = 6.07710050630396597660e-11;
constexpr double pio2_3 = 2.02226624871116645580e-21;
constexpr double pio2_3t = 8.47842766036889956997e-32; // pi/2 - (the three parts above)
constexpr double two_over_pi = 6.36619772367581382433e-01;

// sin r and cos r for |r| <= pi/4 by their Taylor series to r^19 and r^20 (truncation below
// 1e-19 relative). cos r = 1 - r^2/2 + r^4 q is summed as w + ((1 - w) - r^2/2 + r^4 q) with
// w = 1 - r^2/2, which keeps the rounding of w out of the result.
YUXI_HD inline double sin_kernel(double r) {
  const double z = r * r;
  double q = -1.0 / 121645100408832000.0;
  q = q * z + 1.0 / 355687428096000.0;
  q = q * z - 1.0 / 1307674368000.0;
  q = q * z + 1.0 / 6227020800.0;
  q = q * z - 1.0 / 39916800.0;
  q = q * z + 1.0 / 362880.0;
  q = q * z - 1.0 / 5040.0;
  q = q * z + 1.0 / 120.0;
  q = q * z - 1.0 / 6.0;
  return r + r * (z * q);
}
YUXI_HD inline double cos_kernel(double r) {
  const double z = r * r;
  double q = 1.0 / 2432902008176640000.0;
  q = q * z - 1.0 / 6402373705728000.0;
  q = q * z + 1.0 / 20922789888000.0;
  q = q * z - 1.0 / 87178291200.0;
  q = q * z + 1.0 / 479001600.0;
  q = q * z - 1.0 / 3628800.0;
  q = q * z + 1.0 / 40320.0;
  q = q * z - 1.0 / 720.0;
  q = q * z + 1.0 / 24.0;
  const double half_z = 0.5 * z;
  const double w = 1.0 - half_z;
  return w + (((1.0 - w) - half_z) + (z * z) * q);
}

} // namespace detail

// Whether sin_cos(x) is {detail::sin_kernel(x), detail::cos_kernel(x)} alone: within pi/4, zero
// included (a loop over many angles can run the kernels on all of them, vectorised, and sin_cos
// on the others: the same bits). A body at rest turns by zero at every step.
YUXI_HD constexpr bool takes_kernels_alone(double x) {
  return (x < 0 ? -x : x) <= 0.78;
}

// sin x and cos x together. x = k pi/2 + r with |r| <= pi/4 (Cody & Waite's reduction, pi/2 in
// four parts), then the kernels above by the quadrant k mod 4. Within 1 ulp for |x| <= pi/4,
// where the kernels act alone, and 2.5 ulp for |x| < 1.6e6, where the reduced argument's
// rounding adds to theirs, next to multiples of pi/2 too (tests/unit/test_portable_math.cpp);
// beyond, the reduction loses bits and the error grows with |x| (the rotations that call it
// turn by far less than a radian a step).
struct SinCos {
  double sin = 0, cos = 1;
};
YUXI_HD inline SinCos sin_cos(double x) {
  using namespace detail;
  if (!(x - x == 0))
    return {std::numeric_limits<double>::quiet_NaN(),
            std::numeric_limits<double>::quiet_NaN()}; // NaN or infinite
  // Beyond the accurate range, first x mod 2 pi (fmod is exact): an angle that is no longer
  // accurate, but whose sine and cosine are still a rotation's.
  // Within pi/4 (the turns of a rigid body's step) no reduction: k is 0 and r is x, so the
  // general path below gives these bits too, without its rint and fmod. (At -0 the path turns r
  // into +0, and the kernels give sin(-0) = -0 + (-0)(0 q) = +0 themselves: the same bits.)
  if (takes_kernels_alone(x)) return {sin_kernel(x), cos_kernel(x)};
  if (!(std::abs(x) < 1.6e6)) x = std::fmod(x, 6.283185307179586);
  // k: the nearest integer to x 2/pi, as a double (rint is exact and the same everywhere; a
  // conversion to an integer type would overflow for huge x), and its quadrant k mod 4.
  const double kd = std::rint(x * two_over_pi);
  const double r = (((x - kd * pio2_1) - kd * pio2_2) - kd * pio2_3) - kd * pio2_3t;
  const int quadrant = static_cast<int>(std::fmod(kd, 4.0)) & 3; // (-1 & 3 = 3, and so on)
  const double s = sin_kernel(r), c = cos_kernel(r);
  switch (quadrant) {
  case 0:
    return {s, c};
  case 1:
    return {c, -s};
  case 2:
    return {-s, -c};
  default:
    return {-c, s};
  }
}

} // namespace yuxi::portable
