// portable_exp and portable_angle (numerics/portable_math.h): within a few
// units in the last place of the true values, taken from long double
// (x87's 64-bit significand natively) so that the reference is not the
// C library's double result the functions replace.
#include "crestline/numerics/portable_math.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>

#include "crestline/numerics/constants.h"

using crestline::portable_angle;
using crestline::portable_exp;

namespace {

// |a − b| / |b| with b the long double reference.
double relative_error(double a, long double b) { return static_cast<double>(std::fabs((a - b) / b)); }

}  // namespace

TEST_CASE("portable_exp is e^x to 4e-16 over its range, exact where it must be", "[numerics]") {
  double worst = 0;
  auto check = [&](double x) {
    const double e = relative_error(portable_exp(x), std::exp(static_cast<long double>(x)));
    worst = std::max(worst, e);
  };
  // Every 1/64 from −700 to 700 (multiples of the reduction's step and the
  // points between them), then random arguments in the crease filter's range
  // (−2/(1 − cos 20°) ≈ −33 to 0) and over the whole range.
  for (int i = -700 * 64; i <= 700 * 64; ++i) check(i / 64.0);
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> filter(-33.2, 0.0), whole(-700.0, 700.0);
  for (int i = 0; i < 200000; ++i) check(filter(random)), check(whole(random));
  CHECK(worst < 4e-16);

  CHECK(portable_exp(0.0) == 1.0);
  CHECK(portable_exp(-0.0) == 1.0);
  // e^(k ln 2) rounds to 2^k: the reduction leaves r within ulps of 0.
  for (int k = -20; k <= 20; ++k)
    CHECK(portable_exp(k * 0.69314718055994530942) == Approx(std::ldexp(1.0, k)).epsilon(1e-15));
  CHECK(portable_exp(-700.5) == 0.0);
  CHECK(portable_exp(-std::numeric_limits<double>::infinity()) == 0.0);
  CHECK(portable_exp(700.5) == std::numeric_limits<double>::infinity());
  CHECK(std::isnan(portable_exp(std::numeric_limits<double>::quiet_NaN())));
}

TEST_CASE("portable_angle is atan2(y, x) for y >= 0 to 1e-15", "[numerics]") {
  double worst = 0;
  std::mt19937_64 random(6);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int i = 0; i < 200000; ++i) {
    const double y = std::abs(unit(random)), x = unit(random);
    if (y == 0) continue;
    worst = std::max(worst, relative_error(portable_angle(y, x), std::atan2(static_cast<long double>(y), x)));
  }
  CHECK(worst < 1e-15);  // 7.3e-16 (3.3 units in the last place) on these
  CHECK(portable_angle(0.0, 1.0) == 0.0);
  CHECK(portable_angle(0.0, -1.0) == crestline::kPi);
  CHECK(portable_angle(1.0, 0.0) == crestline::kPi / 2);
  CHECK(portable_angle(1.0, 1.0) == Approx(crestline::kPi / 4).epsilon(1e-15));
}

TEST_CASE("portable_cos is cos(x) to 4e-16 absolutely; portable_acos_of_complement is acos(1 - m)", "[numerics]") {
  double worst = 0;
  for (int i = -100000; i <= 100000; ++i) {
    const double x = i * (crestline::kPi / 100000);
    worst = std::max(
        worst, static_cast<double>(std::fabs(crestline::portable_cos(x) - std::cos(static_cast<long double>(x)))));
  }
  CHECK(worst < 4e-16);  // 3.1e-16 by π − x (the double π is 1.2e-16 off)
  CHECK(crestline::portable_cos(0.0) == 1.0);
  CHECK(crestline::portable_cos(crestline::kPi) == -1.0);
  // 180° in radians rounds past π: still cos = −1, not NaN; beyond, periodic.
  CHECK(crestline::portable_cos(180 * (crestline::kPi / 180)) == Approx(-1.0).epsilon(1e-15));
  CHECK(crestline::portable_cos(2 * crestline::kPi + 1) == Approx(std::cos(1.0)).epsilon(1e-14));
  CHECK(std::isnan(crestline::portable_cos(std::numeric_limits<double>::infinity())));

  // Near 1 − m = 1 the complement keeps the small angles (acos of the
  // rounded 1 − m would lose them): m = 1e-12 is an angle of √2·1e-6.
  worst = 0;
  for (int i = 0; i <= 200000; ++i) {
    const double m = i / 100000.0;  // 1 − cos over [0, 2]
    // acos(1 − m) = 2 asin(√(m/2)): no rounding of 1 − m in the reference.
    const long double truth = 2 * std::asin(std::sqrt(static_cast<long double>(m) / 2));
    if (truth > 0) worst = std::max(worst, relative_error(crestline::portable_acos_of_complement(m), truth));
  }
  CHECK(worst < 1e-15);
  CHECK(crestline::portable_acos_of_complement(1e-12) == Approx(std::sqrt(2e-12)).epsilon(1e-12));
  CHECK(crestline::portable_acos_of_complement(0.0) == 0.0);
  CHECK(crestline::portable_acos_of_complement(2.0) == crestline::kPi);
  CHECK(crestline::portable_acos_of_complement(-1.0) == 0.0);  // clamped
  CHECK(crestline::portable_acos_of_complement(3.0) == crestline::kPi);
}
