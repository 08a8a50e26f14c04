#include "crestline/numerics/paired_cg.h"

#include <cmath>
#include <cstring>

namespace crestline {
namespace {

// w with its sign bit flipped when `flip` is 1: branch-free, because the
// signs σ follow the direction fields and are not predictable.
inline double flip_sign(double w, uint32_t flip) {
  uint64_t bits;
  std::memcpy(&bits, &w, sizeof bits);
  bits ^= static_cast<uint64_t>(flip) << 63;
  std::memcpy(&w, &bits, sizeof bits);
  return w;
}

// y = A_k p for both k, interleaved; adds ⟨p_k, y_k⟩ to py[k] in the same pass.
void multiply(const SignedPairMatrix& a, const double* p, double* y, double py[2]) {
  const size_t n = a.rows();
  for (size_t i = 0; i < n; ++i) {
    double y0 = a.diagonal[i] * p[2 * i], y1 = a.diagonal[i] * p[2 * i + 1];
    for (uint32_t e = a.offsets[i]; e < a.offsets[i + 1]; ++e) {
      const uint32_t c = a.columns[e];
      const size_t j = c & SignedPairMatrix::kColumnMask;
      const double w = a.weights[e];
      y0 += flip_sign(w, (c >> 30) & 1) * p[2 * j];
      y1 += flip_sign(w, c >> 31) * p[2 * j + 1];
    }
    y[2 * i] = y0, y[2 * i + 1] = y1;
    py[0] += p[2 * i] * y0, py[1] += p[2 * i + 1] * y1;
  }
}

}  // namespace

SignedPairSolver::SignedPairSolver(SignedPairMatrix matrix) : a_(std::move(matrix)), inverse_diagonal_(a_.rows()) {
  for (size_t i = 0; i < a_.rows(); ++i) inverse_diagonal_[i] = 1.0 / a_.diagonal[i];
}

bool SignedPairSolver::solve(const std::vector<double>& b, std::vector<double>& x, double tolerance, int max_iterations,
                             const std::function<void(int)>& on_iteration) const {
  const SignedPairMatrix& a = a_;
  const std::vector<double>& inverse_diagonal = inverse_diagonal_;
  const size_t n = a.rows();
  std::vector<double> r(2 * n), z(2 * n), p(2 * n), q(2 * n);
  double unused[2] = {0, 0};
  multiply(a, x.data(), q.data(), unused);
  double b2[2] = {0, 0}, rr[2] = {0, 0}, rz[2] = {0, 0};
  for (size_t i = 0; i < n; ++i)
    for (int k = 0; k < 2; ++k) {
      const size_t j = 2 * i + k;
      r[j] = b[j] - q[j];
      z[j] = r[j] * inverse_diagonal[i];
      p[j] = z[j];
      b2[k] += b[j] * b[j], rr[k] += r[j] * r[j], rz[k] += r[j] * z[j];
    }
  bool active[2];
  for (int k = 0; k < 2; ++k) {
    // As Eigen: a zero right-hand side has the solution 0.
    if (b2[k] == 0) {
      for (size_t i = 0; i < n; ++i) x[2 * i + k] = 0;
      active[k] = false;
    } else {
      active[k] = rr[k] > tolerance * tolerance * b2[k];
    }
  }
  for (int it = 0; it < max_iterations && (active[0] || active[1]); ++it) {
    double pq[2] = {0, 0};
    multiply(a, p.data(), q.data(), pq);
    double alpha[2];
    for (int k = 0; k < 2; ++k) alpha[k] = active[k] ? rz[k] / pq[k] : 0.0;
    double rz_new[2] = {0, 0};
    rr[0] = rr[1] = 0;
    for (size_t i = 0; i < n; ++i)
      for (int k = 0; k < 2; ++k) {
        const size_t j = 2 * i + k;
        x[j] += alpha[k] * p[j];
        r[j] -= alpha[k] * q[j];
        z[j] = r[j] * inverse_diagonal[i];
        rr[k] += r[j] * r[j], rz_new[k] += r[j] * z[j];
      }
    double beta[2];
    for (int k = 0; k < 2; ++k) {
      if (active[k] && !(rr[k] > tolerance * tolerance * b2[k])) active[k] = false;
      beta[k] = active[k] ? rz_new[k] / rz[k] : 0.0;
      rz[k] = rz_new[k];
    }
    const double keep[2] = {active[0] ? 1.0 : 0.0, active[1] ? 1.0 : 0.0};
    for (size_t i = 0; i < n; ++i)
      for (int k = 0; k < 2; ++k) p[2 * i + k] = keep[k] * (z[2 * i + k] + beta[k] * p[2 * i + k]);
    if (on_iteration) on_iteration(it + 1);
  }
  for (double v : x)
    if (!std::isfinite(v)) return false;
  return !active[0] && !active[1];
}

}  // namespace crestline
