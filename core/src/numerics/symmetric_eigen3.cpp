#include "crestline/numerics/symmetric_eigen3.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#if defined(__wasm_simd128__)
#include <wasm_simd128.h>
#elif defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace crestline {
namespace {

// Two matrices side by side, one in each lane (GCC/Clang vector extensions:
// SSE2 natively, SIMD128 in WASM, scalar code without either). Every lane
// does its own matrix's arithmetic, operation for operation, and branches
// become selects: each lane's bits are those of its matrix alone.
typedef double Lanes __attribute__((vector_size(16)));
typedef int64_t Mask __attribute__((vector_size(16)));  // all ones where true

inline Lanes select(Mask m, Lanes yes, Lanes no) { return (Lanes)(((Mask)yes & m) | ((Mask)no & ~m)); }
inline Lanes splat(double x) { return Lanes{x, x}; }
inline Lanes select(Mask m, double yes, Lanes no) { return select(m, splat(yes), no); }
// Where m is true, 0; else x.
inline Lanes zero_where(Mask m, Lanes x) { return (Lanes)((Mask)x & ~m); }
inline bool any(Mask m) {
#if defined(__wasm_simd128__)
  return wasm_v128_any_true((v128_t)m);
#elif defined(__SSE2__)
  return _mm_movemask_pd((__m128d)m) != 0;
#else
  return m[0] || m[1];
#endif
}
inline bool all(Mask m) {
#if defined(__wasm_simd128__)
  return wasm_i64x2_all_true((v128_t)m);
#elif defined(__SSE2__)
  return _mm_movemask_pd((__m128d)m) == 3;
#else
  return m[0] && m[1];
#endif
}
constexpr int64_t kSignBit = std::numeric_limits<int64_t>::min();
inline Lanes abs(Lanes x) { return (Lanes)((Mask)x & ~kSignBit); }
inline Lanes sqrt(Lanes x) {
#if defined(__wasm_simd128__)
  return (Lanes)wasm_f64x2_sqrt((v128_t)x);
#elif defined(__SSE2__)
  return _mm_sqrt_pd(x);
#else
  return Lanes{std::sqrt(x[0]), std::sqrt(x[1])};
#endif
}

// Eigen's Givens rotation (JacobiRotation::makeGivens, real case, no r):
// G = [c s; −s c] with G^T (p, q) = (r, 0).
inline void make_givens(Lanes p, Lanes q, Lanes& c, Lanes& s) {
  // |p| > |q|: t = q / p, u = ±√(1 + t²) with p's sign, c = 1 / u and
  // s = −t c. Otherwise t = p / q, u with q's sign, s = −1 / u and c = −t s.
  // Negating a product or a quotient negates its result exactly, so with
  // r = t / u as the product t (1 / u): (c, s) = (1 / u, −r) or (r, −1 / u).
  const Mask p_larger = abs(p) > abs(q);
  const Lanes larger = select(p_larger, p, q);
  const Lanes t = select(p_larger, q, p) / larger;
  // u takes the sign of the larger (nonzero unless both are, handled below).
  const Lanes u = (Lanes)((Mask)sqrt(1.0 + t * t) ^ ((Mask)larger & kSignBit));
  const Lanes inverse = 1.0 / u, r = t * inverse;
  c = select(p_larger, inverse, r);
  s = -select(p_larger, r, inverse);
  const Mask p_zero = p == 0, q_zero = q == 0;
  if (!any(p_zero | q_zero)) return;
  c = zero_where(p_zero, c);
  s = select(p_zero, select(q < 0, 1.0, splat(-1.0)), s);
  c = select(q_zero, select(p < 0, -1.0, splat(1.0)), c);
  s = zero_where(q_zero, s);
}

// Eigen's hypot (positive_real_hypot) of two finite numbers, not both 0
// (Eigen returns 0 then; qr_step has no use for it).
inline Lanes hypot_of(Lanes x, Lanes y) {
  x = abs(x), y = abs(y);
  const Mask x_less = x < y;
  const Lanes p = select(x_less, y, x);  // std::max(x, y)
  const Lanes qp = select(x_less, x, y) / p;
  return p * sqrt(1.0 + qp * qp);
}

// The tridiagonal matrices (diagonal d, subdiagonal e) and the accumulated
// rotations q (q[j] is column j). Every index below is a constant once the
// templates are instantiated, so the compiler keeps all of it in registers.
struct Tridiagonal {
  Lanes d[3], e[2];
  Lanes q[3][3];
};

// Zeroes e[i] where it is negligible beside d[i], d[i + 1]. Again on a
// matrix whose e[i] is 0, or that has not changed, it changes nothing.
template <int i>
inline void deflate(Tridiagonal& t) {
  const Lanes scaled = (1.0 / std::numeric_limits<double>::epsilon()) * t.e[i];
  const Mask negligible =
      (abs(t.e[i]) < std::numeric_limits<double>::min()) | (scaled * scaled <= abs(t.d[i]) + abs(t.d[i + 1]));
  t.e[i] = zero_where(negligible, t.e[i]);
}

// One Givens rotation of the implicit QR step over rows start..end, at row
// k, in the lanes of `step` (all of them unless `masked`).
template <int start, int end, int k, bool masked>
inline void chase(Tridiagonal& t, Lanes& x, Lanes& z, Mask step) {
  auto update = [&](Lanes& target, Lanes value) { target = masked ? select(step, value, target) : value; };
  Lanes* diag = t.d;
  Lanes* sub = t.e;
  Lanes c, s;
  make_givens(x, z, c, s);
  const Lanes sdk = s * diag[k] + c * sub[k];
  const Lanes dkp1 = s * sub[k] + c * diag[k + 1];
  update(diag[k], c * (c * diag[k] - s * sub[k]) - s * (c * sub[k] - s * diag[k + 1]));
  update(diag[k + 1], s * sdk + c * dkp1);
  x = c * sdk - s * dkp1;
  update(sub[k], x);
  if constexpr (k > start) update(sub[k - 1], c * sub[k - 1] - s * z);
  if constexpr (k < end - 1) {
    z = -s * sub[k + 1];
    update(sub[k + 1], c * sub[k + 1]);
  }
  // Q = Q G: applyOnTheRight(k, k + 1, G), i.e. the plane rotation by G's
  // transpose (c, −s) on columns k and k + 1, skipped when it is the identity.
  const Lanes tc = c, ts = -s;
  const Mask rotate = step & ~((tc == 1) & (ts == 0));
  const bool every_lane = all(rotate);
  for (int i = 0; i < 3; ++i) {
    const Lanes xi = t.q[k][i], yi = t.q[k + 1][i];
    const Lanes new_x = tc * xi + ts * yi, new_y = -ts * xi + tc * yi;
    t.q[k][i] = every_lane ? new_x : select(rotate, new_x, xi);
    t.q[k + 1][i] = every_lane ? new_y : select(rotate, new_y, yi);
  }
}

template <int start, int end, int k>
inline void chase(Tridiagonal& t, Lanes& x, Lanes& z, Mask step) {
  if (all(step))
    chase<start, end, k, false>(t, x, z, step);
  else
    chase<start, end, k, true>(t, x, z, step);
}

// One implicit symmetric QR step with Wilkinson shift on rows start..end
// (internal::tridiagonal_qr_step), in the lanes of `step`.
template <int start, int end>
inline void qr_step(Tridiagonal& t, Mask step) {
  const Lanes td = (t.d[end - 1] - t.d[end]) * 0.5;
  const Lanes e = t.e[end - 1];
  const Lanes e2 = e * e;
  const Lanes h = hypot_of(td, e);  // used only where td ≠ 0 and e ≠ 0
  // td + (td > 0 ? h : −h), h ≥ 0: h's sign bit set unless td > 0.
  const Lanes denominator = td + (Lanes)((Mask)h | (kSignBit & ~(td > 0)));
  Lanes shifted = t.d[end] - e2 / denominator;
  // e² underflowed to 0 (|e| below about 1e-162): rare enough for a branch,
  // and the full test only where e² is 0 at all.
  const Mask e2_zero = e2 == 0;
  if (any(e2_zero)) {
    const Mask underflow = e2_zero & (e != 0) & (td != 0) & step;
    if (any(underflow)) shifted = select(underflow, t.d[end] - e / (denominator / e), shifted);
  }
  const Lanes mu = select(td == 0, t.d[end] - abs(e), select(e != 0, shifted, t.d[end]));
  Lanes x = t.d[start] - mu;
  Lanes z = t.e[start];
  step &= z != 0;
  if (!any(step)) return;
  chase<start, end, start>(t, x, z, step);
  if constexpr (end - start == 2) {
    step &= z != 0;
    if (any(step)) chase<start, end, start + 1>(t, x, z, step);
  }
}

bool finite_lower(const SymmetricLower3& s) {
  bool finite = true;
  for (double a : s) finite = finite && std::isfinite(a);
  return finite;
}

double max_abs(const SymmetricLower3& s) {
  double scale = 0;
  for (double a : s) scale = std::max(scale, std::abs(a));
  return scale;
}

// Lane `lane`'s eigenvalues (times its scale) and eigenvectors, sorted
// ascending unless the QR iteration gave up. A template, so that every lane
// index is a constant and the lanes stay in registers.
template <int lane>
void write_lane(const Tridiagonal& t, Lanes scale, Mask gave_up, SymmetricEigen3& out) {
  double d[3], q[3][3];
  for (int j = 0; j < 3; ++j) {
    d[j] = t.d[j][lane];
    for (int r = 0; r < 3; ++r) q[j][r] = t.q[j][r][lane];
  }
  // Ascending, by selection (Eigen sorts only what converged).
  auto swap_columns = [&](int i, int k) {
    std::swap(d[i], d[k]);
    for (int r = 0; r < 3; ++r) std::swap(q[i][r], q[k][r]);
  };
  if (!gave_up[lane]) {
    if (d[1] < d[0]) {
      if (d[2] < d[1])
        swap_columns(0, 2);
      else
        swap_columns(0, 1);
    } else if (d[2] < d[0]) {
      swap_columns(0, 2);
    }
    if (d[2] < d[1]) swap_columns(1, 2);
  }
  const double s = scale[lane];
  out.values = Eigen::Vector3d(d[0] * s, d[1] * s, d[2] * s);
  for (int j = 0; j < 3; ++j)
    for (int r = 0; r < 3; ++r) out.vectors(r, j) = q[j][r];
}

// Two matrices with finite coefficients.
void solve_pair(const SymmetricLower3& first, const SymmetricLower3& second, SymmetricEigen3& out_first,
                SymmetricEigen3& out_second) {
  Lanes scale = {max_abs(first), max_abs(second)};
  scale = select(scale == 0, 1.0, scale);
  Lanes a[6];
  for (int i = 0; i < 6; ++i) a[i] = Lanes{first[i], second[i]} / scale;
  const Lanes a00 = a[0], a10 = a[1], a20 = a[2], a11 = a[3], a21 = a[4], a22 = a[5];

  // Tridiagonalization (the 3×3 case of internal::tridiagonalization_inplace).
  Tridiagonal t;
  const Lanes zero = {}, one = splat(1.0);
  const Lanes v1norm2 = a20 * a20;
  const Mask reduce = ~(v1norm2 <= std::numeric_limits<double>::min());
  const Lanes beta = sqrt(a10 * a10 + v1norm2);
  const Lanes inv_beta = 1.0 / beta;
  const Lanes m01 = a10 * inv_beta, m02 = a20 * inv_beta;
  const Lanes h = 2.0 * m01 * a21 + m02 * (a22 - a11);
  t.d[0] = a00;
  t.d[1] = select(reduce, a11 + m02 * h, a11);
  t.d[2] = select(reduce, a22 - m02 * h, a22);
  t.e[0] = select(reduce, beta, a10);
  t.e[1] = select(reduce, a21 - m01 * h, a21);
  t.q[0][0] = one, t.q[0][1] = zero, t.q[0][2] = zero;
  t.q[1][0] = zero, t.q[1][1] = select(reduce, m01, one), t.q[1][2] = zero_where(~reduce, m02);
  t.q[2][0] = zero, t.q[2][1] = zero_where(~reduce, m02), t.q[2][2] = select(reduce, -m01, one);

  // The QR iteration (internal::computeFromTridiagonal_impl). A matrix's
  // unreduced block, rows start..end, is (0, 2) while e[0] and e[1] are not
  // zero, (1, 2) once only e[0] is, (0, 1) once only e[1] is; it is done when
  // both are. Eigen deflates e[0] and e[1] before each step (e[0] only on
  // (0, 1), which has e[1] = 0 already, and e[1] only on (1, 2)): on every
  // lane before every step here, which changes nothing more. A lane on a
  // 2×2 block waits while others take (0, 2) steps, so that most steps serve
  // all lanes (Eigen: usually 2 to 5 steps on (0, 2), then one on (0, 1)).
  // A lane's steps are at most the steps taken, so `over` is tested only
  // once those pass the limit (a 64-bit lane comparison is several SSE2
  // instructions).
  constexpr int kMaxIterations = 30 * 3;
  Mask iterations = {}, over = {};
  int steps = 0;
  for (;;) {
    deflate<0>(t);
    deflate<1>(t);
    const Mask e0 = t.e[0] != 0, e1 = t.e[1] != 0;
    auto count = [&](Mask step) {
      iterations -= step;
      if (++steps > kMaxIterations) over |= step & (iterations > kMaxIterations);
      return step & ~over;
    };
    if (any(e0 & e1 & ~over)) {
      qr_step<0, 2>(t, count(e0 & e1 & ~over));
      continue;
    }
    const Mask lower_block = e0 & ~e1 & ~over, upper_block = ~e0 & e1 & ~over;
    if (!any(lower_block | upper_block)) break;
    if (any(lower_block)) qr_step<0, 1>(t, count(lower_block));
    if (any(upper_block)) qr_step<1, 2>(t, count(upper_block));
  }

  write_lane<0>(t, scale, over, out_first);
  write_lane<1>(t, scale, over, out_second);
}

}  // namespace

