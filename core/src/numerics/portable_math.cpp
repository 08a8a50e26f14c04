#include "crestline/numerics/portable_math.h"

#include <cmath>

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

}  // namespace crestline
