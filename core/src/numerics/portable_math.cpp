#include "crestline/numerics/portable_math.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "crestline/numerics/constants.h"

namespace crestline {

// atan(t) = π/6 + atan((√3 t − 1)/(t + √3)) brings t ≤ 1
// below tan(π/12), where 17 terms of the series leave less than 1e-19.
double portable_angle(double y, double x) {
  constexpr double kSqrt3 = 1.7320508075688772;
  if (!(y > 0)) return x < 0 ? kPi : 0.0;
  if (x == 0) return kPi / 2;
  double t = y / std::abs(x);
  const bool inverted = t > 1;
  if (inverted) t = 1 / t;
  const bool shifted = t > 0.2679491924311227;  // tan(π/12)
  if (shifted) t = (kSqrt3 * t - 1) / (t + kSqrt3);
  const double t2 = t * t;
  double series = 0;
  for (int k = 16; k >= 0; --k) series = series * t2 + (k % 2 ? -1.0 : 1.0) / (2 * k + 1);
  double a = t * series + (shifted ? kPi / 6 : 0.0);
  if (inverted) a = kPi / 2 - a;
  return x < 0 ? kPi - a : a;
}

// sin² = (1 − c)(1 + c) = m (2 − m) with m = 1 − c: no cancellation near 1.
double portable_acos_of_complement(double one_minus_c) {
  const double m = std::clamp(one_minus_c, 0.0, 2.0);
  return portable_angle(std::sqrt(m * (2 - m)), 1 - m);
}

// fmod (exact) by 2π and cos(x) = cos(2π − x) bring x into [0, π],
// cos(x) = −cos(π − x) into [0, π/2], where 12 terms of the series leave
// less than 10⁻¹⁹.
double portable_cos(double x) {
  if (!std::isfinite(x)) return std::numeric_limits<double>::quiet_NaN();
  x = std::fmod(std::abs(x), 2 * kPi);
  if (x > kPi) x = 2 * kPi - x;
  const bool reflected = x > kPi / 2;
  if (reflected) x = kPi - x;
  const double x2 = x * x;
  double series = 0, factor = 1;
  double terms[12];
  for (int k = 0; k < 12; ++k) terms[k] = (k % 2 ? -1.0 : 1.0) / factor, factor *= (2 * k + 1) * (2 * k + 2);
  for (int k = 11; k >= 0; --k) series = series * x2 + terms[k];
  return reflected ? -series : series;
}

}  // namespace crestline
