#pragma once
// Elementary functions from +, −, ×, ÷ and sqrt only, which IEEE 754 rounds
// the same everywhere: glibc's exp and atan2 (natively) and Emscripten's
// (in WASM) differ in the last bit for some arguments, and the CLI and the
// page must write the same bytes. Each is within a few units in the last
// place of the true value (their tests bound it); none is bit for bit the C
// library's.
#include <cstdint>
#include <cstring>
#include <limits>

namespace crestline {

namespace detail {
// 2^(j/32), j = 0 … 31, each the nearest double.
inline constexpr double kExp2Fractions[32] = {
    0x1.0000000000000p+0, 0x1.059b0d3158574p+0, 0x1.0b5586cf9890fp+0, 0x1.11301d0125b51p+0, 0x1.172b83c7d517bp+0,
    0x1.1d4873168b9aap+0, 0x1.2387a6e756238p+0, 0x1.29e9df51fdee1p+0, 0x1.306fe0a31b715p+0, 0x1.371a7373aa9cbp+0,
    0x1.3dea64c123422p+0, 0x1.44e086061892dp+0, 0x1.4bfdad5362a27p+0, 0x1.5342b569d4f82p+0, 0x1.5ab07dd485429p+0,
    0x1.6247eb03a5585p+0, 0x1.6a09e667f3bcdp+0, 0x1.71f75e8ec5f74p+0, 0x1.7a11473eb0187p+0, 0x1.82589994cce13p+0,
    0x1.8ace5422aa0dbp+0, 0x1.93737b0cdc5e5p+0, 0x1.9c49182a3f090p+0, 0x1.a5503b23e255dp+0, 0x1.ae89f995ad3adp+0,
    0x1.b7f76f2fb5e47p+0, 0x1.c199bdd85529cp+0, 0x1.cb720dcef9069p+0, 0x1.d5818dcfba487p+0, 0x1.dfc97337b9b5fp+0,
    0x1.ea4afa2a490dap+0, 0x1.f50765b6e4540p+0};
}  // namespace detail

/// e^x for |x| ≤ 700, relative error below 4·10⁻¹⁶; 0 below −700 (where
/// e^x < 10⁻³⁰⁴), +∞ above 700, NaN for NaN. Inline: it runs in the crease
/// filter's innermost loop (200 M calls on a noisy 871k-triangle scan).
/// x = (32 m + j) ln2/32 + r with |r| ≤ ln2/64, e^x = 2^m 2^(j/32) e^r, e^r
/// by its Taylor series to r⁶ (the rest below 4·10⁻¹⁸).
inline double portable_exp(double x) {
  if (!(x >= -700)) return x != x ? x : 0.0;
  if (x > 700) return std::numeric_limits<double>::infinity();
  constexpr double kInverseStep = 0x1.71547652b82fep+5;  // 32 / ln 2
  // ln 2 / 32 as a 36-bit head (k·head is exact for |k| < 2^17) and its rest.
  constexpr double kStepHead = 0x1.62e42fefa0000p-6, kStepTail = 0x1.cf79abc9e3b3ap-45;
  // Adding 1.5·2^52 rounds to the nearest integer (ties to even).
  constexpr double kRound = 0x1.8p52;
  const double k = (x * kInverseStep + kRound) - kRound;
  const double r = (x - k * kStepHead) - k * kStepTail;
  const double series =
      1 + r * (1 + r * (1.0 / 2 + r * (1.0 / 6 + r * (1.0 / 24 + r * (1.0 / 120 + r * (1.0 / 720))))));
  const auto steps = static_cast<int64_t>(k);
  const int64_t j = steps & 31, m = (steps - j) / 32;
  const uint64_t power_bits = static_cast<uint64_t>(m + 1023) << 52;
  double power;
  std::memcpy(&power, &power_bits, sizeof power);
  return detail::kExp2Fractions[j] * series * power;
}

/// atan2(y, x) for y ≥ 0: an angle in [0, π].
double portable_angle(double y, double x);

/// acos(c) for c in [−1, 1] (clamped), from 1 − c, which a caller may hold
/// more precisely than c near 1: acos(1 − one_minus_c).
double portable_acos_of_complement(double one_minus_c);

/// cos(x), within 4·10⁻¹⁶ absolutely for |x| ≤ π (beyond, of x reduced by
/// the double nearest 2π); NaN for infinite x.
double portable_cos(double x);

}  // namespace crestline