void symmetric_eigen3(const SymmetricLower3* matrices, size_t count, SymmetricEigen3* out) {
  // The finite matrices in pairs, each pair in order; an odd one out is
  // paired with zero (solved without a QR step).
  size_t waiting = count;  // a finite matrix without its pair yet, or count
  for (size_t i = 0; i < count; ++i) {
    const SymmetricLower3& s = matrices[i];
    if (!finite_lower(s)) {
      // Eigen's max and the QR loop's stopping tests order NaNs their own way.
      Eigen::Matrix3d full;
      full << s[0], s[1], s[2], s[1], s[3], s[4], s[2], s[4], s[5];
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(full);
      out[i].values = eigen.eigenvalues();
      out[i].vectors = eigen.eigenvectors();
      continue;
    }
    if (waiting == count) {
      waiting = i;
      continue;
    }
    solve_pair(matrices[waiting], s, out[waiting], out[i]);
    waiting = count;
  }
  if (waiting != count) {
    SymmetricEigen3 zero;
    solve_pair(matrices[waiting], SymmetricLower3{}, out[waiting], zero);
  }
}

SymmetricEigen3 symmetric_eigen3(const Eigen::Matrix3d& s) {
  const SymmetricLower3 lower = {s(0, 0), s(1, 0), s(2, 0), s(1, 1), s(2, 1), s(2, 2)};
  SymmetricEigen3 out;
  symmetric_eigen3(&lower, 1, &out);
  return out;
}

}  // namespace crestline
