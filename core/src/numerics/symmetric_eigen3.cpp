#include "crestline/numerics/symmetric_eigen3.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <utility>

namespace crestline {
namespace {

// Eigen's Givens rotation (JacobiRotation::makeGivens, real case, no r):
// G = [c s; −s c] with G^T (p, q) = (r, 0).
inline void make_givens(double p, double q, double& c, double& s) {
  if (q == 0) {
    c = p < 0 ? -1.0 : 1.0;
    s = 0;
  } else if (p == 0) {
    c = 0;
    s = q < 0 ? 1.0 : -1.0;
  } else if (std::abs(p) > std::abs(q)) {
    const double t = q / p;
    double u = std::sqrt(1.0 + t * t);
    if (p < 0) u = -u;
    c = 1.0 / u;
    s = -t * c;
  } else {
    const double t = p / q;
    double u = std::sqrt(1.0 + t * t);
    if (q < 0) u = -u;
    s = -1.0 / u;
    c = -t * s;
  }
}

// Eigen's hypot (positive_real_hypot) of two finite numbers.
inline double hypot_of(double x, double y) {
  x = std::abs(x), y = std::abs(y);
  const double p = std::max(x, y);
  if (p == 0) return 0;
  const double qp = std::min(y, x) / p;
  return p * std::sqrt(1.0 + qp * qp);
}

// The tridiagonal matrix (diagonal d, subdiagonal e) and the accumulated
// rotations q (q[j] is column j). Every index below is a constant once the
// templates are instantiated, so the compiler keeps all of it in registers.
struct Tridiagonal {
  double d[3], e[2];
  double q[3][3];
};

// Zeroes e[i] where it is negligible beside d[i], d[i + 1].
template <int i>
inline void deflate(Tridiagonal& t) {
  if (std::abs(t.e[i]) < std::numeric_limits<double>::min()) {
    t.e[i] = 0;
  } else {
    const double scaled = (1.0 / std::numeric_limits<double>::epsilon()) * t.e[i];
    if (scaled * scaled <= std::abs(t.d[i]) + std::abs(t.d[i + 1])) t.e[i] = 0;
  }
}

// One Givens rotation of the implicit QR step over rows start..end, at row k.
template <int start, int end, int k>
inline void chase(Tridiagonal& t, double& x, double& z) {
  double* diag = t.d;
  double* sub = t.e;
  double c, s;
  make_givens(x, z, c, s);
  const double sdk = s * diag[k] + c * sub[k];
  const double dkp1 = s * sub[k] + c * diag[k + 1];
  diag[k] = c * (c * diag[k] - s * sub[k]) - s * (c * sub[k] - s * diag[k + 1]);
  diag[k + 1] = s * sdk + c * dkp1;
  sub[k] = c * sdk - s * dkp1;
  if (k > start) sub[k - 1] = c * sub[k - 1] - s * z;
  x = sub[k];
  if (k < end - 1) {
    z = -s * sub[k + 1];
    sub[k + 1] = c * sub[k + 1];
  }
  // Q = Q G: applyOnTheRight(k, k + 1, G), i.e. the plane rotation by G's
  // transpose (c, −s) on columns k and k + 1, skipped when it is the identity.
  const double tc = c, ts = -s;
  if (tc == 1 && ts == 0) return;
  for (int i = 0; i < 3; ++i) {
    const double xi = t.q[k][i], yi = t.q[k + 1][i];
    t.q[k][i] = tc * xi + ts * yi;
    t.q[k + 1][i] = -ts * xi + tc * yi;
  }
}

// One implicit symmetric QR step with Wilkinson shift on rows start..end
// (internal::tridiagonal_qr_step).
template <int start, int end>
inline void qr_step(Tridiagonal& t) {
  const double td = (t.d[end - 1] - t.d[end]) * 0.5;
  const double e = t.e[end - 1];
  double mu = t.d[end];
  if (td == 0) {
    mu -= std::abs(e);
  } else if (e != 0) {
    const double e2 = e * e;
    const double h = hypot_of(td, e);
    if (e2 == 0)
      mu -= e / ((td + (td > 0 ? h : -h)) / e);
    else
      mu -= e2 / (td + (td > 0 ? h : -h));
  }
  double x = t.d[start] - mu;
  double z = t.e[start];
  if (z == 0) return;
  chase<start, end, start>(t, x, z);
  if (end - start == 2 && z != 0) chase<start, end, start + 1>(t, x, z);
}

}  // namespace

SymmetricEigen3 symmetric_eigen3(const Eigen::Matrix3d& s) {
  SymmetricEigen3 out;
  const double lower[6] = {s(0, 0), s(1, 0), s(2, 0), s(1, 1), s(2, 1), s(2, 2)};
  double scale = 0;
  bool finite = true;
  for (double a : lower) {
    finite = finite && std::isfinite(a);
    scale = std::max(scale, std::abs(a));
  }
  if (!finite) {
    // Eigen's max and the QR loop's stopping tests order NaNs their own way.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(s);
    out.values = eigen.eigenvalues();
    out.vectors = eigen.eigenvectors();
    return out;
  }
  if (scale == 0) scale = 1;
  const double a00 = s(0, 0) / scale, a10 = s(1, 0) / scale, a20 = s(2, 0) / scale, a11 = s(1, 1) / scale,
               a21 = s(2, 1) / scale, a22 = s(2, 2) / scale;

  // Tridiagonalization (the 3×3 case of internal::tridiagonalization_inplace).
  Tridiagonal t;
  t.d[0] = a00;
  const double v1norm2 = a20 * a20;
  if (v1norm2 <= std::numeric_limits<double>::min()) {
    t.d[1] = a11, t.d[2] = a22;
    t.e[0] = a10, t.e[1] = a21;
    t.q[0][0] = 1, t.q[0][1] = 0, t.q[0][2] = 0;
    t.q[1][0] = 0, t.q[1][1] = 1, t.q[1][2] = 0;
    t.q[2][0] = 0, t.q[2][1] = 0, t.q[2][2] = 1;
  } else {
    const double beta = std::sqrt(a10 * a10 + v1norm2);
    const double inv_beta = 1.0 / beta;
    const double m01 = a10 * inv_beta, m02 = a20 * inv_beta;
    const double h = 2.0 * m01 * a21 + m02 * (a22 - a11);
    t.d[1] = a11 + m02 * h;
    t.d[2] = a22 - m02 * h;
    t.e[0] = beta;
    t.e[1] = a21 - m01 * h;
    t.q[0][0] = 1, t.q[0][1] = 0, t.q[0][2] = 0;
    t.q[1][0] = 0, t.q[1][1] = m01, t.q[1][2] = m02;
    t.q[2][0] = 0, t.q[2][1] = m02, t.q[2][2] = -m01;
  }

  // The QR iteration (internal::computeFromTridiagonal_impl): the unreduced
  // block rows start..end is one of (0, 2), (1, 2), (0, 1).
  constexpr int kMaxIterations = 30 * 3;
  int end = 2, start = 0, iter = 0;
  for (;;) {
    if (end == 2) {
      if (start == 0) deflate<0>(t);
      deflate<1>(t);
    } else {
      deflate<0>(t);
    }
    if (end == 2 && t.e[1] == 0) end = 1;
    if (end == 1 && t.e[0] == 0) end = 0;
    if (end == 0) break;
    if (++iter > kMaxIterations) break;
    start = end == 2 && t.e[0] == 0 ? 1 : 0;
    if (end == 1)
      qr_step<0, 1>(t);
    else if (start == 1)
      qr_step<1, 2>(t);
    else
      qr_step<0, 2>(t);
  }
  // Ascending, by selection (Eigen sorts only what converged).
  auto swap_columns = [&](int i, int k) {
    std::swap(t.d[i], t.d[k]);
    for (int r = 0; r < 3; ++r) std::swap(t.q[i][r], t.q[k][r]);
  };
  if (iter <= kMaxIterations) {
    if (t.d[1] < t.d[0]) {
      if (t.d[2] < t.d[1])
        swap_columns(0, 2);
      else
        swap_columns(0, 1);
    } else if (t.d[2] < t.d[0]) {
      swap_columns(0, 2);
    }
    if (t.d[2] < t.d[1]) swap_columns(1, 2);
  }
  out.values = Eigen::Vector3d(t.d[0] * scale, t.d[1] * scale, t.d[2] * scale);
  for (int j = 0; j < 3; ++j)
    for (int r = 0; r < 3; ++r) out.vectors(r, j) = t.q[j][r];
  return out;
}

}  // namespace crestline
